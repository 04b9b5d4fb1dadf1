// The blended sweep's share of the light volume (light_propagation.comp runs it beside the main
// sweep into its own volume): light = mix(main, blended, weight), rounded to half precision once
// more. Unlit stays exactly 1.
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(rgba16f) uniform image3D lightVolume;
layout(rgba16f) uniform readonly image3D blendedVolume;
uniform ivec3 dims;
uniform float weight;

void main() {
    ivec3 voxel = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(voxel, dims))) return;
    imageStore(lightVolume, voxel, mix(imageLoad(lightVolume, voxel), imageLoad(blendedVolume, voxel), weight));
}
