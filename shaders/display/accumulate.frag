// FrameAccumulator: adds one frame to the running mean; the blend state weighs it
// (src/frame_accumulator.cpp).
uniform sampler2D frameColor;
layout(location = 0) out vec4 outColor;
void main() { outColor = texelFetch(frameColor, ivec2(gl_FragCoord.xy), 0); }
