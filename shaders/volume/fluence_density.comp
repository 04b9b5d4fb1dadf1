// The multiple-scattering cache's weights: per cell, the integral over it of s, sigma_t at the
// centre of each voxel taken as constant across the voxel (fluence_photons.comp averages the
// fluence with the same s), in model units^2; voxels that straddle cells count by their overlap.
// Also the direct light's moments, which change with the lights.
#include "common/ray_box.glsl"
#include "volume/transfer_function.glsl"
#include "volume/clip.glsl"
#include "volume/medium_walk.glsl"
uniform mat4 modelToWorld;
#include "volume/direct_light.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(std430, binding = 3) writeonly buffer Weights { float cellWeight[]; };
// Per cell, the integrals of s E and s E^2, E the direct light at each voxel's centre: the
// moments of the once-scattered fluence's regression on E (fluence_resolve.comp); and the largest
// E among the cell's voxels with medium, beyond which the eye does not extrapolate.
layout(std430, binding = 4) writeonly buffer DirectMoments { vec4 cellDirect[]; };
uniform ivec3 cacheCells;
uniform float voxelVolume;  // model units^3

// Whether every brick holding voxels first..last has majorant 0: no voxel there has medium.
bool bricksAreEmpty(ivec3 first, ivec3 last) {
    for (int z = first.z / BRICK_VOXELS; z <= last.z / BRICK_VOXELS; ++z)
        for (int y = first.y / BRICK_VOXELS; y <= last.y / BRICK_VOXELS; ++y)
            for (int x = first.x / BRICK_VOXELS; x <= last.x / BRICK_VOXELS; ++x)
                if (texelFetch(majorants, ivec3(x, y, z), 0).r > 0.0) return false;
    return true;
}

void main() {
    ivec3 c = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(c, cacheCells))) return;
    ivec3 dims = textureSize(volumeTexture, 0);
    vec3 lo = vec3(c) * vec3(dims) / vec3(cacheCells);
    vec3 hi = vec3(c + 1) * vec3(dims) / vec3(cacheCells);
    ivec3 first = ivec3(floor(lo));
    ivec3 last = min(ivec3(ceil(hi)), dims) - 1;
    float sum = 0.0;
    vec2 direct = vec2(0.0);
    float largest = 0.0;
    // Cells within bricks of majorant 0 (most of a sparse volume's) hold no medium: their loop is empty.
    if (bricksAreEmpty(first, last)) last = first - 1;
    for (int z = first.z; z <= last.z; ++z)
        for (int y = first.y; y <= last.y; ++y)
            for (int x = first.x; x <= last.x; ++x) {
                vec3 v = vec3(x, y, z);
                vec3 overlap = max(min(hi, v + 1.0) - max(lo, v), vec3(0.0));
                float s = voxelExtinction(ivec3(x, y, z)) * overlap.x * overlap.y * overlap.z;
                sum += s;
                if (s > 0.0) {
                    float e = directLightAtVoxel(ivec3(x, y, z), dims);
                    direct += s * vec2(e, e * e);
                    largest = max(largest, e);
                }
            }
    int index = (c.z * cacheCells.y + c.y) * cacheCells.x + c.x;
    cellWeight[index] = sum * voxelVolume;
    cellDirect[index] = vec4(direct * voxelVolume, largest, 0.0);
}
