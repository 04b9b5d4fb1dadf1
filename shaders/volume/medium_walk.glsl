// Delta tracking through a volume's medium in model space, shared by the path tracer
// (path_trace.comp) and the fluence cache's photons (fluence_photons.comp): random numbers, the
// field in float (trilinear or cubic, as volume/reconstruction.glsl), extinction from the
// transfer function, the Henyey-Greenstein phase function, and a walk along a ray brick by
// brick against each brick's majorant.
// Needs volume/transfer_function.glsl, volume/clip.glsl and common/ray_box.glsl included first.

uniform sampler3D majorants;  // per brick: an upper bound of sigma_t in it (per model unit)
uniform vec3 boxMin;
uniform vec3 boxMax;
uniform vec3 cellSize;        // one brick, model units
uniform float voxelLength;    // the opacity reference length D
uniform float phaseG;

const float kPi = 3.14159265;
const float kMaxOpticalDepthPerVoxel = 30.0;
const float kFar = 3.0e38;

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

// The volume's trilinear field at p, as GL_LINEAR with clamp-to-edge defines it (texel centres
// at (i + 0.5) / n) and as the CPU reference computes it, but with float weights: llvmpipe
// filters 8-bit textures in 8-bit fixed point, and the rounded samples made the engine data
// set's multiple scattering 3 % too bright (measured at 512 paths per pixel: mean ratio
// 1.028 / 1.026 / 1.011 with texture(), 1.000 for the same field in a 16-bit texture).
#if !CUBIC_RECONSTRUCTION
float sampleVolume(vec3 p) {
    ivec3 dims = textureSize(volumeTexture, 0);
    vec3 x = (p - boxMin) / (boxMax - boxMin) * vec3(dims) - 0.5;
    vec3 lo = floor(x);
    vec3 w = x - lo;
    ivec3 i0 = clamp(ivec3(lo), ivec3(0), dims - 1);
    ivec3 i1 = clamp(ivec3(lo) + 1, ivec3(0), dims - 1);
    float c000 = texelFetch(volumeTexture, i0, 0).r;
    float c100 = texelFetch(volumeTexture, ivec3(i1.x, i0.y, i0.z), 0).r;
    float c010 = texelFetch(volumeTexture, ivec3(i0.x, i1.y, i0.z), 0).r;
    float c110 = texelFetch(volumeTexture, ivec3(i1.x, i1.y, i0.z), 0).r;
    float c001 = texelFetch(volumeTexture, ivec3(i0.x, i0.y, i1.z), 0).r;
    float c101 = texelFetch(volumeTexture, ivec3(i1.x, i0.y, i1.z), 0).r;
    float c011 = texelFetch(volumeTexture, ivec3(i0.x, i1.y, i1.z), 0).r;
    float c111 = texelFetch(volumeTexture, i1, 0).r;
    float c00 = mix(c000, c100, w.x), c10 = mix(c010, c110, w.x);
    float c01 = mix(c001, c101, w.x), c11 = mix(c011, c111, w.x);
    return mix(mix(c00, c10, w.y), mix(c01, c11, w.y), w.z);
}
#else
// The cubic B-spline of the 4^3 voxels around p, with float weights for the same reason.
float sampleVolume(vec3 p) {
    ivec3 dims = textureSize(volumeTexture, 0);
    vec3 x = (p - boxMin) / (boxMax - boxMin) * vec3(dims) - 0.5;
    vec3 lo = floor(x);
    vec3 f = x - lo;
    vec3 f2 = f * f;
    vec3 f3 = f2 * f;
    vec3 w[4];
    w[0] = (1.0 - 3.0 * f + 3.0 * f2 - f3) * (1.0 / 6.0);
    w[1] = (4.0 - 6.0 * f2 + 3.0 * f3) * (1.0 / 6.0);
    w[3] = f3 * (1.0 / 6.0);
    w[2] = 1.0 - w[0] - w[1] - w[3];
    ivec3 first = ivec3(clamp(lo, vec3(-4.0), vec3(dims) + 4.0)) - 1;
    float sum = 0.0;
    for (int k = 0; k < 4; ++k) {
        float plane = 0.0;
        for (int j = 0; j < 4; ++j) {
            float row = 0.0;
            for (int i = 0; i < 4; ++i) {
                ivec3 v = clamp(first + ivec3(i, j, k), ivec3(0), dims - 1);
                row += w[i].x * texelFetch(volumeTexture, v, 0).r;
            }
            plane += w[j].y * row;
        }
        sum += w[k].z * plane;
    }
    return sum;
}
#endif

// sigma_t (per model unit) of a TF opacity per voxel, capped (sss::kMaxOpticalDepthPerVoxel).
float extinctionOf(float alpha) {
    float depth = alpha >= 1.0 ? kMaxOpticalDepthPerVoxel : min(-log(1.0 - alpha), kMaxOpticalDepthPerVoxel);
    return depth / voxelLength;
}

// sigma_t at p, clamped to the majorant so that float rounding in the filtering can never
// exceed it.
float extinction(vec3 p, float majorant, out vec4 tf) {
    // Camera segments are clipped to the kept region (cameraSegment); the cut matter stays for
    // the light only if it casts shadows.
    tf = lightSeesMedium((p - boxMin) / (boxMax - boxMin)) ? classify(sampleVolume(p)) : vec4(0.0);
    return min(extinctionOf(tf.a), majorant);
}

// sigma_t at the centre of voxel v (as the light sees it): the weight the fluence cache averages
// its cells' fluence with (fluence_photons.comp, fluence_density.comp).
float voxelExtinction(ivec3 v) {
    vec3 tc = (vec3(v) + 0.5) / vec3(textureSize(volumeTexture, 0));
    return lightSeesMedium(tc) ? extinctionOf(classify(texelFetch(volumeTexture, v, 0).r).a) : 0.0;
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


// The current walk: origin + t dir, t up to tEnd, through brick `cell`, where the next brick
// boundary on each axis is at tNext; tau is the optical depth left to the next tentative
// collision (delta tracking).
vec3 origin;
vec3 walkDirection;
float t;
float tEnd;
ivec3 cell;
vec3 tNext;
float majorant;
float tau;


// Brick boundaries are always derived from the brick and the walk's origin (never stepped
// incrementally), so a walk resumed in a later dispatch computes exactly what it would have.
void enterCell() {
    vec3 lo = boxMin + vec3(cell) * cellSize;
    vec3 boundary = mix(lo, lo + cellSize, greaterThan(walkDirection, vec3(0.0)));
    vec3 crossing = (boundary - origin) * safeInverse(walkDirection);
    tNext = mix(crossing, vec3(kFar), equal(walkDirection, vec3(0.0)));
    majorant = texelFetch(majorants, cell, 0).r;
}

void startWalk(vec3 o, vec3 d, float t0, float t1) {
    origin = o;
    walkDirection = d;
    t = t0;
    tEnd = t1;
    ivec3 cells = textureSize(majorants, 0);
    cell = clamp(ivec3(floor((o + t0 * d - boxMin) / cellSize)), ivec3(0), cells - 1);
    enterCell();
    tau = exponential();
}

int nextAxis(vec3 v) { return v.x < v.y ? (v.x < v.z ? 0 : 2) : (v.y < v.z ? 1 : 2); }
