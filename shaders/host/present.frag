// HostTarget::Frame::present: the libsss target composited over the host's framebuffer
// (premultiplied "over", blending set by the caller) with its depth, so that libsss meshes hide
// what the host draws afterwards. Display values go through the display transform per
// un-premultiplied colour (shaders/common/display_transform.glsl).
#include "common/display_transform.glsl"

uniform sampler2D linearColor;
uniform sampler2D depth;
uniform ivec2 origin;  // the host rectangle's lower-left corner
uniform int encode;    // 1: display values, 0: linear radiance
uniform float exposureScale;
uniform int toneMap;
uniform int srgb;

layout(location = 0) out vec4 hostColor;

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy) - origin;
    vec4 c = texelFetch(linearColor, texel, 0);
    float a = clamp(c.a, 0.0, 1.0);
    if (a <= 0.0) discard;  // nothing of libsss here: the host's colour and depth stay
    vec3 rgb = c.rgb;
    if (encode == 1) {
        vec3 straight = rgb / a;
        rgb = a * vec3(displayChannel(straight.r, exposureScale, toneMap, srgb),
                       displayChannel(straight.g, exposureScale, toneMap, srgb),
                       displayChannel(straight.b, exposureScale, toneMap, srgb));
    }
    hostColor = vec4(rgb, a);
    gl_FragDepth = texelFetch(depth, texel, 0).r;
}
