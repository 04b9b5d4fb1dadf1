// Scene lights, shared by the mesh and volume shaders. The CPU side (src/light_uniforms.cpp)
// fills these uniforms from sss::Light values.
//   lightVector[i].w == 0: directional; xyz = unit direction *towards* the light
//   lightVector[i].w == 1: point light;   xyz = world position
//   lightRadiance[i]   : colour * intensity
#ifndef MAX_LIGHTS
#define MAX_LIGHTS 8  // kMaxLights in src/light_uniforms.h
#endif
uniform int lightCount;
uniform vec4 lightVector[MAX_LIGHTS];
uniform vec3 lightRadiance[MAX_LIGHTS];

// Unit vector from `position` towards light i, and the radiance arriving there
// (point lights fall off with the inverse square of the distance).
vec3 lightDirectionAt(int i, vec3 position, out vec3 radiance) {
    if (lightVector[i].w == 0.0) {
        radiance = lightRadiance[i];
        return lightVector[i].xyz;
    }
    vec3 toLight = lightVector[i].xyz - position;
    float distanceSquared = max(dot(toLight, toLight), 1e-8);
    radiance = lightRadiance[i] / distanceSquared;
    return toLight * inversesqrt(distanceSquared);
}
