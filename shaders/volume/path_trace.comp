// Progressive volume path tracing (sss::VolumeRenderOptions::multipleScattering): per pixel,
// one path from the eye, adding (radiance, hit) to the running sums in `accumulation`. The estimator is renderVolumePathTraced()'s (sss/volume_path_tracer.h), in
// float: delta tracking against a majorant per brick, next-event estimation to every light
// with ratio tracking, HG scattering, Russian roulette on the throughput. All transport is in
// the volume's model space.
#include "volume/ray_setup.glsl"
#include "volume/transfer_function.glsl"
#include "common/spot_cone.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(rgba32f, binding = 0) uniform image2D accumulation;  // sums of (rgb value, hit)
uniform sampler2D sceneDepth;      // rays end at opaque geometry already in the target
uniform sampler3D majorants;       // per brick: an upper bound of sigma_t in it (per model unit)
uniform ivec2 imageSize;
uniform vec3 boxMin;
uniform vec3 boxMax;
uniform vec3 cellSize;             // one brick, model units
uniform float voxelLength;         // the opacity reference length D
uniform float phaseG;
uniform uint sampleIndex;          // this path's index in the pixel's running mean
uniform int maxBounces;
uniform mat4 modelToWorld;
uniform int lightCount;
uniform vec4 lightModel[MAX_LIGHTS];          // w 0: unit direction towards the light; w 1: position
uniform vec3 lightWorldPosition[MAX_LIGHTS];  // point lights: falloff is in world units
uniform vec3 lightRadiance[MAX_LIGHTS];       // colour * intensity
uniform vec3 lightSpotAxis[MAX_LIGHTS];       // spot lights: world-space unit cone axis (as in lights.glsl)
uniform vec2 lightSpotCosines[MAX_LIGHTS];    // spot lights: (cos outer, cos inner); (-2, -2): no cone

const float kPi = 3.14159265;
const float kRatioRoulette = 0.125;  // ratio tracking is rouletted below this transmittance
const int kRouletteStartBounce = 3;  // as VolumePathTracerOptions::rouletteStartBounce
const float kMaxOpticalDepthPerVoxel = 30.0;
// A bound on tentative collisions per walk: reached only by a degenerate ray, never by a path
// that matters (bonsai paths take tens).
const int kMaxLookups = 65536;

// Counter-based random numbers: a 32-bit hash (PCG's output permutation) of a Weyl sequence
// started at a hash of (pixel, sample index).
uint pcgHash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}
uint rngState;
float uniform01() {  // [0, 1), 24 bits
    rngState += 0x9e3779b9u;
    return float(pcgHash(rngState) >> 8u) * (1.0 / 16777216.0);
}
float exponential() { return -log(1.0 - uniform01()); }  // 1 - u is in (0, 1]

// sigma_t from the TF opacity per voxel, capped (sss::kMaxOpticalDepthPerVoxel), and clamped to
// the majorant so that float rounding in the filtering can never exceed it.
float extinction(vec3 p, float majorant, out vec4 tf) {
    tf = classify(texture(volumeTexture, (p - boxMin) / (boxMax - boxMin)).r);
    float depth = tf.a >= 1.0 ? kMaxOpticalDepthPerVoxel : min(-log(1.0 - tf.a), kMaxOpticalDepthPerVoxel);
    return min(depth / voxelLength, majorant);
}

// 3D DDA over the bricks the segment crosses.
struct Walk {
    ivec3 cell;
    ivec3 stepDir;
    vec3 tNext;
    vec3 tDelta;
};

Walk startWalk(vec3 o, vec3 d, float t0) {
    ivec3 cells = textureSize(majorants, 0);
    vec3 p = o + t0 * d;
    Walk w;
    w.cell = clamp(ivec3(floor((p - boxMin) / cellSize)), ivec3(0), cells - 1);
    vec3 inv = safeInverse(d);
    w.stepDir = ivec3(sign(d));
    vec3 lo = boxMin + vec3(w.cell) * cellSize;
    vec3 boundary = mix(lo, lo + cellSize, greaterThan(d, vec3(0.0)));
    w.tNext = t0 + (boundary - p) * inv;
    w.tDelta = abs(cellSize * inv);
    for (int a = 0; a < 3; ++a)
        if (w.stepDir[a] == 0) w.tNext[a] = 3.0e38;
    return w;
}

int nextAxis(vec3 t) { return t.x < t.y ? (t.x < t.z ? 0 : 2) : (t.y < t.z ? 1 : 2); }

// Delta tracking: the distance of the first real collision in [t0, t1] (its TF sample in tf),
// or -1 if the path leaves the segment.
float track(vec3 o, vec3 d, float t0, float t1, out vec4 tf) {
    tf = vec4(0.0);
    ivec3 cells = textureSize(majorants, 0);
    float tau = exponential();  // optical depth against the majorant left to spend
    Walk w = startWalk(o, d, t0);
    float t = t0;
    int lookups = 0;
    for (;;) {
        int a = nextAxis(w.tNext);
        float tb = min(w.tNext[a], t1);
        if (tb > t) {
            float majorant = texelFetch(majorants, w.cell, 0).r;
            if (majorant > 0.0) {
                for (;;) {
                    float dt = tau / majorant;
                    if (dt >= tb - t) {
                        tau = max(0.0, tau - majorant * (tb - t));
                        break;
                    }
                    t += dt;
                    if (++lookups > kMaxLookups) return -1.0;
                    vec4 sample_;
                    float sigma = extinction(o + t * d, majorant, sample_);
                    if (uniform01() * majorant < sigma) {
                        tf = sample_;
                        return t;
                    }
                    tau = exponential();
                }
            }
            t = tb;
        }
        if (w.tNext[a] >= t1) return -1.0;
        w.cell[a] += w.stepDir[a];
        if (w.cell[a] < 0 || w.cell[a] >= cells[a]) return -1.0;
        w.tNext[a] += w.tDelta[a];
    }
}

// Ratio tracking: an unbiased estimate of the transmittance over [0, t1] from o.
float transmittance(vec3 o, vec3 d, float t1) {
    ivec3 cells = textureSize(majorants, 0);
    Walk w = startWalk(o, d, 0.0);
    float tr = 1.0;
    float ta = 0.0;
    int lookups = 0;
    for (;;) {
        int a = nextAxis(w.tNext);
        float tb = min(w.tNext[a], t1);
        float majorant = texelFetch(majorants, w.cell, 0).r;
        if (tb > ta && majorant > 0.0) {
            // Tentative points are a Poisson process of rate `majorant`: each cell starts afresh.
            for (float t = ta;;) {
                t += exponential() / majorant;
                if (t >= tb) break;
                if (++lookups > kMaxLookups) return 0.0;
                vec4 unused;
                tr *= max(0.0, 1.0 - extinction(o + t * d, majorant, unused) / majorant);
                if (tr < kRatioRoulette) {
                    if (uniform01() * kRatioRoulette >= tr) return 0.0;
                    tr = kRatioRoulette;
                }
            }
        }
        if (w.tNext[a] >= t1) return tr;
        ta = max(ta, tb);
        w.cell[a] += w.stepDir[a];
        if (w.cell[a] < 0 || w.cell[a] >= cells[a]) return tr;
        w.tNext[a] += w.tDelta[a];
    }
}

float phaseHG(float cosTheta) {
    if (abs(phaseG) < 1e-3) return 0.25 / kPi;
    float denom = 1.0 + phaseG * phaseG - 2.0 * phaseG * cosTheta;
    return (1.0 - phaseG * phaseG) / (4.0 * kPi * denom * sqrt(denom));
}

vec3 scatterHG(vec3 d) {
    float u1 = uniform01(), u2 = uniform01();
    float cosT;
    if (abs(phaseG) < 1e-3) {
        cosT = 1.0 - 2.0 * u1;
    } else {
        float s = (1.0 - phaseG * phaseG) / (1.0 - phaseG + 2.0 * phaseG * u1);
        cosT = (1.0 + phaseG * phaseG - s * s) / (2.0 * phaseG);
    }
    cosT = clamp(cosT, -1.0, 1.0);
    float sinT = sqrt(max(0.0, 1.0 - cosT * cosT));
    float phi = 2.0 * kPi * u2;
    // Orthonormal basis around d (Duff et al. 2017).
    float sgn = d.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (sgn + d.z);
    float b = d.x * d.y * a;
    vec3 t1 = vec3(1.0 + sgn * d.x * d.x * a, sgn * b, -sgn * d.x);
    vec3 t2 = vec3(b, sgn + d.y * d.y * a, -d.y);
    return normalize(cosT * d + sinT * (cos(phi) * t1 + sin(phi) * t2));
}

// Clips o + t d, t in [tMin, tMax], to the box; false if nothing is left.
bool clipToBox(vec3 o, vec3 d, inout float tMin, inout float tMax) {
    vec3 inv = safeInverse(d);
    vec3 ta = (boxMin - o) * inv, tb = (boxMax - o) * inv;
    vec3 lo = min(ta, tb), hi = max(ta, tb);
    tMin = max(tMin, max(max(lo.x, lo.y), lo.z));
    tMax = min(tMax, min(min(hi.x, hi.y), hi.z));
    return tMin < tMax;
}

// Sum over lights of p_HG(l . d) E T_l at p, the path arriving along d.
vec3 nextEvent(vec3 p, vec3 d) {
    vec3 sum = vec3(0.0);
    for (int i = 0; i < lightCount; ++i) {
        vec3 l = lightModel[i].xyz;
        vec3 radiance = lightRadiance[i];
        float tEnd = 3.0e38;
        if (lightModel[i].w != 0.0) {
            vec3 toLight = lightModel[i].xyz - p;
            float distance = length(toLight);
            if (!(distance > 0.0)) continue;
            vec3 toLightWorld = lightWorldPosition[i] - (modelToWorld * vec4(p, 1.0)).xyz;
            float distanceSquared = max(dot(toLightWorld, toLightWorld), 1e-8);
            float cosAxis = -dot(toLightWorld, lightSpotAxis[i]) * inversesqrt(distanceSquared);
            radiance = radiance / distanceSquared * spotConeFactor(lightSpotCosines[i], cosAxis);
            l = toLight / distance;
            tEnd = distance;
        }
        float t0 = 0.0;
        float tr = clipToBox(p, l, t0, tEnd) ? transmittance(p, l, tEnd) : 1.0;
        if (tr > 0.0) sum += phaseHG(dot(l, d)) * radiance * tr;
    }
    return sum;
}

// One path: its value (rgb) and whether the camera ray had a real collision.
vec4 path(vec3 o, vec3 d, float t0, float t1) {
    vec3 value = vec3(0.0), throughput = vec3(1.0);
    float hit = 0.0;
    for (int bounce = 0;; ++bounce) {
        vec4 tf;
        float t = track(o, d, t0, t1, tf);
        if (t < 0.0) break;
        hit = 1.0;
        vec3 p = o + t * d;
        vec3 albedo = clamp(tf.rgb, 0.0, 1.0);
        value += throughput * albedo * nextEvent(p, d);
        throughput *= albedo;
        float q = max(max(throughput.r, throughput.g), throughput.b);
        if (!(q > 0.0) || bounce + 1 >= maxBounces) break;
        if (bounce + 1 >= kRouletteStartBounce && q < 1.0) {
            if (uniform01() >= q) break;
            throughput /= q;
        }
        d = scatterHG(d);
        o = p;
        t0 = 0.0;
        t1 = 3.0e38;
        if (!clipToBox(o, d, t0, t1)) break;
    }
    return vec4(value, hit);
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, imageSize))) return;
    // Pixel centres, as the CPU path tracer's (and the ray caster's) rays.
    vec2 ndc = (vec2(pixel) + 0.5) / vec2(imageSize) * 2.0 - 1.0;
    Ray ray = pixelRay(ndc);
    vec2 span = intersectBox(ray, boxMin, boxMax);
    float depth = texelFetch(sceneDepth, pixel, 0).r;
    if (depth < 1.0) {
        vec4 hitWorld = inverseViewProjection * vec4(ndc, depth * 2.0 - 1.0, 1.0);
        vec3 hitModel = (worldToModel * vec4(hitWorld.xyz / hitWorld.w, 1.0)).xyz;
        span.y = min(span.y, dot(hitModel - ray.origin, ray.direction));
    }
    if (!(span.x < span.y)) return;  // the background, exactly (the composite adds nothing)
    // One path per dispatch (see volume/path_trace_pass.cpp), its stream keyed by pixel and index.
    rngState = pcgHash(pcgHash(uint(pixel.y * imageSize.x + pixel.x) ^ 0x6a09e667u) ^ pcgHash(sampleIndex));
    imageStore(accumulation, pixel, imageLoad(accumulation, pixel) + path(ray.origin, ray.direction, span.x, span.y));
}
