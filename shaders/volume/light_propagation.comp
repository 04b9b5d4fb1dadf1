// One step of the light-volume propagation (Ropinski, Doering, Rezk-Salama 2010).
// The volume is swept slice by slice along "sweep" frames (u, v across a slice, w along the
// sweep), each a permutation/flip of the data axes chosen by src/volume/light_volume_pass.cpp
// so the light always travels towards +w. A light's sweeps (two blended ones, or six from a light
// inside) advance together, one slice each per dispatch: workgroup z is the sweep. For each voxel
// of slice w:
//   - the light arriving there is looked up where the light ray through the voxel crosses slice
//     w-1: intensity l with one bilinear fetch (hard shadows), chromaticity c gathered over a
//     cone whose aperture follows the Henyey-Greenstein g;
//   - along the ray across the voxel's slab the medium is sampled at data resolution, and each
//     piece changes the light as c' = (1-a) c + a rgb, l' = (1-a) l, with the TF opacity a
//     corrected for the piece's length;
//   - the (c, l) at the voxel centre, after the first half of the slab, is stored in the light
//     volume (the light volume samples light at points, like the CPU reference), and the light
//     leaving the slab goes to the next slice.
// Outside the volume the light is unattenuated white: (1, 1, 1, 1).
//
// EYE_PASS 1 (the optional second pass, towards the viewer): the same sweep carries the light the
// voxels scatter (litColour, from lit_colour.comp) instead of the TF colour, starting from no
// light (border (0, 0, 0, 1)), so rgb becomes the cone-blurred light scattered towards the eye
// from behind each voxel.
//
// CHROMATICITY 0 (readers that use l alone: the physical model's grey extinction): no cone
// gather and no colour mixing; c stays 1 and l is exactly what CHROMATICITY 1 computes.
#ifndef CHROMATICITY
#define CHROMATICITY 1
#endif
layout(local_size_x = 8, local_size_y = 8) in;

#include "volume/transfer_function.glsl"
#include "volume/clip.glsl"

#define MAX_SWEEPS 6
// Layer 2 s + parity holds the light leaving sweep s's previous (parity = step % 2) or current
// slice. Each sweep uses the layers' first sliceDims texels; the rest stays at the unlit value,
// like the border, so the lookups see what a texture of the slice's own size would give.
uniform sampler2DArray previousSlices;
layout(rgba16f) uniform writeonly image2DArray currentSlices;
uniform vec2 slicesTextureSize;
layout(rgba16f) uniform writeonly image3D lightVolume;    // (c, l) arriving at each voxel
layout(rgba16f) uniform writeonly image3D blendedVolume;  // the same from the blended sweep

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
uniform int pyramidMask[MAX_SWEEPS];   // 1: writes only voxels whose dominant light axis is +w
uniform int step;                      // slices every sweep has done
uniform ivec3 lightVolumeDims;  // per data axis
uniform vec3 voxelSize;         // light-volume voxel edge per data axis, model units
uniform vec3 boxMin;            // model-space corner of the volume box
uniform float referenceLength;  // the TF opacity's reference length (one data voxel)
uniform int isPointLight;
uniform vec3 lightDirection;    // direction the light travels, model space, unit (directional)
uniform vec3 lightPosition;     // model space (point light)
uniform float coneTangent;      // tan of the cone half-angle
uniform vec2 coneWeights;       // (centre tap, each of the 8 ring taps); centre + 8 ring = 1
// Empty space (src/volume/empty_space.h): per brick of brickVoxels^3 data voxels, 0 where the
// brick and its 26 neighbours sample no opacity under the current transfer function.
uniform int skipEmpty;
uniform sampler3D occupiedNeighbourhoods;
uniform ivec3 dataDims;
uniform int brickVoxels;
uniform vec3 textureToBrick;    // dataDims / brickVoxels: a brick by a float product (ray_cast.frag)
#if EYE_PASS
uniform sampler3D litColour;
#endif

void main() {
    int sweep = int(gl_WorkGroupID.z);
    ivec3 dims = sliceDims[sweep];
    ivec2 uv = ivec2(gl_GlobalInvocationID.xy);
    int w = firstSlice[sweep] + step;
    if (uv.x >= dims.x || uv.y >= dims.y || w >= dims.z) return;

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

    float pathLength = s.z / dz;  // model units between slices along the light ray

    // Where the light ray through this voxel crosses the previous slice, in slice texels.
    vec2 previous = vec2(uv) + 0.5 - d.xy / dz * s.z / s.xy;
    float previousLayer = float(2 * sweep + step % 2);
    vec4 centre = texture(previousSlices, vec3(previous / slicesTextureSize, previousLayer));
#if CHROMATICITY
    vec3 chromaticity = centre.rgb;
    vec2 ringRadius = coneTangent * pathLength / s.xy;  // texels
    if (min(ringRadius.x, ringRadius.y) >= 0.5) {
        vec3 ring = vec3(0.0);
        for (int k = 0; k < 8; ++k) {
            float angle = float(k) * 0.78539816;
            vec2 tap = previous + ringRadius * vec2(cos(angle), sin(angle));
            ring += texture(previousSlices, vec3(tap / slicesTextureSize, previousLayer)).rgb;
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
    bool empty = false;
    if (skipEmpty != 0) {
        vec3 halfSlab = 0.5 * abs(slabTc) * vec3(dataDims);
        if (max(max(halfSlab.x, halfSlab.y), halfSlab.z) <= float(brickVoxels)) {
            ivec3 brick = clamp(ivec3(centreTc * textureToBrick), ivec3(0),
                                textureSize(occupiedNeighbourhoods, 0) - 1);
            empty = texelFetch(occupiedNeighbourhoods, brick, 0).r == 0.0;
        }
    }
    for (int k = 0; k < (empty ? 0 : n); ++k) {
        vec3 tcK = centreTc + ((float(k) + 0.5) / float(n) - 0.5) * slabTc;
#if EYE_PASS
        // The viewer sees no cut matter, whatever the light does.
        bool present = clipKeeps(tcK);
#else
        bool present = lightSeesMedium(tcK);
#endif
        vec4 medium = present ? classify(texture(volumeTexture, tcK).r) : vec4(0.0);
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
    imageStore(currentSlices, ivec3(uv, 2 * sweep + 1 - step % 2), light);

    if (pyramidMask[sweep] != 0) {
        // Light inside the volume: six sweeps, each owning the voxels whose light arrives
        // mostly along its +w (measured in voxels, so the lookup stays within one texel).
        vec3 inVoxels = abs(d) / s;
        if (d.z <= 0.0 || inVoxels.z < inVoxels.x || inVoxels.z < inVoxels.y) return;
    }
    if (blended[sweep] != 0)
        imageStore(blendedVolume, voxel, arriving);
    else
        imageStore(lightVolume, voxel, arriving);
}
