// Combine (Dal Corso et al. 2017, pass 3): look the visible point up in every scattering map
// like a shadow map, average the layers that see it, apply the exit Fresnel factor, add the
// calibrated profile's single scattering and an optional specular highlight; writes linear
// radiance.
//
// Defines (src/mesh/combine_pass.cpp):
//   PER_VERTEX 0|1      : 1: the vertices' radiosity only, no map lookups (MeshCombine::PerVertex
//                         and VertexEstimate)
//   SURFACE_SHADOWS 0|1 : whether other meshes or volumes shadow this one (common/surface_shadows.glsl)
#ifndef PER_VERTEX
#define PER_VERTEX 0
#endif
#include "common/camera.glsl"
#include "common/lights.glsl"
#include "common/dirpole.glsl"
#include "common/surface_shadows.glsl"

in vec3 modelPosition;
in vec3 modelNormal;
in vec3 worldPosition;
in vec3 worldNormal;

#if !PER_VERTEX
#include "mesh/map_lookup.glsl"
#endif

in vec3 vertexRadiosity;     // the vertex-radiosity pass's value, interpolated
uniform float eta;
uniform float specularStrength;
uniform float shininess;
uniform vec3 environment;    // a uniform environment's radiance times the total diffuse reflectance
uniform DirpoleParams dipole;  // single scattering (dipole.singleScattering = 0: none)
uniform sampler2DArray lightPositions;          // the light buffer: what each light sees
uniform mat4 lightViewProjection[MAX_LIGHTS];  // world -> light-buffer clip space
uniform float lightTexelWorld;                 // a light-buffer texel's size at the object, world units

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

layout(location = 0) out vec4 fragColor;

void main() {
    // Cached combine: the vertices' radiosity only. Otherwise the maps, and a point no layer sees
    // (deep concavities) takes the radiosity interpolated from its triangle's vertices, which the
    // vertex pass filled in from the surface around them.
    vec3 radiosity = vertexRadiosity;
#if !PER_VERTEX
    MapLookup maps = lookUpScatteringMaps(modelPosition, normalize(modelNormal));
    if (maps.weight > 0.0) radiosity = maps.radiosity;
#endif

    vec3 nWorld = normalize(worldNormal);
    if (!gl_FrontFacing) nWorld = -nWorld;
    vec3 wo = towardsViewer(worldPosition);
    float exitT = dirpoleFresnelT(eta, dot(wo, nWorld));
    // The maps hold the integral of T_in S_d E over the lit surface (S_d is per steradian), so the
    // radiance leaving towards the eye is that times the exit transmittance.
    vec3 color = exitT * radiosity + environment;
    // One pass over the lights for both view-dependent terms: each light's direction, radiance
    // and shadows are found once.
    bool single = dipole.singleScattering > 0.0, specular = specularStrength > 0.0;
    if (single || specular) {
        for (int i = 0; i < lightCount; ++i) {
            vec3 radiance;
            vec3 l = lightDirectionAt(i, worldPosition, radiance);
            float nDotL = dot(nWorld, l);
            if (nDotL <= 0.0) continue;
            radiance *= nDotL * volumeTransmittance(i, worldPosition, l) * meshShadow(i, worldPosition, nWorld, l, 0);
            if (single) {
                float visible = selfVisibility(i, worldPosition, nWorld, l);
                if (visible > 0.0) color += visible * radiance * dirpoleSingleScattering(dipole, nWorld, l, wo);
            }
            if (specular) {
                vec3 h = normalize(l + wo);
                // The surface reflects what it does not transmit: 1 - T at the viewing angle.
                color += specularStrength * (1.0 - exitT) * radiance * pow(max(dot(nWorld, h), 0.0), shininess);
            }
        }
    }
    fragColor = vec4(max(color, vec3(0.0)), 1.0);  // linear radiance
}
