// The multiple-scattering cache's light towards one viewer (FluenceCache::evaluateView): per cell
// of the level the ray caster reads, what the cell scatters towards the eye, as a line in the
// direct light E that the eye knows at each sample. The ray caster then reads three textures per
// sample instead of the cache's five, and none of the lobe's arithmetic: it is done here once per
// cell and camera move, not once per sample and frame.
//
// The radiance is taken as the HG lobe with the same first moment as the cell's light,
// phi p_HG(k, w . F / |F|), k = |F| / phi; the HG phase function convolves it to
// phi p_HG(g k, v . F / |F|) towards the viewer v (the Legendre coefficients of HG lobes
// multiply: g^l k^l). The lobe's second band is then replaced by the one the photons measured
// (docs/multiple-scattering.md).
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

uniform sampler3D cacheFluence;       // w phi (rgb), w: every texture is premultiplied by w
uniform sampler3D cacheFlux;          // w F of the mean channel (xyz), w M_yz
uniform sampler3D cacheFluxLengths;   // w |F| per channel (rgb), w times the largest E
uniform sampler3D cacheSecondMoment;  // w M_xx, w M_yy, w M_xy, w M_xz (traceless)
uniform sampler3D cacheDirectSlope;   // w B (rgb), w mean E
uniform float cacheLevel;             // FluenceCache::readLevel
uniform vec4 viewer;                  // model space: the eye (w 1) or the direction towards it (w 0)
uniform vec3 boxMin;
uniform vec3 boxMax;
uniform float phaseG;
// Premultiplied by w, as the cache: the light scattered towards the viewer at the cell's mean
// direct light (rgb) and w; its slope against the direct light (rgb) and that mean; the largest
// direct light it follows.
layout(rgba32f, binding = 0) uniform writeonly image3D towardsViewer;
layout(rgba32f, binding = 1) uniform writeonly image3D towardsViewerSlope;
layout(r32f, binding = 2) uniform writeonly image3D towardsViewerCap;

// Within a mean free path of a lit surface the once-scattered fluence levels off while the
// direct light keeps rising (docs/multiple-scattering.md).
const float kDirectBeyondLargest = 2.0;
const float kFourPi = 12.5663706;

// Per channel, the share of the fluence that travels towards v, per steradian.
vec3 lobeTowards(vec3 v, vec4 weighted, vec4 fluxAndYz, vec3 lengths, vec4 m) {
    vec3 flux = fluxAndYz.xyz;
    float fluxLength = length(flux);
    // Each channel's flux along the mean channel's: its share of the channels' flux lengths
    // times the mean vector's length. Noise (few photons, coarse levels' averages) shortens the
    // mean vector but lengthens each cell's own, which alone gave near-delta lobes.
    float meanLength = (lengths.r + lengths.g + lengths.b) / 3.0;
    vec3 k = meanLength > 0.0 ? min(lengths * (fluxLength / meanLength) / max(weighted.rgb, vec3(1e-30)), vec3(0.99))
                              : vec3(0.0);
    float cosTheta = fluxLength > 0.0 ? dot(flux, v) / fluxLength : 0.0;
    vec3 gk = phaseG * k;
    vec3 d = 1.0 + gk * gk - 2.0 * gk * cosTheta;
    vec3 lobe = (1.0 - gk * gk) / (kFourPi * d * sqrt(d));
    // Band 2: (5 / 4 pi) g^2 times the measured 3/2 v.M.v / phi in place of the lobe's k^2 P2(cos).
    float vMv = m.x * v.x * v.x + m.y * v.y * v.y - (m.x + m.y) * v.z * v.z +
                2.0 * (m.z * v.x * v.y + m.w * v.x * v.z + fluxAndYz.w * v.y * v.z);
    float meanPhi = (weighted.r + weighted.g + weighted.b) / 3.0;
    float measured = meanPhi > 0.0 ? 1.5 * vMv / meanPhi : 0.0;
    float p2 = 1.5 * cosTheta * cosTheta - 0.5;
    lobe += (5.0 / kFourPi) * phaseG * phaseG * (measured - k * k * p2);
    return max(lobe, vec3(0.0));
}

// A cache texture at cell c of the read level. At a whole level (WHOLE_LEVEL, FluenceCache's
// program variant) the cells are the level's texels: the texel itself, unfiltered, which took
// llvmpipe's pass over 128^3 cells from 200 to 135 ms; between two levels, filtered.
#if WHOLE_LEVEL
vec4 cacheAt(sampler3D t, ivec3 c, vec3 tc) { return texelFetch(t, c, int(cacheLevel)); }
#else
vec4 cacheAt(sampler3D t, ivec3 c, vec3 tc) { return textureLod(t, tc, cacheLevel); }
#endif

void main() {
    ivec3 c = ivec3(gl_GlobalInvocationID);
    ivec3 size = imageSize(towardsViewer);
    if (any(greaterThanEqual(c, size))) return;
    vec3 tc = (vec3(c) + 0.5) / vec3(size);
    vec4 weighted = cacheAt(cacheFluence, c, tc);
    if (!(weighted.a > 0.0)) {
        imageStore(towardsViewer, c, vec4(0.0));
        imageStore(towardsViewerSlope, c, vec4(0.0));
        imageStore(towardsViewerCap, c, vec4(0.0));
        return;
    }
    vec3 towards = viewer.w != 0.0 ? viewer.xyz - mix(boxMin, boxMax, tc) : viewer.xyz;
    vec3 v = length(towards) > 0.0 ? normalize(towards) : vec3(0.0, 0.0, 1.0);
    vec4 lengthsAndLargest = cacheAt(cacheFluxLengths, c, tc);
    vec3 lobe = lobeTowards(v, weighted, cacheAt(cacheFlux, c, tc), lengthsAndLargest.rgb,
                            cacheAt(cacheSecondMoment, c, tc));
    // The cell's slope of the once-scattered light against the direct light (ray_cast.glsl
    // applies it per sample), the direct light taken at most kDirectBeyondLargest times the
    // largest a voxel centre of the cell has.
    vec4 slope = cacheAt(cacheDirectSlope, c, tc);
    imageStore(towardsViewer, c, vec4(weighted.rgb * lobe, weighted.a));
    imageStore(towardsViewerSlope, c, vec4(slope.rgb * lobe, slope.a));
    imageStore(towardsViewerCap, c, vec4(kDirectBeyondLargest * lengthsAndLargest.a));
}
