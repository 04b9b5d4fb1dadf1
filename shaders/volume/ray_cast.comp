// The compute ray caster: one invocation per pixel of the volume's screen rectangle, composited
// "over" the target's colour through image load/store. On GPUs that run fragment work on a
// fraction of the chip (datacenter parts), compute gets all of it. The ray is castRay() in
// ray_cast.glsl, the same as the fragment caster's.
#include "volume/ray_cast.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(rgba32f) uniform image2D target;  // premultiplied colour, alpha = coverage
uniform ivec2 rectOrigin;                // first pixel of the rectangle
uniform ivec2 rectSize;
uniform vec2 viewportSize;               // the target's size in pixels

void main() {
    ivec2 offset = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(offset, rectSize))) return;
    ivec2 pixel = rectOrigin + offset;
    vec2 fragCoord = vec2(pixel) + 0.5;
    vec4 ray = castRay(fragCoord, fragCoord / viewportSize * 2.0 - 1.0);
    if (ray == vec4(0.0)) return;  // nothing to add: leave the target as it is
    vec4 behind = imageLoad(target, pixel);
    imageStore(target, pixel, ray + (1.0 - ray.a) * behind);
}
