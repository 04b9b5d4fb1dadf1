// Clears a render target's colour (sss::RenderTarget::clear on hardware GPUs). Datacenter GPUs
// clear colour attachments on their small graphics partition: an H200 took 0.30 ms for a
// 1200 x 680 RGBA32F target that this dispatch writes in 0.07 ms (sss-bench --table clear).
layout(local_size_x = 8, local_size_y = 8) in;

layout(rgba32f) uniform writeonly image2D target;
uniform vec4 color;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (all(lessThan(pixel, imageSize(target)))) imageStore(target, pixel, color);
}
