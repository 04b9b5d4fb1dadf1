// The multiple-scattering cache's light towards one viewer (FluenceCache::evaluateView): per cell,
// what the cell scatters towards the eye, as a line in the direct light E that the eye knows at
// each sample. The ray caster then reads three textures per sample instead of the cache's six,
// and none of the lobe's arithmetic: it is done here once per cell and camera move, not once per
// sample and frame. (Where the cells outnumber the pixels on a software rasteriser the ray
// caster evaluates the same lobe per sample instead: CACHE_PER_SAMPLE.)
//
// The lobe: volume/fluence_lobe.glsl.
#include "volume/fluence_lobe.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

uniform sampler3D cacheFluence;       // w phi (rgb), w: every texture is premultiplied by w
uniform sampler3D cacheFluxRed;       // w F of the red channel (xyz), w M_yz
uniform sampler3D cacheFluxGreen;     // w F of the green channel (xyz), w times the largest E
uniform sampler3D cacheFluxBlue;      // w F of the blue channel (xyz)
uniform sampler3D cacheSecondMoment;  // w M_xx, w M_yy, w M_xy, w M_xz (traceless)
uniform sampler3D cacheDirectSlope;   // w B (rgb), w mean E
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

// A cache texture at cell c: the texel itself, unfiltered (filtered, llvmpipe's pass over 128^3
// cells took 200 ms instead of 135). While the cache refines its finest cells hold what the
// readers need (fluence_finest.comp).
vec4 cacheAt(sampler3D t, ivec3 c) { return texelFetch(t, c, 0); }

void main() {
    ivec3 c = ivec3(gl_GlobalInvocationID);
    ivec3 size = imageSize(towardsViewer);
    if (any(greaterThanEqual(c, size))) return;
    vec3 tc = (vec3(c) + 0.5) / vec3(size);
    vec4 weighted = cacheAt(cacheFluence, c);
    if (!(weighted.a > 0.0)) {
        imageStore(towardsViewer, c, vec4(0.0));
        imageStore(towardsViewerSlope, c, vec4(0.0));
        imageStore(towardsViewerCap, c, vec4(0.0));
        return;
    }
    vec3 towards = viewer.w != 0.0 ? viewer.xyz - mix(boxMin, boxMax, tc) : viewer.xyz;
    vec3 v = length(towards) > 0.0 ? normalize(towards) : vec3(0.0, 0.0, 1.0);
    CacheTowardsViewer light =
        cacheTowards(v, phaseG, weighted, cacheAt(cacheFluxRed, c), cacheAt(cacheFluxGreen, c), cacheAt(cacheFluxBlue, c),
                     cacheAt(cacheSecondMoment, c), cacheAt(cacheDirectSlope, c));
    imageStore(towardsViewer, c, light.atMean);
    imageStore(towardsViewerSlope, c, light.slope);
    imageStore(towardsViewerCap, c, vec4(light.cap));
}
