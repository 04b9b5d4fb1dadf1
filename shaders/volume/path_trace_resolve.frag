// The path tracer's running mean over the target: the sums divided by the sample count give
// premultiplied radiance and coverage alpha, drawn with "over" blending like the ray caster's.
uniform sampler2D accumulation;
uniform float inverseSamples;
uniform vec3 radianceScale;  // the lights' radiance now over that of the paths traced (per channel)

layout(location = 0) out vec4 fragColor;

void main() {
    vec4 sum = texelFetch(accumulation, ivec2(gl_FragCoord.xy), 0);
    fragColor = vec4(sum.rgb * radianceScale, sum.a) * inverseSamples;
}
