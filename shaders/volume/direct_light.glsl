// The direct light the multiple-scattering cache regresses its once-scattered fluence on
// (src/volume/fluence_cache.h): the lights' light volumes (l: the light arriving unscattered),
// each weighted by its light's mean radiance channel at the box's centre. The ray caster forms
// the same sum from the light it carries to each sample (ray_cast.glsl, shade).
uniform sampler3D lightVolumes[MAX_LIGHTS];
uniform float directLightWeight[MAX_LIGHTS];
uniform int directLightCount;

float directLightAt(vec3 tc) {
    float e = 0.0;
    for (int i = 0; i < directLightCount; ++i) e += directLightWeight[i] * texture(lightVolumes[i], tc).a;
    return e;
}
