// The direct light the multiple-scattering cache regresses its once-scattered fluence on
// (src/volume/fluence_cache.h): the lights' light volumes (l: the light arriving unscattered),
// each weighted by its light's mean radiance channel at the box's centre. The ray caster forms
// the same sum from the light it carries to each sample (ray_cast.glsl, shade), meshes' shadows
// included (MESH_SHADOWS). The includer declares modelToWorld, boxMin and boxMax.
//   DIRECT_LIGHTS: the number of light volumes, a compile-time constant so that the loop below
//   indexes the sampler array with constants (a dynamic index cost llvmpipe 1.6 s per light
//   change on the bonsai's density pass)
#if DIRECT_LIGHTS > 0
uniform sampler3D lightVolumes[DIRECT_LIGHTS];
uniform float directLightWeight[DIRECT_LIGHTS];
#endif

#include "volume/mesh_visibility.glsl"

// At the centre of voxel v of a volume `dims` voxels wide.
float directLightAtVoxel(ivec3 v, ivec3 dims) {
    vec3 tc = (vec3(v) + 0.5) / vec3(dims);
    vec3 world = (modelToWorld * vec4(mix(boxMin, boxMax, tc), 1.0)).xyz;
    float e = 0.0;
    for (int i = 0; i < DIRECT_LIGHTS; ++i)
        e += directLightWeight[i] * texture(lightVolumes[i], tc).a * meshVisibility(i, world);
    return e;
}
