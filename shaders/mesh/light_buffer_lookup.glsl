// The light buffer (src/mesh/light_buffer_pass.h) as the estimator, the near field and the
// combine pass read it: what surface each light sees, and whether a point is that surface.
#include "common/lights.glsl"

uniform sampler2DArray lightPositions;           // xyz world, w = 1 where covered; one layer per light
uniform mat4 lightViewProjection[MAX_LIGHTS];    // world -> light-buffer clip space
uniform float lightTexelWorld;                   // a light-buffer texel's size at the object, world units

// Whether light l reaches x directly, judged like a shadow map against the light buffer: lit
// where the surface the light sees near x's texel is x itself; the 2x2 texels around x, blended
// bilinearly (a fraction, smooth across texels). The bias grows with the slope: one texel
// across, a surface tilted by theta to the light moves tan(theta) texels along it.
float selfVisibility(int l, vec3 x, vec3 n, vec3 toLight) {
    vec4 clip = lightViewProjection[l] * vec4(x, 1.0);
    vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    ivec2 size = textureSize(lightPositions, 0).xy;
    vec2 texel = uv * vec2(size) - 0.5;
    ivec2 base = ivec2(floor(texel));
    vec2 f = texel - vec2(base);
    bool point = lightVector[l].w != 0.0;
    float cosTheta = max(dot(n, toLight), 0.05);
    float bias = lightTexelWorld * (2.0 + 1.5 * sqrt(1.0 - cosTheta * cosTheta) / cosTheta);
    float lit = 0.0;
    for (int k = 0; k < 4; ++k) {
        ivec2 o = ivec2(k & 1, k >> 1);
        ivec2 t = clamp(base + o, ivec2(0), size - 1);
        vec4 seen = texelFetch(lightPositions, ivec3(t, l), 0);
        // How much nearer the light the seen surface is than x (nothing there: no occluder).
        float nearer = seen.w < 0.5 ? -1.0
                       : point ? distance(x, lightVector[l].xyz) - distance(seen.xyz, lightVector[l].xyz)
                               : dot(seen.xyz - x, toLight);
        float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        lit += nearer < bias ? w : 0.0;
    }
    return lit;
}
