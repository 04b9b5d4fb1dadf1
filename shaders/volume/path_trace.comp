// Progressive volume path tracing (sss::VolumeRenderOptions::multipleScattering): per pixel, a
// run of paths from the eye, each adding (radiance, hit) to the running sums in `accumulation`.
// The estimator is renderVolumePathTraced()'s (sss/volume_path_tracer.h), in float: delta
// tracking against a majorant per brick, next-event estimation to every light with ratio
// tracking, HG scattering, Russian roulette on the throughput. All transport is in the volume's
// model space.
//
// Paths are resumable. llvmpipe gives a shader invocation 65535 loop iterations in all (over
// every loop it runs, counted once per SIMD vector of invocations) and then leaves its loops
// early, silently cutting paths short (512 paths in one invocation lost 28 % of the light). So,
// whatever a path's length, a dispatch spends at most `stepsPerDispatch` units per
// invocation: one per iteration of the walk loop (a tentative collision or a move to the next
// brick, with no loop inside) and one per iteration of the event loop around it (a collision's
// next-event set-up, a shadow ray's end, a path's end). Each loop iteration of a vector spends a
// unit of at least one of its lanes, so a vector of L lanes runs at most L * stepsPerDispatch
// iterations (8 * 1024 by default). A path's whole state (`PathState` below) lives in `paths`
// between dispatches; the host dispatches until no invocation reports unfinished work.
// llvmpipe runs both sides of every branch (masked), so the walk loop holds only what every
// step needs, and the rarer events wait for the event loop.
//
// Contract with volume/path_trace_pass.cpp:
//   A dispatch covers the band of rows [bandFirstRow, bandFirstRow + bandRows); `paths` holds
//   one state per pixel of the band.
//   restart != 0: the pixel starts `pathsPerPixel` new paths, numbered from `firstSample`
//                 (the band's first dispatch in an accumulate()); otherwise it resumes `paths`.
//   status.unfinished counts the invocations that still hold work after this dispatch;
//   status.abandoned counts paths given up after kMaxStepsPerPath steps (a degenerate ray).
#include "volume/ray_setup.glsl"
#include "volume/transfer_function.glsl"
#include "volume/clip.glsl"
#include "common/spot_cone.glsl"
#include "volume/medium_walk.glsl"
#include "volume/mesh_visibility.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(rgba32f, binding = 0) uniform image2D accumulation;  // sums of (rgb value, hit)
uniform sampler2D sceneDepth;      // rays end at opaque geometry already in the target
uniform ivec2 imageSize;
uniform int maxBounces;
uniform mat4 modelToWorld;
uniform int lightCount;
uniform vec4 lightModel[MAX_LIGHTS];          // w 0: unit direction towards the light; w 1: position
uniform vec3 lightWorldPosition[MAX_LIGHTS];  // point lights: falloff is in world units
uniform vec3 lightRadiance[MAX_LIGHTS];       // colour * intensity
uniform vec3 lightSpotAxis[MAX_LIGHTS];       // spot lights: world-space unit cone axis (as in lights.glsl)
uniform vec2 lightSpotCosines[MAX_LIGHTS];    // spot lights: (cos outer, cos inner); (-2, -2): no cone
uniform int lightShadowLayer[MAX_LIGHTS];     // the renderer's index of each light (its mesh shadow map)
uniform int bandFirstRow;          // this dispatch covers rows [bandFirstRow, bandFirstRow + bandRows)
uniform int bandRows;
uniform int restart;
uniform uint firstSample;          // index of the first path of this run in the pixel's running mean
uniform uint pathsPerPixel;        // paths per pixel in this run
uniform int stepsPerDispatch;      // the loop bound, far below llvmpipe's 65535

const float kRatioRoulette = 0.125;  // ratio tracking is rouletted below this transmittance
const int kRouletteStartBounce = 3;  // as VolumePathTracerOptions::rouletteStartBounce
// A path that has taken this many steps is given up and counted (status.abandoned): only a
// degenerate ray gets there (engine paths take a few hundred on average).
const uint kMaxStepsPerPath = 1u << 24;
// The walk loop hands over to the event loop after this many steps. Measured on the engine
// (48 paths per pixel, llvmpipe, process CPU time): 6.4 s at 16, 6.9 s at 64, 9.3 s without a
// bound (lanes wait for the longest walk of their vector); 4 was slower than 16 as well.
const int kWalkStepsPerEvent = 16;

// What a pixel's path needs to go on in the next dispatch (std430: 112 bytes).
struct PathState {
    vec4 value;        // rgb: radiance so far; a: 1 once the camera ray had a real collision
    vec4 throughput;   // rgb: path throughput (the last albedo included); a: tau, optical depth left
    vec4 origin;       // xyz: the walk's origin (the camera or the last collision); w: its position t
    vec4 direction;    // xyz: the path's direction; w: the walk's end t1
    ivec4 cell;        // xyz: the walk's brick; w: the stage
    uvec4 counters;    // x: random state; y: bounce; z: light of the shadow ray; w: paths left
    vec4 shadow;       // x: ratio tracking's transmittance; y: steps of this path (uint bits)
};
layout(std430, binding = 0) buffer Paths { PathState paths[]; };
layout(std430, binding = 1) buffer Status {
    uint unfinished;
    uint abandoned;
} status;

// ---- The path's state, as locals while a dispatch runs ----
const int kStageDone = 0;       // no path left in this run
const int kStageTrack = 1;      // walk: delta tracking along the path's direction
const int kStageShadow = 2;     // walk: ratio tracking towards light `light`
const int kStageLight = 3;      // event: start the shadow ray to light `light` (or scatter)
const int kStageShadowEnd = 4;  // event: add light `light`'s next-event term
const int kStageFinished = 5;   // event: add the path to the sums, start the next

int stage;
vec3 value;
float hit;
vec3 throughput;
int bounce;
int light;           // which light's shadow ray (kStageLight, kStageShadow, kStageShadowEnd)
uint pathsLeft;      // paths of this run not added to the sums yet, the current one included
uint pathSteps;      // units this path has spent
vec3 pathDirection;  // the direction the path travels (and arrived at `origin` along, in NEE)
float tr;            // ratio tracking's transmittance so far
// One step of the current walk (kStageTrack or kStageShadow): the next tentative collision if
// it lies in this brick, else the move to the next brick. Delta tracking carries the optical
// depth left over into the next brick; ratio tracking restarts in each (as the CPU's; the
// tentative collisions are a memoryless Poisson process, so both are exact).
void walkStep() {
    bool shadow = stage == kStageShadow;
    int a = nextAxis(tNext);
    float tb = min(tNext[a], tEnd);
    if (tb > t && majorant > 0.0 && tau < majorant * (tb - t)) {
        t += tau / majorant;
        vec4 tf;
        float sigma = extinction(origin + t * walkDirection, majorant, tf);
        float u = uniform01();
        if (!shadow) {
            if (u * majorant < sigma) {  // a real collision
                hit = 1.0;
                origin += t * walkDirection;
                // The albedo joins the throughput now: the next-event terms use it as the CPU's
                // throughput * albedo does, and a black medium needs no shadow rays.
                throughput *= clamp(tf.rgb, 0.0, 1.0);
                light = 0;
                stage = max(max(throughput.r, throughput.g), throughput.b) > 0.0 ? kStageLight : kStageFinished;
            }
        } else {
            tr *= max(0.0, 1.0 - sigma / majorant);
            if (tr < kRatioRoulette) {
                if (u * kRatioRoulette >= tr) {
                    tr = 0.0;
                    stage = kStageShadowEnd;
                } else {
                    tr = kRatioRoulette;
                }
            }
        }
        tau = exponential();
    } else {
        if (tb > t && majorant > 0.0) tau = shadow ? exponential() : max(0.0, tau - majorant * (tb - t));
        t = max(t, tb);
        int next = cell[a] + int(sign(walkDirection[a]));
        if (tNext[a] >= tEnd || next < 0 || next >= textureSize(majorants, 0)[a]) {
            stage = shadow ? kStageShadowEnd : kStageFinished;  // the walk's end, or the box's
        } else {
            cell[a] = next;
            enterCell();
        }
    }
}

// The camera ray through the pixel centre, clipped to the box and to the scene's depth.
bool cameraSegment(ivec2 pixel, out vec3 o, out vec3 d, out float t0, out float t1) {
    vec2 ndc = (vec2(pixel) + 0.5) / vec2(imageSize) * 2.0 - 1.0;
    Ray ray = pixelRay(ndc);
    vec2 span = intersectBox(ray, boxMin, boxMax);
    span = clipSpan((ray.origin - boxMin) / (boxMax - boxMin), ray.direction / (boxMax - boxMin), span);
    float depth = texelFetch(sceneDepth, pixel, 0).r;
    if (depth < 1.0) {
        vec4 hitWorld = inverseViewProjection * vec4(ndc, depth * 2.0 - 1.0, 1.0);
        vec3 hitModel = (worldToModel * vec4(hitWorld.xyz / hitWorld.w, 1.0)).xyz;
        span.y = min(span.y, dot(hitModel - ray.origin, ray.direction));
    }
    o = ray.origin;
    d = ray.direction;
    t0 = span.x;
    t1 = span.y;
    return span.x < span.y;
}

// Starts the next path of the run, its random stream keyed by pixel and sample index (so the
// sums do not depend on how the work is split into dispatches).
void startPath(ivec2 pixel) {
    vec3 o, d;
    float t0, t1;
    if (pathsLeft == 0u || !cameraSegment(pixel, o, d, t0, t1)) {
        stage = kStageDone;  // the background, exactly: the composite adds nothing
        pathsLeft = 0u;
        return;
    }
    uint sampleIndex = firstSample + (pathsPerPixel - pathsLeft);
    rngState = pcgHash(pcgHash(uint(pixel.y * imageSize.x + pixel.x) ^ 0x6a09e667u) ^ pcgHash(sampleIndex));
    value = vec3(0.0);
    hit = 0.0;
    throughput = vec3(1.0);
    bounce = 0;
    pathSteps = 0u;
    pathDirection = d;
    stage = kStageTrack;
    startWalk(o, d, t0, t1);
}

// Light `light` seen from `origin`: its direction, distance and radiance there.
void lightGeometry(out vec3 l, out float distance, out vec3 radiance) {
    l = lightModel[light].xyz;
    radiance = lightRadiance[light];
    distance = kFar;
    if (lightModel[light].w != 0.0) {
        vec3 toLight = lightModel[light].xyz - origin;
        distance = length(toLight);
        vec3 toLightWorld = lightWorldPosition[light] - (modelToWorld * vec4(origin, 1.0)).xyz;
        float distanceSquared = max(dot(toLightWorld, toLightWorld), 1e-8);
        float cosAxis = -dot(toLightWorld, lightSpotAxis[light]) * inversesqrt(distanceSquared);
        radiance = radiance / distanceSquared * spotConeFactor(lightSpotCosines[light], cosAxis);
        l = toLight / distance;
    }
}

// Light `light`'s next-event term, p_HG(l . d) E T_l, times the throughput (albedo included).
void addNextEvent(float transmittance) {
    vec3 l, radiance;
    float distance;
    lightGeometry(l, distance, radiance);
    if (transmittance > 0.0) value += throughput * phaseHG(dot(l, pathDirection)) * radiance * transmittance;
}

// After the last next-event term at a collision: roulette, scattering, the next walk.
void scatter() {
    float q = max(max(throughput.r, throughput.g), throughput.b);
    if (!(q > 0.0) || bounce + 1 >= maxBounces) {
        stage = kStageFinished;
        return;
    }
    if (bounce + 1 >= kRouletteStartBounce && q < 1.0) {
        if (uniform01() >= q) {
            stage = kStageFinished;
            return;
        }
        throughput /= q;
    }
    ++bounce;
    pathDirection = scatterHG(pathDirection);
    float t0 = 0.0, t1 = kFar;
    if (!clipToBox(origin, pathDirection, t0, t1)) {
        stage = kStageFinished;  // on a face, leaving
        return;
    }
    stage = kStageTrack;
    startWalk(origin, pathDirection, t0, t1);
}

// Light `light`'s shadow ray, or scattering after the last light. A light with no direction
// (the path is at it) adds nothing, and a ray that misses the box adds its term at once; both
// leave the stage at kStageLight for the next light.
void nextLight() {
    if (light >= lightCount) {
        scatter();
        return;
    }
    vec3 l, radiance;
    float distance;
    lightGeometry(l, distance, radiance);
    float t0 = 0.0, t1 = distance;
    if (!(distance > 0.0)) {
        ++light;  // at the light: no direction (measure zero), as the CPU
    } else if (meshVisibility(lightShadowLayer[light], (modelToWorld * vec4(origin, 1.0)).xyz) == 0.0) {
        ++light;  // a mesh of the hybrid scene blocks it
    } else if (!clipToBox(origin, l, t0, t1)) {
        addNextEvent(1.0);
        ++light;
    } else {
        stage = kStageShadow;
        tr = 1.0;
        startWalk(origin, l, 0.0, t1);  // from the collision, as the CPU's transmittance()
    }
}

void load(uint i) {
    PathState s = paths[i];
    value = s.value.rgb;
    hit = s.value.a;
    throughput = s.throughput.rgb;
    tau = s.throughput.a;
    origin = s.origin.xyz;
    t = s.origin.w;
    pathDirection = s.direction.xyz;
    tEnd = s.direction.w;
    cell = s.cell.xyz;
    stage = s.cell.w;
    rngState = s.counters.x;
    bounce = int(s.counters.y);
    light = int(s.counters.z);
    pathsLeft = s.counters.w;
    tr = s.shadow.x;
    pathSteps = floatBitsToUint(s.shadow.y);
    // What the walk derives from the stored state, computed as when it started.
    walkDirection = pathDirection;
    if (stage == kStageShadow) {
        vec3 radiance;
        float distance;
        lightGeometry(walkDirection, distance, radiance);
    }
    if (stage == kStageTrack || stage == kStageShadow) enterCell();
}

void store(uint i) {
    paths[i] = PathState(vec4(value, hit), vec4(throughput, tau), vec4(origin, t), vec4(pathDirection, tEnd),
                         ivec4(cell, stage), uvec4(rngState, uint(bounce), uint(light), pathsLeft),
                         vec4(tr, uintBitsToFloat(pathSteps), 0.0, 0.0));
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy) + ivec2(0, bandFirstRow);
    if (pixel.x >= imageSize.x || pixel.y >= min(imageSize.y, bandFirstRow + bandRows)) return;
    uint index = uint((pixel.y - bandFirstRow) * imageSize.x + pixel.x);  // in the band's states
    if (restart != 0) {
        pathsLeft = pathsPerPixel;
        startPath(pixel);
    } else {
        if (paths[index].cell.w == kStageDone) return;
        load(index);
    }
    int budget = stepsPerDispatch;
    // The event loop: each iteration spends one unit, then walks, then handles what the walk
    // ended with. Events come in this order so that one iteration can take a path from a
    // shadow ray's end through scattering, or from its end to the next path's first walk.
    while (budget > 0 && stage != kStageDone) {
        --budget;
        ++pathSteps;
        // The walk loop: the hot path, one tentative collision or brick per iteration. It stops
        // after kWalkStepsPerEvent iterations, so that lanes whose walks ended wait at most that
        // long for their events while other lanes of their SIMD vector walk on.
        for (int w = 0; w < kWalkStepsPerEvent && budget > 0 && pathSteps < kMaxStepsPerPath &&
                        (stage == kStageTrack || stage == kStageShadow);
             ++w) {
            --budget;
            ++pathSteps;
            walkStep();
        }
        if (pathSteps >= kMaxStepsPerPath && stage != kStageFinished) {
            atomicAdd(status.abandoned, 1u);  // a degenerate ray: given up, and counted
            stage = kStageFinished;
        }
        if (stage == kStageShadowEnd) {
            addNextEvent(tr);
            ++light;
            stage = kStageLight;
        }
        if (stage == kStageLight) nextLight();
        if (stage == kStageFinished) {
            // Each path adds to the sums on its own, in sample order: the sums do not depend on
            // where dispatches split the work.
            imageStore(accumulation, pixel, imageLoad(accumulation, pixel) + vec4(value, hit));
            --pathsLeft;
            startPath(pixel);
        }
    }
    store(index);
    if (stage != kStageDone) atomicAdd(status.unfinished, 1u);
}
