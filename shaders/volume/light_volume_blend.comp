// Puts the sweeps' light in the light volume where light_propagation.comp left it elsewhere: the
// blended sweep's share, light = mix(main, blended, weight), rounded to half precision once more
// (unlit stays exactly 1); and a sweep along x, which stored its light at (y, z, x) in
// rowOrderedVolume, read from there (the same half floats).
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

// Without the chromaticity the volumes hold l alone (light_propagation.comp), and imageLoad
// returns (l, 0, 0, 1): the mix below keeps l in the first channel.
#ifndef CHROMATICITY
#define CHROMATICITY 1
#endif
#include "volume/light_volume_format.glsl"
layout(LIGHT_VOLUME_FORMAT) uniform image3D lightVolume;
layout(LIGHT_VOLUME_FORMAT) uniform readonly image3D blendedVolume;
layout(LIGHT_VOLUME_FORMAT) uniform readonly image3D rowOrderedVolume;
uniform ivec3 dims;
uniform int mainRowOrdered;     // 1: the main sweep's light is in rowOrderedVolume
uniform int blendedRowOrdered;  // 1: the blended sweep's light is
uniform float weight;           // the blended sweep's share; 0: no blended sweep

void main() {
    ivec3 voxel = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(voxel, dims))) return;
    vec4 light = mainRowOrdered != 0 ? imageLoad(rowOrderedVolume, voxel.yzx) : imageLoad(lightVolume, voxel);
    if (weight > 0.0) {
        vec4 other = blendedRowOrdered != 0 ? imageLoad(rowOrderedVolume, voxel.yzx) : imageLoad(blendedVolume, voxel);
        light = mix(light, other, weight);
    }
    imageStore(lightVolume, voxel, light);
}
