// The light buffer (src/mesh/light_buffer_pass.h) as the estimator, the near field and the
// combine pass read it: what surface each light sees, and whether a point is that surface.
#include "common/lights.glsl"

uniform sampler2DArray lightPositions;           // xyz world, w = 1 where covered; one layer per light
uniform sampler2DArray lightNormals;             // xyz world, the surface each light sees
uniform mat4 lightViewProjection[MAX_LIGHTS];    // world -> light-buffer clip space
uniform float lightTexelWorld;                   // a light-buffer texel's size at the object, world units

// How far along light l the point x lies behind the surface point `seen`.
float depthBehind(int l, vec3 seen, vec3 x, vec3 toLight) {
    return lightVector[l].w != 0.0 ? distance(x, lightVector[l].xyz) - distance(seen, lightVector[l].xyz)
                                   : dot(seen - x, toLight);
}

// The depth bias of a point with unit normal n: one texel across, a surface tilted by theta to
// the light moves tan(theta) texels along it.
float lightBufferBias(vec3 n, vec3 toLight) {
    float cosTheta = max(dot(n, toLight), 0.05);
    return lightTexelWorld * (2.0 + 1.5 * sqrt(1.0 - cosTheta * cosTheta) / cosTheta);
}

// The 2x2 texels of light l's buffer around p, for bilinear blends: texel k (0..3) is
// lightTexel(t, k, l) with weight lightTexelWeight(t, k). inside: p projects into the buffer.
struct LightTexels {
    ivec2 base, size;
    vec2 f;
    bool inside;
};

LightTexels lightTexelsAround(int l, vec3 p) {
    vec4 clip = lightViewProjection[l] * vec4(p, 1.0);
    vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    LightTexels t;
    t.size = textureSize(lightPositions, 0).xy;
    vec2 texel = uv * vec2(t.size) - 0.5;
    t.base = ivec2(floor(texel));
    t.f = texel - vec2(t.base);
    t.inside = all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0)));
    return t;
}

ivec3 lightTexel(LightTexels t, int k, int l) {
    return ivec3(clamp(t.base + ivec2(k & 1, k >> 1), ivec2(0), t.size - 1), l);
}

float lightTexelWeight(LightTexels t, int k) {
    return ((k & 1) == 1 ? t.f.x : 1.0 - t.f.x) * ((k >> 1) == 1 ? t.f.y : 1.0 - t.f.y);
}

// What light l sees around p, over the 2x2 texels around p's, blended bilinearly (smooth across
// texels). x: whether p is the surface seen there (judged like a shadow map, with p's `bias`):
// the share of light l that reaches p directly. y: the share where a surface lies more than
// `behindBias` in front of the point `behind` (a surface that hides it from the light).
vec2 lightSeenAround(int l, vec3 p, float bias, vec3 behind, float behindBias) {
    LightTexels t = lightTexelsAround(l, p);
    vec3 toLight = lightVector[l].w != 0.0 ? normalize(lightVector[l].xyz - p) : lightVector[l].xyz;
    vec2 seenAround = vec2(0.0);
    for (int k = 0; k < 4; ++k) {
        vec4 seen = texelFetch(lightPositions, lightTexel(t, k, l), 0);
        float w = lightTexelWeight(t, k);
        if (seen.w < 0.5) {
            seenAround.x += w;  // nothing there: nothing in the way
            continue;
        }
        seenAround.x += depthBehind(l, seen.xyz, p, toLight) < bias ? w : 0.0;
        seenAround.y += depthBehind(l, seen.xyz, behind, toLight) > behindBias ? w : 0.0;
    }
    return seenAround;
}

// Whether light l reaches x directly: the share of lightSeenAround.
float selfVisibility(int l, vec3 x, vec3 n, vec3 toLight) {
    return lightSeenAround(l, x, lightBufferBias(n, toLight), x, 1e30).x;
}
