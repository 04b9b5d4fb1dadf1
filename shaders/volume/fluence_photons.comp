// The multiple-scattering cache's photons (volume/fluence_cache.h): paths from the lights through
// the medium, in model space, by the path tracer's delta tracking and Henyey-Greenstein
// scattering. Once a photon has scattered, every tentative collision at p adds w s(p) / majorant
// to the cell p lies in, s being sigma_t at the centre of p's voxel: the collision estimator of
// the integral of s times the track length, so that the cell's fluence comes out averaged with
// the weight s, where the medium scatters (fluence_density.comp gives the integral of s). Per
// channel for the fluence, times the direction of travel for each channel's flux vector, and,
// for the mean channel, times the traceless square of the direction (the second moment).
// Light that has not scattered yet is the light volume's, and is left out.
//
// The sums are 64-bit two's-complement fixed point in pairs of uints (low word, high word), added
// with integer atomics and stochastic rounding: unbiased, and the same sums whatever the order of
// the adds, so a cache does not depend on how the GPU schedules its photons. Slots per cell:
// fluence r, g, b, then the flux vector of r, of g and of b (x, y, z each), then the mean
// channel's second moment xx - 1/3, yy - 1/3, xy, xz, yz, then the fluence of light scattered
// once (r, g, b) and the same times the direct light E at the voxel (r, g, b): the moments of
// the once-scattered fluence's regression on E (fluence_resolve.comp).
//
// Photons are resumable, as the path tracer's paths (path_trace.comp says why): a dispatch
// spends at most `stepsPerDispatch` units per invocation and keeps each photon's state in
// `photons`; the host dispatches until no invocation reports unfinished work.
#include "common/ray_box.glsl"
#include "volume/transfer_function.glsl"
#include "volume/clip.glsl"
#include "common/spot_cone.glsl"
#include "volume/medium_walk.glsl"
uniform mat4 modelToWorld;
#include "volume/direct_light.glsl"

layout(local_size_x = 64) in;

uniform int invocations;             // photon slots in this run
uniform uint photonsPerInvocation;   // photons each slot traces in this run
uniform uint firstPhoton;            // index of this run's first photon (keys the random streams)
uniform int restart;                 // 1: each slot starts its photons; 0: resume `photons`
uniform int stepsPerDispatch;
uniform int maxBounces;
uniform ivec3 cacheCells;
uniform float depositScale;          // fixed-point quanta per unit of w s / majorant
uniform vec3 boxCentre;              // the box's bounding sphere, model space
uniform float boxRadius;
uniform int lightCount;
uniform vec4 lightModel[MAX_LIGHTS];        // w 0: unit direction towards the light; w 1: position
uniform vec3 lightWeight[MAX_LIGHTS];       // a photon's starting weight (rgb, largest channel 1)
uniform float lightPick[MAX_LIGHTS];        // cumulative probability of emitting from each light
uniform float lightConeCosine[MAX_LIGHTS];  // point lights: cone of directions that can reach the box
uniform vec3 lightSpotAxis[MAX_LIGHTS];     // world space, as path_trace.comp
uniform vec2 lightSpotCosines[MAX_LIGHTS];
uniform int lightShadowLayer[MAX_LIGHTS];    // the renderer's index of each light (its mesh shadow map)

const int kRouletteStartBounce = 3;  // as the path tracer
const uint kMaxStepsPerPhoton = 1u << 24;
const int kWalkStepsPerEvent = 16;

// std430: 80 bytes.
struct PhotonState {
    vec4 throughput;  // rgb: weight; a: tau
    vec4 origin;      // xyz: the walk's origin; w: t
    vec4 direction;   // xyz: direction of travel; w: the walk's end
    ivec4 cell;       // xyz: brick; w: stage + kStages x the light it left
    uvec4 counters;   // x: random state; y: scatterings so far; z: photons left; w: steps
};
layout(std430, binding = 0) buffer Photons { PhotonState photons[]; };
layout(std430, binding = 1) buffer Status {
    uint unfinished;
    uint abandoned;
} status;
#define SUMS_WRITABLE
#include "volume/fluence_sums.glsl"

const int kStageDone = 0;
const int kStageTrack = 1;
const int kStageScatter = 2;
const int kStageFinished = 3;
const int kStages = 4;

int stage;
int photonLight;  // the layer of the light it left: meshes block its way to the first scattering
vec3 throughput;
int bounce;
uint photonsLeft;
uint photonSteps;

// Adds `quanta` (either sign) to a slot's 64-bit two's-complement sum: rounded stochastically
// (unbiased), the low word added atomically, and its carry with the high word.
void addFixed(SumsSlot slot, float quanta) {
    int v = int(floor(quanta + uniform01()));
    if (v == 0) return;
    uint low = uint(v);
    uint old = sumsAdd(slot, 0u, low);
    uint high = (v < 0 ? 0xffffffffu : 0u) + (old + low < old ? 1u : 0u);  // sign extension + carry
    if (high != 0u) sumsAdd(slot, 1u, high);
}

// The last deposit's voxel, its sigma_t and its direct light (negative: not read yet). Successive
// tentative collisions often fall in one voxel, where a majorant is far above most of its brick:
// reading each once took a photon on the bonsai from 11 to 7 microseconds on llvmpipe.
ivec3 lastVoxel = ivec3(-1);
float lastVoxelExtinction = 0.0;
float lastVoxelDirect = -1.0;

void deposit(vec3 p) {
    vec3 tc = (p - boxMin) / (boxMax - boxMin);
    ivec3 dims = textureSize(volumeTexture, 0);
    ivec3 voxel = clamp(ivec3(tc * vec3(dims)), ivec3(0), dims - 1);
    if (voxel != lastVoxel) {
        lastVoxel = voxel;
        lastVoxelExtinction = voxelExtinction(voxel);
        lastVoxelDirect = -1.0;
    }
    float weight = lastVoxelExtinction / majorant;
    if (!(weight > 0.0)) return;
    ivec3 c = clamp(ivec3(tc * vec3(cacheCells)), ivec3(0), cacheCells - 1);
    SumsSlot base = sumsOfCell(uint((c.z * cacheCells.y + c.y) * cacheCells.x + c.x));
    vec3 q = throughput * (weight * depositScale);
    for (int channel = 0; channel < 3; ++channel) {
        addFixed(nextSlot(base, uint(channel)), q[channel]);
        for (int axis = 0; axis < 3; ++axis)
            addFixed(nextSlot(base, uint(3 + 3 * channel + axis)), q[channel] * walkDirection[axis]);
    }
    vec3 d = walkDirection;
    float mean = (q.r + q.g + q.b) / 3.0;
    addFixed(nextSlot(base, 12u), mean * (d.x * d.x - 1.0 / 3.0));
    addFixed(nextSlot(base, 13u), mean * (d.y * d.y - 1.0 / 3.0));
    addFixed(nextSlot(base, 14u), mean * d.x * d.y);
    addFixed(nextSlot(base, 15u), mean * d.x * d.z);
    addFixed(nextSlot(base, 16u), mean * d.y * d.z);
    if (bounce == 1) {
        // Light scattered once, and the same times the direct light at the voxel's centre (the
        // density pass's moments take E there too).
        if (lastVoxelDirect < 0.0) lastVoxelDirect = directLightAtVoxel(voxel, dims);
        float direct = lastVoxelDirect;
        for (int channel = 0; channel < 3; ++channel) {
            addFixed(nextSlot(base, uint(17 + channel)), q[channel]);
            addFixed(nextSlot(base, uint(20 + channel)), q[channel] * direct);
        }
    }
}

// One tentative collision or brick crossing of the photon's walk.
void walkStep() {
    int a = nextAxis(tNext);
    float tb = min(tNext[a], tEnd);
    if (tb > t && majorant > 0.0 && tau < majorant * (tb - t)) {
        t += tau / majorant;
        vec3 p = origin + t * walkDirection;
        if (bounce == 0 && meshVisibility(photonLight, (modelToWorld * vec4(p, 1.0)).xyz) == 0.0) {
            stage = kStageFinished;  // a mesh took it before it got here (and it deposits nothing yet)
            return;
        }
        vec4 tf;
        float sigma = extinction(p, majorant, tf);
        if (bounce > 0) deposit(p);
        if (uniform01() * majorant < sigma) {
            origin = p;
            throughput *= clamp(tf.rgb, 0.0, 1.0);
            stage = kStageScatter;
        }
        tau = exponential();
    } else {
        if (tb > t && majorant > 0.0) tau = max(0.0, tau - majorant * (tb - t));
        t = max(t, tb);
        int next = cell[a] + int(sign(walkDirection[a]));
        if (tNext[a] >= tEnd || next < 0 || next >= textureSize(majorants, 0)[a]) {
            stage = kStageFinished;  // left the box
        } else {
            cell[a] = next;
            enterCell();
        }
    }
}

// A unit vector and two more completing an orthonormal basis (Duff et al. 2017).
void basisAround(vec3 d, out vec3 t1, out vec3 t2) {
    float sgn = d.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (sgn + d.z);
    float b = d.x * d.y * a;
    t1 = vec3(1.0 + sgn * d.x * d.x * a, sgn * b, -sgn * d.x);
    t2 = vec3(b, sgn + d.y * d.y * a, -d.y);
}

// Emits from light i: a directional light's beam through a disk covering the box, a point
// light's directions within the cone that can reach the box (its weight times the spot cone).
void emit(int i, out vec3 o, out vec3 d) {
    vec3 t1, t2;
    float u1 = uniform01(), u2 = uniform01();
    if (lightModel[i].w == 0.0) {
        vec3 l = lightModel[i].xyz;
        basisAround(l, t1, t2);
        float r = boxRadius * sqrt(u1), phi = 2.0 * kPi * u2;
        o = boxCentre + 2.0 * boxRadius * l + r * (cos(phi) * t1 + sin(phi) * t2);
        d = -l;
        return;
    }
    o = lightModel[i].xyz;
    vec3 axis = boxCentre - o;
    float axisLength = length(axis);
    axis = axisLength > 0.0 ? axis / axisLength : vec3(0.0, 0.0, 1.0);
    basisAround(axis, t1, t2);
    float cosT = 1.0 - u1 * (1.0 - lightConeCosine[i]);
    float sinT = sqrt(max(0.0, 1.0 - cosT * cosT)), phi = 2.0 * kPi * u2;
    d = normalize(cosT * axis + sinT * (cos(phi) * t1 + sin(phi) * t2));
    float cosAxis = dot(normalize(mat3(modelToWorld) * d), lightSpotAxis[i]);
    throughput *= spotConeFactor(lightSpotCosines[i], cosAxis);
}

void startPhoton(uint slot) {
    if (photonsLeft == 0u) {
        stage = kStageDone;
        return;
    }
    uint index = firstPhoton + slot * photonsPerInvocation + (photonsPerInvocation - photonsLeft);
    rngState = pcgHash(pcgHash(index ^ 0x510e527fu) ^ 0x9b05688cu);
    float u = uniform01();
    int i = 0;
    while (i + 1 < lightCount && u >= lightPick[i]) ++i;
    photonLight = lightShadowLayer[i];
    throughput = lightWeight[i];
    bounce = 0;
    photonSteps = 0u;
    vec3 o, d;
    emit(i, o, d);
    float t0 = 0.0, t1 = kFar;
    if (!(max(max(throughput.r, throughput.g), throughput.b) > 0.0) || !clipToBox(o, d, t0, t1)) {
        stage = kStageFinished;  // misses the box (counted all the same: the estimate stays unbiased)
        return;
    }
    stage = kStageTrack;
    startWalk(o, d, t0, t1);
}

// At a real collision: the photon scatters for the (bounce + 1)-th time, if the cache holds
// that order (maxBounces scatterings in all, the last one the eye's), after Russian roulette.
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
    vec3 d = scatterHG(walkDirection);
    float t0 = 0.0, t1 = kFar;
    if (!clipToBox(origin, d, t0, t1)) {
        stage = kStageFinished;
        return;
    }
    stage = kStageTrack;
    startWalk(origin, d, t0, t1);
}

void load(uint i) {
    PhotonState s = photons[i];
    throughput = s.throughput.rgb;
    tau = s.throughput.a;
    origin = s.origin.xyz;
    t = s.origin.w;
    walkDirection = s.direction.xyz;
    tEnd = s.direction.w;
    cell = s.cell.xyz;
    stage = s.cell.w % kStages;
    photonLight = s.cell.w / kStages;
    rngState = s.counters.x;
    bounce = int(s.counters.y);
    photonsLeft = s.counters.z;
    photonSteps = s.counters.w;
    if (stage == kStageTrack) enterCell();
}

void store(uint i) {
    photons[i] = PhotonState(vec4(throughput, tau), vec4(origin, t), vec4(walkDirection, tEnd),
                             ivec4(cell, stage + kStages * photonLight),
                             uvec4(rngState, uint(bounce), photonsLeft, photonSteps));
}

void main() {
    uint slot = gl_GlobalInvocationID.x;
    if (slot >= uint(invocations)) return;
    if (restart != 0) {
        photonsLeft = photonsPerInvocation;
        startPhoton(slot);
    } else {
        if (photons[slot].cell.w % kStages == kStageDone) return;
        load(slot);
    }
    int budget = stepsPerDispatch;
    while (budget > 0 && stage != kStageDone) {
        --budget;
        ++photonSteps;
        for (int w = 0; w < kWalkStepsPerEvent && budget > 0 && photonSteps < kMaxStepsPerPhoton && stage == kStageTrack;
             ++w) {
            --budget;
            ++photonSteps;
            walkStep();
        }
        if (photonSteps >= kMaxStepsPerPhoton && stage != kStageFinished) {
            atomicAdd(status.abandoned, 1u);
            stage = kStageFinished;
        }
        if (stage == kStageScatter) scatter();
        if (stage == kStageFinished) {
            --photonsLeft;
            startPhoton(slot);
        }
    }
    store(slot);
    if (stage != kStageDone) atomicAdd(status.unfinished, 1u);
}
