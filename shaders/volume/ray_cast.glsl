// Single-pass GPU ray casting, front to back, with the transfer function: castRay() gives one
// pixel's premultiplied colour. Two entry points share it: ray_cast.frag (a fullscreen triangle,
// blended over the target) and ray_cast.comp (the volume's screen rectangle, composited through
// image load/store); src/volume/ray_cast_pass.cpp picks one (VolumeRenderOptions::rayCaster).
// Variants (defines set by src/volume/ray_cast_pass.cpp; switches that a uniform could hold are
// defines because llvmpipe runs a branch's body whether or not any lane takes it):
//   SHADING_GRADIENT 0|1   : Blinn-Phong from the gradient (central differences)
//   SHADING_SCATTERING 0|1 : light from the light volumes (chromaticity c, intensity l)
//   EMPTY_SPACE_SKIPPING 0|1 : jump over bricks the transfer function makes fully transparent
//   EYE_PASS 0|1           : add the eye pass's blurred light from behind (scattering only)
//   PREINTEGRATED 0|1      : classify the segment between samples from the pre-integrated table
//   GRADIENT_VOLUME 0|1    : gradients from the precomputed gradient volume (else six fetches)
//   VALUES_IN_GRADIENTS 0|1: its fourth channel holds the data value: a gradient-shaded sample
//                            reads one texel for its value and its gradient
//   LIGHT_COUNT n          : the number of lights, fixed at compile time so the loop over the
//                            light volumes indexes its sampler array with constants (dynamic
//                            indices make software rasterisers fetch from every array element)
//   DIRECTIONAL_LIGHTS_ONLY 0|1: every light is directional: gradient shading takes each light's
//                            half vector once per ray, and no sample needs its world position
//   INTEGER_SHININESS n    : 1..256: the specular exponent, raised to by squaring; 0: pow()
//   PHYSICAL_MODEL 0|1     : physical single scattering (sss::VolumeModel::Physical): grey
//                            light, l alone; 0: the paper's model, chromaticity c as well
//   MESH_SHADOWS 0|1       : meshes of a hybrid scene cast shadows into the volume
//   CLIP 0|1               : clip planes or a crop box cut the volume (volume/clip.glsl)
//   SCATTERING_CACHE 0|1   : add the multiple-scattering cache's light (physical model)
//   CACHE_PER_SAMPLE 0|1   : evaluate its lobe per sample from its six textures; 0: read the
//                            view pass's three (FluenceCache::evaluateView)
//   DIAGONAL_GRADIENT_METRIC 0|1: gradientMetric is diagonal (the model transform neither shears
//                            nor scales unequally along turned axes): |M g|^2 is three products
// Both 0 is emission-absorption; both 1 is scattering with gradient specular highlights.
// (The first lines of the program: an #extension must come before any code.)
#extension GL_ARB_shader_group_vote : enable
#include "common/camera.glsl"
#include "common/lights.glsl"
#include "common/blinn_phong.glsl"
#include "volume/ray_setup.glsl"
#include "volume/transfer_function.glsl"
#include "volume/clip.glsl"

// One fetch per sample for value and gradient (see VALUES_IN_GRADIENTS above).
#if SHADING_GRADIENT && GRADIENT_VOLUME && VALUES_IN_GRADIENTS
#define COMBINED_FETCH 1
#else
#define COMBINED_FETCH 0
#endif

uniform vec3 boxMin;
uniform vec3 boxMax;
uniform ivec3 volumeDims;
uniform float stepLength;             // model units
uniform float opacityExponent;        // stepLength / reference length (one voxel)
uniform float earlyTermination;       // stop when accumulated opacity reaches this
uniform int jitterEnabled;
uniform float jitterShift;            // added to every pixel's jitter: differs per anti-aliasing frame
uniform int maxSteps;
uniform sampler2D sceneDepth;         // depth of what the target already holds (opaque meshes)
#if EMPTY_SPACE_SKIPPING
uniform sampler3D occupancy;          // per brick: > 0 where the TF gives any opacity
uniform int brickVoxels;
// Texture coordinates to brick coordinates (dims / brickVoxels): a sample's brick is a float
// product, not an integer division per sample (software rasterisers have no vector integer
// division and split it into scalar ones: a fifth of an emission-absorption frame on llvmpipe).
// brickVoxels is a power of two, so the product is exact and the brick the same.
uniform vec3 textureToBrick;
ivec3 lastBrick;  // set once per ray (main)
// The ray leaves brick b at the least of b * brickExitStep + brickExitOffset over the axes (its far
// faces; both set once per ray in main): a multiply-add per skip instead of a box intersection,
// which llvmpipe computed at every sample, since it runs a branch whether or not a lane takes it.
vec3 brickExitStep;
vec3 brickExitOffset;
#endif

#if SHADING_GRADIENT || SHADING_SCATTERING
uniform mat4 modelToWorld;
uniform float ambientStrength;
uniform float diffuseStrength;
uniform float phaseG;               // its Henyey-Greenstein mean cosine
#endif
#if SHADING_GRADIENT
uniform mat3 gradientToOutward;    // model-space gradient -> outward world normal (unnormalised)
uniform mat3 gradientMetric;       // its transpose times itself: |gradientToOutward g|^2 = g . gradientMetric g
uniform vec3 specularColor;
uniform float shininess;
uniform float gradientThreshold;   // |gradient| (per voxel) below which shading fades out
#endif
#if SHADING_SCATTERING
uniform sampler3D lightVolumes[MAX_LIGHTS];   // one per light: (c, l) arriving at each point
uniform mat3 worldToModelDirection;           // inverse of modelToWorld's linear part
uniform float lightVolumeReach;               // light-volume texels towards the light (see shade)
#include "volume/mesh_visibility.glsl"

#if EYE_PASS
uniform sampler3D eyeVolume;    // rgb: scattered light arriving from behind, towards the viewer
uniform float eyePassStrength;
#endif

#endif

vec3 toTexture(vec3 p) { return (p - boxMin) / (boxMax - boxMin); }


#if SHADING_GRADIENT
// The shading normal, kept in the gradient's space: n is the outward world normal M g / |M g|
// (M = gradientToOutward) turned to the viewer, so n . x = scale (g . M^T x). A direction known
// once per ray (the viewer, a directional light, its half vector) is taken to that space once,
// and a sample pays one dot product per direction instead of a matrix, a normalisation and
// then the dot products (about 7 % of a gradient frame on llvmpipe).
struct SurfaceNormal {
    vec3 g;          // the gradient, value units per voxel along the model axes
    float scale;     // +-1 / |M g|, the sign turning n to the viewer; 0 where g has no direction
    float strength;  // 0..1: fades shading out where the gradient is too weak to define n
};

// M^T x: a world direction in the gradient's space (see SurfaceNormal).
vec3 toGradientSpace(vec3 x) { return x * gradientToOutward; }

float normalDot(SurfaceNormal surface, vec3 gradientSpaceDirection) {
    return surface.scale * dot(surface.g, gradientSpaceDirection);
}

#if GRADIENT_VOLUME
uniform sampler3D gradientVolume;  // per-voxel central differences d, encoded (volume/gradient.comp)
uniform vec2 gradientDecode;       // d = texel * x + y (GradientEncoding)
#endif
#if COMBINED_FETCH
// The gradient (central differences) at the point being shaded: the caller reads it with the
// value (sampleVolume) and sets it before compositing.
vec3 shadedDifferences;
#endif

// viewer: the direction towards the viewer in the gradient's space.
SurfaceNormal gradientNormal(vec3 tc, vec3 viewer) {
    // Central differences, one voxel apart on each axis; gradient in value units per voxel.
#if COMBINED_FETCH
    vec3 g = shadedDifferences * (0.5 * valueScaleOffset.x);
#elif GRADIENT_VOLUME
    // Precomputed: the per-voxel differences reconstructed as the field is (trilinear or cubic)
    // are the central differences of the field, the gradient the on-the-fly path computes.
    vec3 g = (reconstruct(gradientVolume, tc).xyz * gradientDecode.x + gradientDecode.y) * (0.5 * valueScaleOffset.x);
#else
    vec3 h = 1.0 / vec3(volumeDims);
    vec3 g = vec3(volumeValue(tc + vec3(h.x, 0, 0)) - volumeValue(tc - vec3(h.x, 0, 0)),
                  volumeValue(tc + vec3(0, h.y, 0)) - volumeValue(tc - vec3(0, h.y, 0)),
                  volumeValue(tc + vec3(0, 0, h.z)) - volumeValue(tc - vec3(0, 0, h.z))) *
             0.5 * valueScaleOffset.x;
#endif
    // Surfaces face from high to low values; M also scales the gradient by the box so
    // anisotropic boxes get correct normals (RayCastPass::run). A zero gradient has no
    // direction: no light (its strength is zero there too).
#if DIAGONAL_GRADIENT_METRIC
    float outwardSquared = dot(g * g, vec3(gradientMetric[0][0], gradientMetric[1][1], gradientMetric[2][2]));
#else
    float outwardSquared = dot(g, gradientMetric * g);
#endif
    float scale = outwardSquared > 1e-24 ? inversesqrt(outwardSquared) : 0.0;
    return SurfaceNormal(g, dot(g, viewer) < 0.0 ? -scale : scale, smoothstep(0.0, gradientThreshold, length(g)));
}
#endif

// The data value at texture coordinate tc (xyz: its central differences with COMBINED_FETCH).
#if COMBINED_FETCH
vec4 sampleVolume(vec3 tc) {
    vec4 s = reconstruct(gradientVolume, tc);
    return vec4(s.xyz * gradientDecode.x + gradientDecode.y, s.w);
}
#else
vec4 sampleVolume(vec3 tc) { return vec4(0.0, 0.0, 0.0, volumeValue(tc)); }
#endif

#if PREINTEGRATED
// Texel (front value, back value) of one step-long segment over which the data goes linearly
// from front to back (src/volume/preintegration.h): layer 0 its premultiplied colour and
// opacity, layer 1 where it adds its light (fraction from its front) x opacity.
uniform sampler2DArray preintegrationTable;
uniform float preintegrationSize;

struct Segment {
    vec4 premultiplied;
    float depth;  // where the segment adds its light on average, as a fraction from its front
};

vec2 preintegrationCoordinate(float front, float back) {
    vec2 x = clamp(vec2(front, back) * valueScaleOffset.x + valueScaleOffset.y, 0.0, 1.0);
    return (x * (preintegrationSize - 1.0) + 0.5) / preintegrationSize;
}

Segment classifySegment(float front, float back) {
    vec2 uv = preintegrationCoordinate(front, back);
    vec4 c = texture(preintegrationTable, vec3(uv, 0.0));
    float depth = texture(preintegrationTable, vec3(uv, 1.0)).r;
    return Segment(c, c.a > 0.0 ? clamp(depth / c.a, 0.0, 1.0) : 0.5);
}

// The same for a homogeneous stretch of optical depth tau (meanContributionDepth in C++).
float meanContributionDepth(float tau) {
    return tau < 0.1 ? 0.5 - tau / 12.0 : 1.0 / tau - 1.0 / (exp(min(tau, 80.0)) - 1.0);
}

// A stretch shorter than a step (where the ray enters or leaves the medium) classified by one
// value over its `voxels`.
Segment pointSegment(float value, float voxels) {
    vec4 tf = classify(value);
    float a = correctOpacity(tf.a, voxels, 1.0);
    float tau = -log(max(1.0 - min(tf.a, 1.0), 1e-7)) * voxels;
    return Segment(vec4(tf.rgb * a, a), meanContributionDepth(tau));
}
#endif

#if SHADING_GRADIENT || SHADING_SCATTERING
// Towards the viewer from any point of this pixel's ray: the same all along it (set in main).
vec3 viewerDirection;
#if SHADING_GRADIENT
vec3 viewerInGradientSpace;  // toGradientSpace(viewerDirection) (set in main)
#if DIRECTIONAL_LIGHTS_ONLY
// Each light's direction and half vector normalize(l + v) in the gradient's space: also the same
// all along the ray (set in main).
vec3 rayLightsInGradientSpace[MAX_LIGHTS];
vec3 rayHalfVectorsInGradientSpace[MAX_LIGHTS];
#endif
#endif

#if SHADING_SCATTERING
// The light-volume reach towards light i, whose direction is l (see shade): in texture
// coordinates, and its per-axis inverse.
struct LightReach {
    vec3 reach;
    vec3 inverseReach;
    float voxels;  // its length in data voxels
};

LightReach lightReachTowards(int i, vec3 l) {
    vec3 lightTexels = vec3(textureSize(lightVolumes[i], 0));
    vec3 towardsLight = worldToModelDirection * l * lightTexels / (boxMax - boxMin);
    float towardsLength = length(towardsLight);
    vec3 reach = towardsLength > 0.0 ? towardsLight / towardsLength * lightVolumeReach / lightTexels : vec3(0.0);
    return LightReach(reach, safeInverse(reach), length(reach * vec3(volumeDims)));
}
#if DIRECTIONAL_LIGHTS_ONLY
// A directional light's reach is the same at every sample (set in main).
LightReach rayLightReaches[MAX_LIGHTS];
#endif
#endif

#if SCATTERING_CACHE
#include "volume/fluence_lobe.glsl"
uniform float cacheDirectWeight[MAX_LIGHTS];  // volume/direct_light.glsl's weights, for the cache's lights
uniform vec3 cacheRadianceScale;               // the lights' radiance now over the cache's (per channel)
#if CACHE_PER_SAMPLE
// The cache's six textures (FluenceCache::bindSources) at their finest cells, and the lobe towards
// the viewer evaluated at every shaded sample: cheaper than the view pass over every cell where
// the cells outnumber the pixels (VolumeRenderOptions::cacheViewEvaluation).
uniform sampler3D cacheFluence;
uniform sampler3D cacheFluxRed;
uniform sampler3D cacheFluxGreen;
uniform sampler3D cacheFluxBlue;
uniform sampler3D cacheSecondMoment;
uniform sampler3D cacheDirectSlope;
uniform vec4 cacheViewer;  // model space: the eye (w 1) or the direction towards it (w 0)

CacheTowardsViewer cacheTowardsViewerAt(vec3 p, vec3 tc) {
    vec4 weighted = textureLod(cacheFluence, tc, 0.0);
    if (!(weighted.a > 0.0)) return CacheTowardsViewer(vec4(0.0), vec4(0.0), 0.0);
    vec3 towards = cacheViewer.w != 0.0 ? cacheViewer.xyz - p : cacheViewer.xyz;
    vec3 v = length(towards) > 0.0 ? normalize(towards) : vec3(0.0, 0.0, 1.0);
    return cacheTowards(v, phaseG, weighted, textureLod(cacheFluxRed, tc, 0.0), textureLod(cacheFluxGreen, tc, 0.0),
                        textureLod(cacheFluxBlue, tc, 0.0), textureLod(cacheSecondMoment, tc, 0.0),
                        textureLod(cacheDirectSlope, tc, 0.0));
}
#else
// The cache's light towards this viewer (FluenceCache::evaluateView, volume/fluence_view.comp),
// per cell and premultiplied by the cell's weight w (normalised interpolation): at the cell's
// mean direct light, and w; its slope against the direct light, and that mean; the largest
// direct light it follows.
uniform sampler3D cacheTowardsViewer;
uniform sampler3D cacheTowardsViewerSlope;
uniform sampler3D cacheTowardsViewerCap;

CacheTowardsViewer cacheTowardsViewerAt(vec3 p, vec3 tc) {
    vec4 atMean = textureLod(cacheTowardsViewer, tc, 0.0);
    if (!(atMean.a > 0.0)) return CacheTowardsViewer(vec4(0.0), vec4(0.0), 0.0);  // no medium: no more reads
    return CacheTowardsViewer(atMean, textureLod(cacheTowardsViewerSlope, tc, 0.0),
                              textureLod(cacheTowardsViewerCap, tc, 0.0).r);
}
#endif

// At model-space point p (texture coordinate tc); direct: the light arriving unscattered at the
// sample, as volume/direct_light.glsl weighs it. Within a cell, the light scattered once follows
// the direct light that scatters it: the cell's slope moves the sample's light by its direct
// light's difference from the cell's mean, up to the cap; however noisy the slope, it keeps the
// light within 0 and 3 times the cell's mean.
vec3 cachedInScattering(vec3 p, vec3 tc, float direct) {
    CacheTowardsViewer light = cacheTowardsViewerAt(p, tc);
    if (!(light.atMean.a > 0.0)) return vec3(0.0);
    float inverseWeight = 1.0 / light.atMean.a;
    vec3 mean = light.atMean.rgb * inverseWeight;
    float cap = light.cap * inverseWeight;
    return clamp(mean + light.slope.rgb * inverseWeight * (min(direct, cap) - light.slope.a * inverseWeight), vec3(0.0),
                 3.0 * mean);
}
#endif

#if SHADING_SCATTERING
// The light volume stores light at voxel centres, and next to a dense or thin structure its
// trilinear interpolation mixes in the dark voxels inside it (rings as the surface crosses the
// grid, and too little light on every lit surface). So a sample reads it lightVolumeReach texels
// towards the light, at q, clear of the structure it sits in, and carries that light back to
// itself through the data, c and l changing on the way as in the light volume:
// L(p) = L(q) T(q -> p).

// The share of the full reach (texture coordinates, towards light i) that stays inside the box
// and short of a point light; beyond either the light arrives whole.
float reachShare(int i, vec3 tc, LightReach full, vec3 worldPosition) {
    vec3 exits = max(-tc * full.inverseReach, (1.0 - tc) * full.inverseReach);
    float share = min(min(exits.x, exits.y), exits.z);
#if !DIRECTIONAL_LIGHTS_ONLY
    if (lightVector[i].w != 0.0) {
        float reachWorld = length(mat3(modelToWorld) * (full.reach * (boxMax - boxMin)));
        if (reachWorld > 0.0) share = min(share, length(lightVector[i].xyz - worldPosition) / reachWorld);
    }
#endif
    return clamp(share, 0.0, 1.0);
}

#if PHYSICAL_MODEL
// The classification's opacity alone (RayCastInputs::opacityTable): all the grey light reads of
// it, with a quarter of the channels to filter.
uniform sampler2D opacityTable;
#if PREINTEGRATED
float segmentOpacity(float front, float back) { return texture(opacityTable, preintegrationCoordinate(front, back)).r; }
#endif
#endif

// `light` ((c, l) at tc + reach) carried back to tc through the data, in pieces about a voxel
// long. The physical model's light is grey (it reads l alone): there the pieces' transmittances
// multiply, and one power corrects their product for the pieces' length instead of one per piece.
vec4 carriedBack(vec4 light, vec3 tc, vec3 reach, float reachVoxels) {
    int pieces = clamp(int(ceil(reachVoxels)), 1, 16);
    float pieceVoxels = reachVoxels / float(pieces);
#if PREINTEGRATED
    float pieceSteps = pieceVoxels / opacityExponent;  // the table's opacities are per ray step
#else
    float pieceSteps = pieceVoxels;  // the transfer function's are per voxel
#endif
#if PHYSICAL_MODEL
    float transmitted = 1.0;
#endif
#if PREINTEGRATED
    // Each piece classified as a segment between its two ends (the data linear between them), as
    // the eye ray's: point samples a voxel apart miss most of a thin opaque layer's steep rise,
    // and let too much light through to a sample just inside it.
    float far = volumeValue(tc + reach);
    for (int k = pieces - 1; k >= 0; --k) {
        float near = volumeValue(tc + reach * (float(k) / float(pieces)));
        bool seen = lightSeesMedium(tc + reach * ((float(k) + 0.5) / float(pieces)));
#if PHYSICAL_MODEL
        transmitted *= seen ? 1.0 - min(segmentOpacity(far, near), 1.0) : 1.0;
        far = near;
#else
        Segment piece = classifySegment(far, near);
        far = near;
        float a = piece.premultiplied.a;
        if (a <= 0.0 || !seen) continue;
        vec3 colour = piece.premultiplied.rgb / a;
        a = correctOpacity(a, pieceSteps, 1.0);
        light = vec4((1.0 - a) * light.rgb + a * colour, (1.0 - a) * light.a);
#endif
    }
#else
    for (int k = pieces - 1; k >= 0; --k) {
        vec3 tcK = tc + reach * ((float(k) + 0.5) / float(pieces));
#if PHYSICAL_MODEL
        float opacity = lightSeesMedium(tcK) ? classifyOpacity(opacityTable, volumeValue(tcK)) : 0.0;
        transmitted *= 1.0 - min(opacity, 1.0);
#else
        vec4 medium = lightSeesMedium(tcK) ? classify(volumeValue(tcK)) : vec4(0.0);
        float a = correctOpacity(medium.a, pieceSteps, 1.0);
        light = vec4((1.0 - a) * light.rgb + a * medium.rgb, (1.0 - a) * light.a);
#endif
    }
#endif
#if PHYSICAL_MODEL
    light.a *= pow(transmitted, pieceSteps);
#endif
    return light;
}

// The light from light i arriving at p (texture coordinate tc), as (c l, l): c the light
// volume's chromaticity, l its intensity, times the meshes' shadow.
vec4 arrivingLight(int i, vec3 p, vec3 tc) {
#if !DIRECTIONAL_LIGHTS_ONLY
    vec3 worldPosition = (modelToWorld * vec4(p, 1.0)).xyz;
    vec3 radiance;
    LightReach full = lightReachTowards(i, lightDirectionAt(i, worldPosition, radiance));
#else
    const vec3 worldPosition = vec3(0.0);  // directional lights do not depend on it
    LightReach full = rayLightReaches[i];
#endif
    float share = reachShare(i, tc, full, worldPosition);
    vec3 reach = full.reach * share;
    vec4 light = share < 1.0 ? vec4(1.0) : texture(lightVolumes[i], tc + reach);
    light = carriedBack(light, tc, reach, full.voxels * share);
    light.a *= meshVisibility(i, (modelToWorld * vec4(p, 1.0)).xyz);
    return vec4(light.rgb * light.a, light.a);
}

#if PREINTEGRATED
// The light at the current segment's two ends, per light. The ray caster evaluates it once per
// sample, at every sample next to a segment that holds medium (it looks one sample ahead), so a
// segment's front is the previous sample's light: one call site in the loop, which keeps
// neighbouring rays in step on SIMD hardware.
vec4 frontLight[MAX_LIGHTS];
vec4 backLight[MAX_LIGHTS];
bool frontLit;              // frontLight holds the light at the current segment's start (the march's)
float segmentOpticalDepth;  // the eye ray's across the current segment

void evaluateLightAt(vec3 q) {
    for (int i = 0; i < LIGHT_COUNT; ++i) backLight[i] = arrivingLight(i, q, toTexture(q));
}

// Outside the loop only (the ray's first and last stretches): llvmpipe runs a branch's body
// whether or not a lane takes it, so a second light evaluation in the loop would double its cost.
void evaluateFrontLightAt(vec3 q) {
    for (int i = 0; i < LIGHT_COUNT; ++i) frontLight[i] = arrivingLight(i, q, toTexture(q));
}

// After a sample: its light is the next segment's front.
void passLightOn() {
    for (int i = 0; i < LIGHT_COUNT; ++i) frontLight[i] = backLight[i];
}

float layerMean(float x) {
    x = max(x, -80.0);
    return abs(x) < 1e-3 ? 1.0 - 0.5 * x : (1.0 - exp(-x)) / x;
}

// The light a segment scatters, as one arriving light: its optical depth taken to grow in step
// with the eye ray's across the segment, which is exact in a layered medium of any profile and
// keeps a surface lit at a grazing angle from being shaded by the light one point deep in it
// (docs/opaque-surfaces.md derives it).
vec4 segmentLight(int i) {
    float a = segmentOpticalDepth;
#if PHYSICAL_MODEL
    // Grey light: l alone, in every channel.
    float front = max(frontLight[i].a, 1e-20);
    float b = log(front / max(backLight[i].a, 1e-20));
    return vec4(front * layerMean(a + b) / layerMean(a));
#else
    vec4 front = max(frontLight[i], vec4(1e-20));
    vec4 b = log(front / max(backLight[i], vec4(1e-20)));
    return front * vec4(layerMean(a + b.x), layerMean(a + b.y), layerMean(a + b.z), layerMean(a + b.w)) / layerMean(a);
#endif
}
#endif
#endif

vec3 shade(vec3 p, vec3 tc, vec3 color) {
#if !DIRECTIONAL_LIGHTS_ONLY
    vec3 worldPosition = (modelToWorld * vec4(p, 1.0)).xyz;
#else
    const vec3 worldPosition = vec3(0.0);  // directional lights do not depend on it
#endif
#if SHADING_GRADIENT
    SurfaceNormal surface = gradientNormal(tc, viewerInGradientSpace);
#endif
    vec3 lit = ambientStrength * color;
#if SCATTERING_CACHE
    float direct = 0.0;  // the light arriving unscattered (cachedInScattering)
#endif
    for (int i = 0; i < LIGHT_COUNT; ++i) {
#if DIRECTIONAL_LIGHTS_ONLY
        // The light's own (lightDirectionAt's test of the light's kind, though the same for every
        // sample, cost llvmpipe a tenth of a gradient frame).
        vec3 radiance = lightRadiance[i];
        vec3 l = lightVector[i].xyz;
#else
        vec3 radiance;
        vec3 l = lightDirectionAt(i, worldPosition, radiance);
#endif
#if SHADING_GRADIENT && DIRECTIONAL_LIGHTS_ONLY
        float nDotL = normalDot(surface, rayLightsInGradientSpace[i]);
        float nDotH = normalDot(surface, rayHalfVectorsInGradientSpace[i]);
#elif SHADING_GRADIENT
        float nDotL = normalDot(surface, toGradientSpace(l));
        float nDotH = normalDot(surface, toGradientSpace(normalize(l + viewerDirection)));
#endif
#if SHADING_SCATTERING
#if PREINTEGRATED
        vec4 light = segmentLight(i);
#else
        vec4 light = arrivingLight(i, p, tc);
#endif
#if PHYSICAL_MODEL
        // Single scattering: albedo (TF colour) x phase function between the light's travel
        // direction -l and the way to the viewer x the light that arrives (grey extinction: no
        // chromaticity).
        float cosTheta = dot(-l, viewerDirection);
        float d = 1.0 + phaseG * phaseG - 2.0 * phaseG * cosTheta;
        float phase = (1.0 - phaseG * phaseG) / (12.5663706 * d * sqrt(d));
        lit += color * radiance * (light.a * phase);
#if SCATTERING_CACHE
        direct += cacheDirectWeight[i] * light.a;
#endif
#else
        lit += diffuseStrength * color * radiance * light.rgb;
#endif
#if SHADING_GRADIENT
        if (nDotL > 0.0)
            lit += surface.strength * light.a * radiance * specularColor * specularPower(max(nDotH, 0.0), shininess);
#endif
#else
        lit += blinnPhongCosines(nDotL, nDotH, radiance, diffuseStrength * color, specularColor, shininess);
#endif
    }
#if SHADING_SCATTERING
#if SCATTERING_CACHE
    lit += color * cacheRadianceScale * cachedInScattering(p, tc, direct);
#endif
#if EYE_PASS
    lit += diffuseStrength * eyePassStrength * color * texture(eyeVolume, tc).rgb;  // the paper's model only
#endif
    return lit;
#else
    // Homogeneous regions have no meaningful normal: fade to the unshaded colour there.
    return mix(color, lit, surface.strength);
#endif
}
#endif

#if !PREINTEGRATED
// The transfer function with each entry's opacity corrected for one ray step (the TF's is per
// voxel), on a grid finer than the TF's (src/volume/step_classification.h): a table lookup per
// sample instead of a pow().
uniform sampler2D stepTransferFunction;
uniform float stepTransferFunctionEntries;

vec4 classifyStep(float value) {
    return texture(stepTransferFunction, vec2(transferFunctionCoordinate(value, stepTransferFunctionEntries), 0.5));
}
#endif

#if EMPTY_SPACE_SKIPPING
ivec3 brickAt(vec3 tc) { return clamp(ivec3(tc * textureToBrick), ivec3(0), lastBrick); }
bool inEmptyBrick(vec3 tc) { return texelFetch(occupancy, brickAt(tc), 0).r == 0.0; }

// The last sample index (samples at tFirst + i * stepLength) inside `brick`, which the ray
// leaves in whole steps, so the samples taken are exactly those a caster without skipping would
// take (and the skipped ones would all be transparent).
int lastStepIn(ivec3 brick, float tFirst) {
    vec3 tFar = vec3(brick) * brickExitStep + brickExitOffset;
    float exitT = min(min(tFar.x, tFar.y), tFar.z);
    return int(ceil((exitT - tFirst) / stepLength)) - 1;
}
#endif

#if SHADING_SCATTERING
// Scattering shades a sample at several times the cost of taking it (the light volume and the
// light carried back through the data), and SIMD hardware shades a group of rays together, in
// every loop pass where one of them shades (llvmpipe even where none does). So the rays march
// and shade apart: each queues the samples it must light, and the group shades in rounds, each
// ray its oldest queued sample. Between rounds every ray marches on until every ray of the group
// holds a sample (GL_ARB_shader_group_vote), its queue filling meanwhile, so no ray idles in the
// march while another looks for its next sample. The queue only reorders the work: each ray
// lights and composites the same samples in the same order, so the image is the same.
// Measured on llvmpipe (benchmarks/README.md, "Queued shading").
#define QUEUED_SHADING 1
#else
#define QUEUED_SHADING 0
#endif

#if QUEUED_SHADING
const int kQueuedSamples = 8;  // measured: 4 and 16 slower on llvmpipe

// Whether every ray of this SIMD group still in the loop holds `condition`; without the vote,
// this ray's own (each ray then stops marching at its first sample to light).
#ifdef GL_ARB_shader_group_vote
#define EVERY_RAY(condition) allInvocationsARB(condition)
#else
#define EVERY_RAY(condition) (condition)
#endif

// A sample waiting to be lit: at t along the ray, the light it adds weighted by the ray's
// transmittance when it was taken.
struct QueuedSample {
    vec4 colour;  // the TF's colour and opacity; pre-integrated: the segment's, premultiplied
    float t;
    float transmittance;
#if PREINTEGRATED
    float depth;  // the segment's (Segment)
#endif
#if COMBINED_FETCH
    vec3 differences;  // the gradient where it is shaded
#endif
};

struct SampleQueue {
    QueuedSample samples[kQueuedSamples];  // newest first
    int count;
};

void enqueue(inout SampleQueue queue, QueuedSample s) {
    for (int k = kQueuedSamples - 1; k > 0; --k) queue.samples[k] = queue.samples[k - 1];
    queue.samples[0] = s;
    ++queue.count;
}

// Constant indices only: an array indexed by a variable lives in memory on llvmpipe (gathers and
// scatters at every step), one indexed by constants in registers.
QueuedSample dequeueOldest(inout SampleQueue queue) {
    --queue.count;
    QueuedSample oldest = queue.samples[0];
    for (int k = 1; k < kQueuedSamples; ++k)
        if (queue.count == k) oldest = queue.samples[k];
    return oldest;
}

// The ray's march: its next step index, its opacity so far, and whether it still marches (not
// past its end, not terminated early).
struct RayMarch {
    int i;
    float alpha;
    bool marching;
#if PREINTEGRATED
    vec4 ahead;              // the next sample taken, one step early
    Segment aheadSegment;    // the segment that ends there
    bool frontLit;           // the light at the last sample marched is the next segment's front
    bool reachedEnd;         // the march left the ray at its end (not by early termination)
    float tEnd;              // where: the first sample position at or past span.y
#if EMPTY_SPACE_SKIPPING
    bool aheadEmpty;         // the next sample lies in an empty brick
#endif
#if COMBINED_FETCH
    vec3 previousDifferences;  // the gradient at the last sample marched
#endif
#endif
};

void addToOpacity(inout RayMarch m, float a) {
    m.alpha += (1.0 - m.alpha) * a;
    if (m.alpha >= earlyTermination) m.marching = false;
}

#if PREINTEGRATED
// One step of the march: the segment ending at sample i is queued if it, or the segment after
// it, holds medium (its light is then either one's end). The next sample is taken one step
// early, past empty bricks: one fetch and one classification per sample.
void marchOneStep(inout RayMarch m, inout SampleQueue queue, Ray ray, float tFirst, vec2 span, vec3 tcOrigin,
                  vec3 tcDirection) {
    float t = tFirst + float(m.i) * stepLength;
    if (m.i >= maxSteps || t >= span.y) {
        m.reachedEnd = m.i < maxSteps;
        m.tEnd = t;
        m.marching = false;
        return;
    }
    float value = m.ahead.w;
    Segment segment = m.aheadSegment;
#if COMBINED_FETCH
    vec3 differences = mix(m.previousDifferences, m.ahead.xyz, segment.depth);
    m.previousDifferences = m.ahead.xyz;
#endif
    // The next sample: one step on, or, where it and this one lie in empty bricks, the last
    // sample of its brick (which opens the segment to the one after it).
    int next = m.i + 1;
    bool nextLands = false;
#if EMPTY_SPACE_SKIPPING
    // This sample's brick was the last step's next one (a landing sample lies in the brick it
    // landed in): one occupancy fetch per step.
    bool emptyHere = m.aheadEmpty;
    ivec3 nextBrick = brickAt(tcOrigin + (tFirst + float(next) * stepLength) * tcDirection);
    m.aheadEmpty = texelFetch(occupancy, nextBrick, 0).r == 0.0;
    if (emptyHere && m.aheadEmpty) {
        next = max(next, lastStepIn(nextBrick, tFirst));
        nextLands = true;
    }
#endif
    m.ahead = sampleVolume(tcOrigin + min(tFirst + float(next) * stepLength, span.y) * tcDirection);
    // A landing sample's segment starts at itself (the skipped ones were clear).
    m.aheadSegment = classifySegment(nextLands ? m.ahead.w : value, m.ahead.w);
    m.i = next;
    bool lightHere = segment.premultiplied.a > 0.0 || (!nextLands && m.aheadSegment.premultiplied.a > 0.0);
    m.frontLit = lightHere && !nextLands;
    if (!lightHere) return;
#if COMBINED_FETCH
    enqueue(queue, QueuedSample(segment.premultiplied, t, 1.0 - m.alpha, segment.depth, differences));
#else
    enqueue(queue, QueuedSample(segment.premultiplied, t, 1.0 - m.alpha, segment.depth));
#endif
    addToOpacity(m, segment.premultiplied.a);
}

// Lights and removes the oldest queued sample: its light as the end of its segment (and the
// front of the next), and the light its segment adds.
vec3 shadeOldest(inout SampleQueue queue, Ray ray, vec3 tcOrigin, vec3 tcDirection) {
    QueuedSample s = dequeueOldest(queue);
    vec3 end = ray.origin + s.t * ray.direction;
    evaluateLightAt(end);
    vec3 added = vec3(0.0);
    float a = s.colour.a;
    if (a > 0.0) {
        segmentOpticalDepth = -log(max(1.0 - a, 1e-7));
#if COMBINED_FETCH
        shadedDifferences = s.differences;
#endif
        // Shaded where the segment adds its light (compositeSegment).
        vec3 p = end - (1.0 - s.depth) * stepLength * ray.direction;
        added = s.transmittance * a * shade(p, toTexture(p), s.colour.rgb / a);
    }
    passLightOn();
    return added;
}
#else
// One step of the march, queueing the sample if it is visible.
void marchOneStep(inout RayMarch m, inout SampleQueue queue, Ray ray, float tFirst, vec2 span, vec3 tcOrigin,
                  vec3 tcDirection) {
    float t = tFirst + float(m.i) * stepLength;
    vec3 tc = tcOrigin + t * tcDirection;
    if (m.i >= maxSteps || t >= span.y) {
        m.marching = false;
        return;
    }
#if EMPTY_SPACE_SKIPPING
    ivec3 brick = brickAt(tc);
    if (texelFetch(occupancy, brick, 0).r == 0.0) {
        m.i = max(m.i, lastStepIn(brick, tFirst)) + 1;
        return;
    }
#endif
    vec4 sampled = sampleVolume(tc);
    vec4 tf = classifyStep(sampled.w);
    ++m.i;
    if (!(tf.a > 0.0)) return;
#if COMBINED_FETCH
    enqueue(queue, QueuedSample(tf, t, 1.0 - m.alpha, sampled.xyz));
#else
    enqueue(queue, QueuedSample(tf, t, 1.0 - m.alpha));
#endif
    addToOpacity(m, tf.a);
}

// Shades and removes the oldest queued sample: the light it adds.
vec3 shadeOldest(inout SampleQueue queue, Ray ray, vec3 tcOrigin, vec3 tcDirection) {
    QueuedSample s = dequeueOldest(queue);
#if COMBINED_FETCH
    shadedDifferences = s.differences;
#endif
    return s.transmittance * s.colour.a *
           shade(ray.origin + s.t * ray.direction, tcOrigin + s.t * tcDirection, s.colour.rgb);
}
#endif

// Rounds: march until every ray of the group holds a queued sample (or its queue is full, or its
// march has ended), then light each ray's oldest. At most one round per sample.
vec3 marchAndShade(inout RayMarch march, Ray ray, float tFirst, vec2 span, vec3 tcOrigin, vec3 tcDirection) {
    SampleQueue queue;
    queue.count = 0;
    vec3 color = vec3(0.0);
    for (int round = 0; round < maxSteps; ++round) {
        do {
            if (march.marching && queue.count < kQueuedSamples)
                marchOneStep(march, queue, ray, tFirst, span, tcOrigin, tcDirection);
        } while (march.marching && queue.count < kQueuedSamples && !EVERY_RAY(queue.count > 0));
        if (queue.count == 0) break;
        color += shadeOldest(queue, ray, tcOrigin, tcDirection);
    }
    return color;
}
#endif

// Adds one sample (point classification) or segment (pre-integrated) front to back: colour
// `albedo`, opacity `a`, shaded at p (texture coordinate tc).
void composite(vec3 p, vec3 tc, vec3 albedo, float a, inout vec3 color, inout float alpha) {
#if SHADING_GRADIENT || SHADING_SCATTERING
    vec3 c = shade(p, tc, albedo);
#else
    vec3 c = albedo;
#endif
    color += (1.0 - alpha) * a * c;
    alpha += (1.0 - alpha) * a;
}

#if PREINTEGRATED
// A segment that ends at `end` and is `length` long (model units) along the ray. Shading goes
// where the segment adds its light, not at its end: in dense material the end lies in the
// shadow of the very surface the segment holds.
void compositeSegment(Segment segment, vec3 end, float length, vec3 direction, inout vec3 color, inout float alpha) {
    float a = segment.premultiplied.a;
    if (a <= 0.0) return;
#if SHADING_SCATTERING
    // frontLight and backLight hold the light at its ends (the caller's).
    segmentOpticalDepth = -log(max(1.0 - a, 1e-7));
#endif
    // The segment's mean colour, weighted by what each part of it adds.
    vec3 p = end - (1.0 - segment.depth) * length * direction;
    composite(p, toTexture(p), segment.premultiplied.rgb / a, a, color, alpha);
}
#endif

// fragCoord: the pixel's centre in window coordinates; ndc: the same point in [-1, 1]^2.
// Returns premultiplied colour, alpha = opacity.
vec4 castRay(vec2 fragCoord, vec2 ndc) {
    Ray ray = pixelRay(ndc);
#if EMPTY_SPACE_SKIPPING
    lastBrick = textureSize(occupancy, 0) - 1;
    vec3 brickSize = vec3(brickVoxels) / vec3(volumeDims) * (boxMax - boxMin);
    vec3 inverseDirection = safeInverse(ray.direction);
    brickExitStep = brickSize * inverseDirection;
    brickExitOffset = (boxMin - ray.origin) * inverseDirection + max(brickExitStep, vec3(0.0));
#endif
#if SHADING_GRADIENT || SHADING_SCATTERING
    viewerDirection = -normalize(mat3(modelToWorld) * ray.direction);
#endif
#if SHADING_GRADIENT
    viewerInGradientSpace = toGradientSpace(viewerDirection);
#if DIRECTIONAL_LIGHTS_ONLY
    for (int i = 0; i < LIGHT_COUNT; ++i) {
        rayLightsInGradientSpace[i] = toGradientSpace(lightVector[i].xyz);
        rayHalfVectorsInGradientSpace[i] = toGradientSpace(normalize(lightVector[i].xyz + viewerDirection));
    }
#endif
#endif
#if SHADING_SCATTERING && DIRECTIONAL_LIGHTS_ONLY
    for (int i = 0; i < LIGHT_COUNT; ++i) rayLightReaches[i] = lightReachTowards(i, lightVector[i].xyz);
#endif
    vec2 span = intersectBox(ray, boxMin, boxMax);
    // The ray in texture coordinates: a sample's is a multiply-add, not three divisions.
    vec3 tcOrigin = toTexture(ray.origin);
    vec3 tcDirection = ray.direction / (boxMax - boxMin);
    span = clipSpan(tcOrigin, tcDirection, span);  // the clip planes and crop box
    // Rays end at opaque geometry already in the target: a mesh in front hides the volume, a
    // mesh inside it cuts the rays at its surface.
    float depth = texelFetch(sceneDepth, ivec2(fragCoord), 0).r;
    if (depth < 1.0) {
        vec4 hitWorld = inverseViewProjection * vec4(ndc, depth * 2.0 - 1.0, 1.0);
        vec3 hitModel = (worldToModel * vec4(hitWorld.xyz / hitWorld.w, 1.0)).xyz;
        span.y = min(span.y, dot(hitModel - ray.origin, ray.direction));
    }
    vec3 color = vec3(0.0);
    float alpha = 0.0;
#if PREINTEGRATED && SHADING_SCATTERING
    frontLit = false;
    vec4 ahead;              // the next sample taken, one step early
    Segment aheadSegment;    // the segment that ends there
#endif
    if (span.x < span.y) {
        float tFirst = span.x + (jitterEnabled != 0 ? fract(pixelJitter(fragCoord) + jitterShift) : 0.5) * stepLength;
#if PREINTEGRATED
        // Each sample stands for the segment from the previous sample to it; the stretches before
        // the first sample and after the last are classified by one value each (outside the
        // loop: inside it, llvmpipe ran the whole ray twice as slowly). `previous` is the value of
        // the last sample taken; segmentOpen (the one-loop form): that sample lay outside empty
        // bricks, so the segment from it may hold medium.
        float firstEnd = min(tFirst, span.y);
        vec3 firstPoint = ray.origin + firstEnd * ray.direction;
        vec4 firstSample = sampleVolume(toTexture(firstPoint));
        float previous = firstSample.w;
#if COMBINED_FETCH
        vec3 previousDifferences = firstSample.xyz;  // the gradient at `previous`
        shadedDifferences = firstSample.xyz;
#endif
        Segment first = pointSegment(previous, (firstEnd - span.x) / stepLength * opacityExponent);
#if SHADING_SCATTERING
        ahead = sampleVolume(tcOrigin + min(tFirst + stepLength, span.y) * tcDirection);
        aheadSegment = classifySegment(previous, ahead.w);
        bool firstLit = first.premultiplied.a > 0.0 || aheadSegment.premultiplied.a > 0.0;
        if (first.premultiplied.a > 0.0) evaluateFrontLightAt(ray.origin + span.x * ray.direction);
        if (firstLit) evaluateLightAt(firstPoint);
#endif
        compositeSegment(first, firstPoint, firstEnd - span.x, ray.direction, color, alpha);
#if SHADING_SCATTERING
        passLightOn();
        frontLit = firstLit;
#endif
#if !SHADING_SCATTERING
        bool segmentOpen = true;
        bool landing = false;  // the loop has just skipped bricks and lands on their last sample
#endif
        const int firstStep = 1;
        bool reachedEnd = false;  // the loop left the ray at its end (not by early termination)
        float tEnd = 0.0;         // where: the first sample position at or past span.y
#else
        const int firstStep = 0;
#endif
        // Sample i sits at tFirst + i * step: computed from i, not accumulated, so a skip lands
        // on exactly the positions the unskipped loop would reach.
#if QUEUED_SHADING && PREINTEGRATED
        RayMarch march;
        march.i = firstStep;
        march.alpha = alpha;
        march.marching = true;  // as the first segment: early termination is tested after a lit sample
        march.ahead = ahead;
        march.aheadSegment = aheadSegment;
        march.frontLit = frontLit;
        march.reachedEnd = false;
        march.tEnd = 0.0;
#if EMPTY_SPACE_SKIPPING
        march.aheadEmpty = inEmptyBrick(tcOrigin + (tFirst + float(firstStep) * stepLength) * tcDirection);
#endif
#if COMBINED_FETCH
        march.previousDifferences = previousDifferences;
#endif
        color += marchAndShade(march, ray, tFirst, span, tcOrigin, tcDirection);
        alpha = march.alpha;
        frontLit = march.frontLit;
        reachedEnd = march.reachedEnd;
        tEnd = march.tEnd;
#elif QUEUED_SHADING
        RayMarch march = RayMarch(firstStep, 0.0, true);
        color += marchAndShade(march, ray, tFirst, span, tcOrigin, tcDirection);
        alpha = march.alpha;
#else
        for (int i = firstStep; i < maxSteps; ++i) {
            float t = tFirst + float(i) * stepLength;
            if (t >= span.y) {
#if PREINTEGRATED
                reachedEnd = true;
                tEnd = t;
#endif
                break;
            }
            vec3 p = ray.origin + t * ray.direction;
            vec3 tc = tcOrigin + t * tcDirection;
#if EMPTY_SPACE_SKIPPING
            ivec3 brick = brickAt(tc);
            bool emptyBrick = texelFetch(occupancy, brick, 0).r == 0.0;
#if PREINTEGRATED
            // The segment from the last sample taken into an empty brick may still hold medium at
            // its start: take this one sample to close it, and skip from the next.
            if (emptyBrick && !segmentOpen && !landing) {
#else
            if (emptyBrick) {
#endif
#if PREINTEGRATED
                // Land on the brick's last sample, which opens the segment to the next one: no
                // sample before it is needed, and the next segment's light is looked ahead to.
                i = max(i, lastStepIn(brick, tFirst)) - 1;  // the loop adds one
                landing = true;
#else
                i = max(i, lastStepIn(brick, tFirst));  // the loop adds one
#endif
                continue;
            }
#endif
            vec4 sampled = sampleVolume(tc);
            float value = sampled.w;
#if PREINTEGRATED
            // Landed in an empty brick: no segment ends here (and this sample's value is clear).
            if (landing) previous = value;
            landing = false;
            Segment segment = classifySegment(previous, value);
#if COMBINED_FETCH
            // The segment is shaded where it adds its light, a fraction `depth` along it: the
            // gradient there, linear between its two samples.
            shadedDifferences = mix(previousDifferences, sampled.xyz, segment.depth);
            previousDifferences = sampled.xyz;
#endif
            compositeSegment(segment, p, stepLength, ray.direction, color, alpha);
            previous = value;
#if EMPTY_SPACE_SKIPPING
            segmentOpen = !emptyBrick;
#else
            segmentOpen = true;
#endif
#else
            vec4 tf = classifyStep(value);
            if (tf.a <= 0.0) continue;
#if COMBINED_FETCH
            shadedDifferences = sampled.xyz;
#endif
            composite(p, tc, tf.rgb, tf.a, color, alpha);
#endif
            if (alpha >= earlyTermination) break;
        }
#endif
#if PREINTEGRATED
        // The rest of the ray after its last sample, if the loop reached the ray's end.
        float tailStart = max(tEnd - stepLength, span.x);
        float tail = span.y - tailStart;
        if (reachedEnd && tail > 0.0 && alpha < earlyTermination) {
            vec3 tailEnd = ray.origin + span.y * ray.direction;
            vec4 tailSample = sampleVolume(toTexture(tailEnd - 0.5 * tail * ray.direction));
#if COMBINED_FETCH
            shadedDifferences = tailSample.xyz;
#endif
            Segment tailSegment = pointSegment(tailSample.w, tail / stepLength * opacityExponent);
#if SHADING_SCATTERING
            if (tailSegment.premultiplied.a > 0.0) {
                if (!frontLit) evaluateFrontLightAt(ray.origin + tailStart * ray.direction);
                evaluateLightAt(tailEnd);
            }
#endif
            compositeSegment(tailSegment, tailEnd, tail, ray.direction, color, alpha);
        }
#endif
    }
    return vec4(color, alpha);
}
