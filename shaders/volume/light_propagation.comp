// The light-volume propagation (Ropinski, Doering, Rezk-Salama 2010).
// The volume is swept slice by slice along "sweep" frames (u, v across a slice, w along the
// sweep), each a permutation/flip of the data axes chosen by src/volume/light_volume_pass.cpp
// so the light always travels towards +w. A light's sweeps (two blended ones, or six from a light
// inside) advance together: workgroup z is the sweep. For each voxel of slice w:
//   - the light arriving there is looked up where the light ray through the voxel crosses slice
//     w-1: (c, l) by a clamped Catmull-Rom lookup (sharp shadows), then chromaticity c
//     gathered over a cone whose aperture follows the Henyey-Greenstein g;
//   - along the ray across the voxel's slab the medium is sampled at data resolution, and each
//     piece changes the light as c' = (1-a) c + a rgb, l' = (1-a) l, with the TF opacity a
//     corrected for the piece's length;
//   - the (c, l) at the voxel centre, after the first half of the slab, is stored in the light
//     volume (the light volume samples light at points, like the CPU reference), and the light
//     leaving the slab goes to the next slice.
// Outside the volume the light is unattenuated white: (1, 1, 1, 1).
//
// SLAB 0: one slice per dispatch, the lookups read from the slice texture. SLAB 1, several
// slices per dispatch (docs/light-volume-sweep.md): each workgroup owns a TILE x TILE square of
// its sweep's slices and advances it `slabSlices` slices through shared memory. A slice's
// lookups reach at most `slabHalo` texels beyond the voxel (bounded on the CPU), so the
// workgroup first loads the previous slice over the tile and slices x halo texels around it,
// then computes each slice over a square that shrinks by the halo per slice, down to the tile
// itself. The margins are computed twice, by neighbouring workgroups; in exchange a light costs
// a few dispatches instead of one per slice (each a GPU-wide wait), and the cone's taps read
// shared memory. Shared memory and the slice texture hold the same half floats, rounded alike,
// and both variants weight the centre lookup's taps in the shader, so any number of slices per
// dispatch gives the same intensity l texel for texel; SLAB 0's cone taps are filtered by the
// texture unit.
//
// EYE_PASS 1 (the optional second pass, towards the viewer): the same sweep carries the light the
// voxels scatter (litColour, from lit_colour.comp) instead of the TF colour, starting from no
// light (outsideLight (0, 0, 0, 1)), so rgb becomes the cone-blurred light scattered towards the
// eye from behind each voxel.
//
// CHROMATICITY 0 (readers that use l alone: the physical model's grey extinction): no cone
// gather and no colour mixing; c stays 1 and l is exactly what CHROMATICITY 1 computes with the
// same SLAB and slices per dispatch.
#ifndef CHROMATICITY
#define CHROMATICITY 1
#endif
#ifndef SLAB
#define SLAB 0
#endif
// The slice texture holds SLICE_PADDING texels of outsideLight around each slice (slice texel t
// is texel t + SLICE_PADDING). PADDED_LOOKUPS 1 (SLAB 0, where the CPU bounded every lookup's
// reach within the padding): the lookups read it without testing the slice's edges.
#ifndef SLICE_PADDING
#define SLICE_PADDING 0
#endif
#ifndef PADDED_LOOKUPS
#define PADDED_LOOKUPS 0
#endif
// COLUMN_VOXELS n > 1 (SLAB 0, a directional light): each invocation propagates a column of n
// voxels along v, which share their lookups' rows (arrivingAlongColumn).
#ifndef COLUMN_VOXELS
#define COLUMN_VOXELS 1
#endif
#if SLAB
// TILE (slice texels per workgroup and side) and SLAB_SIDE (TILE + 2 x slices x halo at most)
// come from light_volume_pass.cpp.
layout(local_size_x = 32, local_size_y = 32) in;
const int kThreads = 1024;
const int kItems = SLAB_SIDE * SLAB_SIDE / kThreads;  // slab texels per invocation
#else
layout(local_size_x = 8, local_size_y = 8) in;
#endif

#include "volume/transfer_function.glsl"
#include "volume/clip.glsl"
#include "volume/empty_neighbourhood.glsl"

#define MAX_SWEEPS 6
// Layer 2 s + parity holds the light leaving sweep s's last slice of the previous (parity =
// pass % 2) or of this dispatch. Its texels are read by texelFetch (texels beyond a sweep's
// slice are outsideLight, whatever the layer holds there; SLAB 0's first pass reads layers
// cleared to it); SLAB 0's cone taps are filtered by the texture unit, with a border of
// outsideLight.
uniform sampler2DArray previousSlices;
uniform vec2 slicesTextureSize;  // SLAB 0
layout(rgba16f) uniform writeonly image2DArray currentSlices;
#include "volume/light_volume_format.glsl"
layout(LIGHT_VOLUME_FORMAT) uniform writeonly image3D lightVolume;  // (c, l) arriving at each voxel
layout(LIGHT_VOLUME_FORMAT) uniform writeonly image3D blendedVolume;  // the same from the blended sweep
// The same from a sweep along x, at (y, z, x): its slices' stores run along this volume's rows
// (light_volume_blend.comp puts them in place).
layout(LIGHT_VOLUME_FORMAT) uniform writeonly image3D rowOrderedVolume;
uniform vec4 outsideLight;  // the light entering from outside the volume

// Each sweep's frame against the data axes (set on the CPU, so no voxel permutes axes):
// voxel = voxelOrigin + u voxelStepU + v voxelStepV + w voxelStepW, a data-space vector x is
// dataToSweep x in the sweep frame, and a voxel's edges along u, v, w are sweepVoxelSize.
uniform ivec3 sliceDims[MAX_SWEEPS];   // light-volume voxels along u, v, w
uniform int firstSlice[MAX_SWEEPS];    // the slice the sweep starts at
uniform ivec3 voxelOrigin[MAX_SWEEPS];
uniform ivec3 voxelStepU[MAX_SWEEPS];
uniform ivec3 voxelStepV[MAX_SWEEPS];
uniform ivec3 voxelStepW[MAX_SWEEPS];
uniform mat3 dataToSweep[MAX_SWEEPS];
uniform vec3 sweepVoxelSize[MAX_SWEEPS];
uniform int blended[MAX_SWEEPS];       // 1: writes blendedVolume, mixed into lightVolume afterwards
uniform int rowOrdered[MAX_SWEEPS];    // 1 (a sweep along x): writes rowOrderedVolume instead
uniform int pyramidMask[MAX_SWEEPS];   // 1: writes only voxels whose dominant light axis is +w
uniform int slabSlices[MAX_SWEEPS];    // SLAB 1: slices each dispatch advances the sweep
uniform int slabHalo[MAX_SWEEPS];      // SLAB 1: texels beyond a voxel its lookups reach at most
uniform int pass;                      // dispatches before this one
uniform int firstSweep;                // the sweep of the dispatch's first workgroups along z
uniform ivec3 lightVolumeDims;  // per data axis
uniform vec3 voxelSize;         // light-volume voxel edge per data axis, model units
uniform vec3 boxMin;            // model-space corner of the volume box
uniform float referenceLength;  // the TF opacity's reference length (one data voxel)
uniform int isPointLight;
uniform vec3 lightDirection;    // direction the light travels, model space, unit (directional)
uniform vec3 lightPosition;     // model space (point light)
uniform float coneTangent;      // tan of the cone half-angle
uniform vec2 coneWeights;       // (centre tap, each of the 8 ring taps); centre + 8 ring = 1
#if EYE_PASS
uniform sampler3D litColour;
#endif

int sweep;
ivec3 dims;

bool inSlice(ivec2 texel) { return all(greaterThanEqual(texel, ivec2(0))) && all(lessThan(texel, dims.xy)); }

// Half floats rounded as packHalf2x16 rounds: a store to the slice texture may round otherwise.
uvec2 packLight(vec4 light) { return uvec2(packHalf2x16(light.rg), packHalf2x16(light.ba)); }
vec4 unpackLight(uvec2 halves) { return vec4(unpackHalf2x16(halves.x), unpackHalf2x16(halves.y)); }

#if SLAB
// The previous slice around this workgroup's tile, as half floats (c.rg, c.b l).
shared uvec2 slab[SLAB_SIDE * SLAB_SIDE];
ivec2 slabOrigin;  // slice texel at slab[0]
int slabSide;      // texels of the slab the workgroup loaded, per side

int slabIndex(ivec2 texel) {
    ivec2 local = clamp(texel - slabOrigin, ivec2(0), ivec2(slabSide - 1));
    return local.y * SLAB_SIDE + local.x;
}

vec4 previousTexel(ivec2 texel) { return inSlice(texel) ? unpackLight(slab[slabIndex(texel)]) : outsideLight; }

#else
vec4 previousTexel(ivec2 texel) {
    ivec3 stored = ivec3(texel + SLICE_PADDING, 2 * sweep + pass % 2);
#if PADDED_LOOKUPS
    return texelFetch(previousSlices, stored, 0);
#else
    return inSlice(texel) ? texelFetch(previousSlices, stored, 0) : outsideLight;
#endif
}
#endif

// The previous slice's light at `position` (slice texels, centres at + 0.5), bilinear: the
// chromaticity cone's ring taps, which blur on purpose. SLAB 0 lets the texture unit filter them
// (by hand they made the paper model's change frame 1.4x slower on llvmpipe), so its colours
// differ from the slabs' by the unit's 8-bit weights.
vec4 previousLight(vec2 position) {
#if !SLAB
    return texture(previousSlices, vec3((position + float(SLICE_PADDING)) / slicesTextureSize, float(2 * sweep + pass % 2)));
#endif
    vec2 corner = position - 0.5;
    ivec2 i = ivec2(floor(corner));
    vec2 f = corner - vec2(i);
    vec4 bottom = mix(previousTexel(i), previousTexel(i + ivec2(1, 0)), f.x);
    vec4 top = mix(previousTexel(i + ivec2(0, 1)), previousTexel(i + ivec2(1, 1)), f.x);
    return mix(bottom, top, f.y);
}

// Catmull-Rom weights of the four texels around a fraction f of the way between the middle two.
vec4 catmullRomWeights(float f) {
    float f2 = f * f, f3 = f2 * f;
    return vec4(-0.5 * f3 + f2 - 0.5 * f, 1.5 * f3 - 2.5 * f2 + 1.0, -1.5 * f3 + 2.0 * f2 + 0.5 * f,
                0.5 * f3 - 0.5 * f2);
}

// The light arriving along the ray: Catmull-Rom over 4x4 texels, clamped to the range of the
// middle 2x2. A bilinear lookup at a fractional shift blurs a shadow at every slice (by f(1-f)
// texels squared), so shadows cast from far away arrived smeared over several voxels
// (docs/light-volume-sweep.md); the cubic keeps their edges and the clamp keeps it monotone.
// The voxel at uv looks up the previous slice `shift` texels back: the 4x4 texels from
// uv + floor(-shift) - 1, weighted for the fraction fract(-shift). Row by row, so that a column
// of voxels with the same shift (a directional light's) shares its rows (arrivingAlongColumn).
// Written out tap by tap: on llvmpipe a loop over the taps or a branch that skips them where
// the middle four agree measured 5-10 % slower.
struct LookupFootprint {
    ivec2 corner;  // the middle 2x2's first texel, weighted wx.y and wy.y
    vec4 wx, wy;
};

LookupFootprint lookupFootprint(ivec2 uv, vec2 shift) {
    vec2 offset = -shift;
    vec2 whole = floor(offset);
    vec2 f = offset - whole;
    return LookupFootprint(uv + ivec2(whole), catmullRomWeights(f.x), catmullRomWeights(f.y));
}

vec4 rowSum(vec4 wx, vec4 left, vec4 middleLeft, vec4 middleRight, vec4 right) {
    return wx.x * left + wx.y * middleLeft + wx.z * middleRight + wx.w * right;
}

vec4 combineRows(vec4 wy, vec4 above, vec4 row0, vec4 row1, vec4 below, vec4 low, vec4 high) {
    return clamp(wy.x * above + wy.y * row0 + wy.z * row1 + wy.w * below, low, high);
}

vec4 arrivingAlongRay(ivec2 uv, vec2 shift) {
    LookupFootprint l = lookupFootprint(uv, shift);
    ivec2 i = l.corner;
    vec4 t00 = previousTexel(i), t10 = previousTexel(i + ivec2(1, 0));
    vec4 t01 = previousTexel(i + ivec2(0, 1)), t11 = previousTexel(i + ivec2(1, 1));
    vec4 low = min(min(t00, t10), min(t01, t11)), high = max(max(t00, t10), max(t01, t11));
    vec4 above = rowSum(l.wx, previousTexel(i + ivec2(-1, -1)), previousTexel(i + ivec2(0, -1)),
                        previousTexel(i + ivec2(1, -1)), previousTexel(i + ivec2(2, -1)));
    vec4 row0 = rowSum(l.wx, previousTexel(i + ivec2(-1, 0)), t00, t10, previousTexel(i + ivec2(2, 0)));
    vec4 row1 = rowSum(l.wx, previousTexel(i + ivec2(-1, 1)), t01, t11, previousTexel(i + ivec2(2, 1)));
    vec4 below = rowSum(l.wx, previousTexel(i + ivec2(-1, 2)), previousTexel(i + ivec2(0, 2)),
                        previousTexel(i + ivec2(1, 2)), previousTexel(i + ivec2(2, 2)));
    return combineRows(l.wy, above, row0, row1, below, low, high);
}

#if COLUMN_VOXELS > 1
// arrivingAlongRay for the COLUMN_VOXELS voxels from uv up along v, all with the same shift:
// COLUMN_VOXELS + 3 rows of four texels instead of 16 texels per voxel, the same arithmetic.
void arrivingAlongColumn(ivec2 uv, vec2 shift, out vec4 centres[COLUMN_VOXELS]) {
    LookupFootprint l = lookupFootprint(uv, shift);
    const int rows = COLUMN_VOXELS + 3;
    vec4 sums[rows], middleLeft[rows], middleRight[rows];
    for (int r = 0; r < rows; ++r) {
        ivec2 t = l.corner + ivec2(0, r - 1);
        middleLeft[r] = previousTexel(t);
        middleRight[r] = previousTexel(t + ivec2(1, 0));
        sums[r] = rowSum(l.wx, previousTexel(t + ivec2(-1, 0)), middleLeft[r], middleRight[r],
                         previousTexel(t + ivec2(2, 0)));
    }
    for (int k = 0; k < COLUMN_VOXELS; ++k) {
        vec4 low = min(min(middleLeft[k + 1], middleRight[k + 1]), min(middleLeft[k + 2], middleRight[k + 2]));
        vec4 high = max(max(middleLeft[k + 1], middleRight[k + 1]), max(middleLeft[k + 2], middleRight[k + 2]));
        centres[k] = combineRows(l.wy, sums[k], sums[k + 1], sums[k + 2], sums[k + 3], low, high);
    }
}
#endif

// Where the light reaching voxel (uv, w) of the sweep comes from.
struct VoxelLight {
    ivec3 voxel;      // data index
    vec3 direction;   // the light's travel, model space (not unit for a point light)
    float dz;         // its component along w, at least 1e-3
    vec2 shift;       // where its ray crosses the previous slice: this many texels back along u, v
};

VoxelLight voxelLight(ivec2 uv, int w) {
    ivec3 voxel = voxelOrigin[sweep] + uv.x * voxelStepU[sweep] + uv.y * voxelStepV[sweep] + w * voxelStepW[sweep];
    vec3 position = boxMin + (vec3(voxel) + 0.5) * voxelSize;
    vec3 direction = isPointLight != 0 ? position - lightPosition : lightDirection;
    // Direction and voxel size in the sweep frame.
    vec3 d = dataToSweep[sweep] * direction;
    vec3 s = sweepVoxelSize[sweep];
    // A voxel centred exactly on a point light gets an arbitrary direction instead of NaN.
    d = dot(d, d) > 1e-20 ? normalize(d) : vec3(0.0, 0.0, 1.0);
    // Light must travel forward along w; a point light beside the sweep gives dz -> 0.
    float dz = max(d.z, 1e-3);
    return VoxelLight(voxel, direction, dz, d.xy / dz * s.z / s.xy);
}

// Propagates the light across voxel (uv, w) of the sweep, which `centre` arrives at from the
// previous slice; stores the light arriving at its centre in the light volume when `store`, and
// returns the light leaving its slab.
vec4 propagateVoxel(ivec2 uv, VoxelLight ray, vec4 centre, bool store) {
    ivec3 voxel = ray.voxel;
    vec3 direction = ray.direction;
    vec3 s = sweepVoxelSize[sweep];
    float pathLength = s.z / ray.dz;  // model units between slices along the light ray
    // Where the light ray through this voxel crosses the previous slice, in slice texels.
    vec2 previous = vec2(uv) + 0.5 - ray.shift;
#if CHROMATICITY
    vec3 chromaticity = centre.rgb;
    vec2 ringRadius = coneTangent * pathLength / s.xy;  // texels
    if (min(ringRadius.x, ringRadius.y) >= 0.5) {
        vec3 ring = vec3(0.0);
        for (int k = 0; k < 8; ++k) {
            float angle = float(k) * 0.78539816;
            ring += previousLight(previous + ringRadius * vec2(cos(angle), sin(angle))).rgb;
        }
        chromaticity = coneWeights.x * centre.rgb + coneWeights.y * ring;
    }
#else
    const vec3 chromaticity = vec3(1.0);
#endif
    // Across this voxel's slab (from plane w - 1/2 to w + 1/2) the light crosses the medium at
    // data resolution: n samples along the ray, about one per data voxel of path and at least
    // two (one sample at the centre let light slip past thin structures between slices; two per
    // voxel measured no better). The light volume keeps the light at the voxel centre, after
    // the first n/2 of them.
    vec3 centreTc = (vec3(voxel) + 0.5) / vec3(lightVolumeDims);
    vec3 slabTc = normalize(direction) * pathLength / (voxelSize * vec3(lightVolumeDims));
    int n = 2 * clamp(int(ceil(0.5 * pathLength / referenceLength)), 1, 8);
    float piece = pathLength / float(n);
    vec4 light = vec4(chromaticity, centre.a);
    vec4 arriving = light;
    // Where every medium sample below lies within a brick of empty bricks (per axis, in data
    // voxels), each would have opacity 0 and leave the light exactly as it is: skip them. On the
    // bonsai most voxels are empty, and these samples were a quarter to a third of the sweep.
    bool empty = pathIsEmpty(centreTc, 0.5 * slabTc);
    for (int k = 0; k < (empty ? 0 : n); ++k) {
        vec3 tcK = centreTc + ((float(k) + 0.5) / float(n) - 0.5) * slabTc;
#if EYE_PASS
        // The viewer sees no cut matter, whatever the light does.
        bool present = clipKeeps(tcK);
#else
        bool present = lightSeesMedium(tcK);
#endif
        vec4 medium = present ? classify(volumeValue(tcK)) : vec4(0.0);
#if EYE_PASS
        vec3 source = texture(litColour, tcK).rgb;
#else
        vec3 source = medium.rgb;
#endif
        float a = correctOpacity(medium.a, piece, referenceLength);
#if CHROMATICITY
        light = vec4((1.0 - a) * light.rgb + a * source, (1.0 - a) * light.a);
#else
        light.a *= 1.0 - a;
#endif
        if (k == n / 2 - 1) arriving = light;
    }
    if (!store) return light;
    if (pyramidMask[sweep] != 0) {
        // Light inside the volume: six sweeps, each owning the voxels whose light arrives
        // mostly along its +w (measured in voxels, so the lookup stays within one texel). Every
        // sweep decides from the same data-space arithmetic, a tie going to the lower axis, so
        // exactly one writes each voxel (per-sweep frames round apart).
        ivec3 stepW = voxelStepW[sweep];
        int axis = stepW.x != 0 ? 0 : (stepW.y != 0 ? 1 : 2);
        vec3 inVoxels = abs(direction) / voxelSize;
        bool owns = direction[axis] * float(stepW[axis]) > 0.0;
        for (int b = 0; b < 3; ++b)
            if (b != axis) owns = owns && (inVoxels[axis] > inVoxels[b] || (inVoxels[axis] == inVoxels[b] && axis < b));
        if (!owns) return light;
    }
#if !CHROMATICITY
    arriving = vec4(arriving.a);  // the one channel holds l
#endif
    if (rowOrdered[sweep] != 0)
        imageStore(rowOrderedVolume, voxel.yzx, arriving);
    else if (blended[sweep] != 0)
        imageStore(blendedVolume, voxel, arriving);
    else
        imageStore(lightVolume, voxel, arriving);
    return light;
}

// Stores the light leaving slice texel uv for the next dispatch's lookups, rounded to half floats
// as the slabs' shared memory rounds, so the next slice reads what theirs would.
void storeLeaving(ivec2 uv, uvec2 halves) {
    imageStore(currentSlices, ivec3(uv + SLICE_PADDING, 2 * sweep + 1 - pass % 2), unpackLight(halves));
}

vec4 propagateVoxel(ivec2 uv, int w, bool store) {
    VoxelLight ray = voxelLight(uv, w);
    return propagateVoxel(uv, ray, arrivingAlongRay(uv, ray.shift), store);
}

#if SLAB
void main() {
    sweep = firstSweep + int(gl_WorkGroupID.z);
    dims = sliceDims[sweep];
    int slices = slabSlices[sweep];
    int halo = slabHalo[sweep];
    int firstW = firstSlice[sweep] + pass * slices;
    int count = clamp(dims.z - firstW, 0, slices);
    ivec2 tileOrigin = ivec2(gl_WorkGroupID.xy) * TILE;
    // Whole workgroups leave here, before any barrier.
    if (count == 0 || any(greaterThanEqual(tileOrigin, dims.xy))) return;
    slabOrigin = tileOrigin - slices * halo;
    slabSide = TILE + 2 * slices * halo;
    int invocation = int(gl_LocalInvocationIndex);

    for (int i = 0; i < kItems; ++i) {
        int index = invocation + i * kThreads;
        if (index >= slabSide * slabSide) break;
        ivec2 texel = slabOrigin + ivec2(index % slabSide, index / slabSide);
        vec4 stored = texelFetch(previousSlices, ivec3(texel + SLICE_PADDING, 2 * sweep + pass % 2), 0);
        slab[slabIndex(texel)] = packLight(pass > 0 && inSlice(texel) ? stored : outsideLight);
    }
    barrier();

    uvec2 leaving[kItems];
    for (int j = 0; j < count; ++j) {
        int margin = (slices - 1 - j) * halo;
        ivec2 regionOrigin = tileOrigin - margin;
        int side = TILE + 2 * margin;
        bool lastSlice = j == count - 1;
        for (int i = 0; i < kItems; ++i) {
            int index = invocation + i * kThreads;
            if (index >= side * side) break;
            ivec2 uv = regionOrigin + ivec2(index % side, index / side);
            bool inTile = all(greaterThanEqual(uv, tileOrigin)) && all(lessThan(uv, tileOrigin + TILE));
            leaving[i] = packLight(inSlice(uv) ? propagateVoxel(uv, firstW + j, inTile) : outsideLight);
            if (lastSlice && inTile && inSlice(uv)) storeLeaving(uv, leaving[i]);
        }
        barrier();  // every lookup into the previous slice is done
        for (int i = 0; i < kItems; ++i) {
            int index = invocation + i * kThreads;
            if (index >= side * side) break;
            slab[slabIndex(regionOrigin + ivec2(index % side, index / side))] = leaving[i];
        }
        barrier();
    }
}
#elif COLUMN_VOXELS > 1
void main() {
    sweep = firstSweep + int(gl_WorkGroupID.z);
    dims = sliceDims[sweep];
    ivec2 first = ivec2(gl_GlobalInvocationID.x, gl_GlobalInvocationID.y * uint(COLUMN_VOXELS));
    int w = firstSlice[sweep] + pass;
    if (first.x >= dims.x || first.y >= dims.y || w >= dims.z) return;
    vec4 centres[COLUMN_VOXELS];
    arrivingAlongColumn(first, voxelLight(first, w).shift, centres);
    for (int k = 0; k < COLUMN_VOXELS; ++k) {
        ivec2 uv = first + ivec2(0, k);
        if (uv.y >= dims.y) break;
        storeLeaving(uv, packLight(propagateVoxel(uv, voxelLight(uv, w), centres[k], true)));
    }
}
#else
void main() {
    sweep = firstSweep + int(gl_WorkGroupID.z);
    dims = sliceDims[sweep];
    ivec2 uv = ivec2(gl_GlobalInvocationID.xy);
    int w = firstSlice[sweep] + pass;
    if (uv.x >= dims.x || uv.y >= dims.y || w >= dims.z) return;
    storeLeaving(uv, packLight(propagateVoxel(uv, w, true)));
}
#endif
