// The field between voxel centres (sss::VolumeReconstruction): the texture unit's trilinear
// interpolation, or the cubic B-spline of the voxels. The B-spline's four weights per axis are
// folded into two trilinear fetches whose positions carry the weights' ratios (Sigg and Hadwiger
// 2005), so a sample costs eight fetches. docs/reconstruction.md.
#ifndef CUBIC_RECONSTRUCTION
#define CUBIC_RECONSTRUCTION 0
#endif

#if CUBIC_RECONSTRUCTION
vec4 reconstruct(sampler3D field, vec3 tc) {
    vec3 n = vec3(textureSize(field, 0));
    vec3 x = tc * n - 0.5;
    vec3 i = floor(x);
    vec3 f = x - i;
    vec3 f2 = f * f;
    vec3 f3 = f2 * f;
    vec3 w0 = (1.0 - 3.0 * f + 3.0 * f2 - f3) * (1.0 / 6.0);
    vec3 w1 = (4.0 - 6.0 * f2 + 3.0 * f3) * (1.0 / 6.0);
    vec3 w3 = f3 * (1.0 / 6.0);
    vec3 g1 = 1.0 - w0 - w1;  // w2 + w3, both pairs' weights >= 1/6
    // Voxel k's centre is at (k + 0.5) / n: the pair (i - 1, i) and the pair (i + 1, i + 2).
    vec3 p0 = (i - 0.5 + w1 / (1.0 - g1)) / n;
    vec3 p1 = (i + 1.5 + w3 / g1) / n;
    vec4 z0 = mix(mix(texture(field, vec3(p0.x, p0.y, p0.z)), texture(field, vec3(p1.x, p0.y, p0.z)), g1.x),
                  mix(texture(field, vec3(p0.x, p1.y, p0.z)), texture(field, vec3(p1.x, p1.y, p0.z)), g1.x), g1.y);
    vec4 z1 = mix(mix(texture(field, vec3(p0.x, p0.y, p1.z)), texture(field, vec3(p1.x, p0.y, p1.z)), g1.x),
                  mix(texture(field, vec3(p0.x, p1.y, p1.z)), texture(field, vec3(p1.x, p1.y, p1.z)), g1.x), g1.y);
    return mix(z0, z1, g1.z);
}
#else
vec4 reconstruct(sampler3D field, vec3 tc) { return texture(field, tc); }
#endif
