// The path tracer's running mean over the target: the sums divided by the sample count give
// premultiplied radiance and coverage alpha, drawn with "over" blending like the ray caster's.
uniform sampler2D accumulation;
uniform float inverseSamples;

layout(location = 0) out vec4 fragColor;

void main() { fragColor = texelFetch(accumulation, ivec2(gl_FragCoord.xy), 0) * inverseSamples; }
