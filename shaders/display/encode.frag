// DisplayEncoder: linear colour -> display values (shaders/common/display_transform.glsl).
#include "common/display_transform.glsl"

uniform sampler2D linearColor;
uniform float exposureScale;
uniform int toneMap;
uniform int srgb;

layout(location = 0) out vec4 displayColor;

void main() {
    vec4 c = texelFetch(linearColor, ivec2(gl_FragCoord.xy), 0);
    displayColor = vec4(displayChannel(c.r, exposureScale, toneMap, srgb), displayChannel(c.g, exposureScale, toneMap, srgb),
                        displayChannel(c.b, exposureScale, toneMap, srgb), clamp(c.a, 0.0, 1.0));
}
