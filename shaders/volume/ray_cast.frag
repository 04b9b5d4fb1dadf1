// The fragment ray caster: a fullscreen triangle whose fragments are blended "over" the target
// (src/volume/composite_over.h). The ray itself is castRay() in ray_cast.glsl.
#include "volume/ray_cast.glsl"

in vec2 ndc;
layout(location = 0) out vec4 fragColor;   // premultiplied colour, alpha = opacity

void main() { fragColor = castRay(gl_FragCoord.xy, ndc); }
