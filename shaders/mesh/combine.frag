// Combine (Dal Corso et al. 2017, pass 3): look the visible point up in every scattering map
// like a shadow map, average the layers that see it, apply the exit Fresnel factor, add an
// optional specular highlight; writes linear radiance.
#include "common/camera.glsl"
#include "common/lights.glsl"
#include "common/dirpole.glsl"
#include "common/surface_shadows.glsl"

in vec3 modelPosition;
in vec3 modelNormal;
in vec3 worldPosition;
in vec3 worldNormal;

#include "mesh/map_lookup.glsl"

in vec3 vertexRadiosity;     // the vertex-radiosity pass's value, interpolated
uniform float eta;
uniform float specularStrength;
uniform float shininess;
uniform vec3 environment;    // a uniform environment's radiance times the total diffuse reflectance

layout(location = 0) out vec4 fragColor;

void main() {
    MapLookup maps = lookUpScatteringMaps(modelPosition, normalize(modelNormal));
    // A point no layer sees (deep concavities) takes the radiosity interpolated from its
    // triangle's vertices, which the vertex pass filled in from the surface around them.
    vec3 radiosity = maps.weight > 0.0 ? maps.radiosity : vertexRadiosity;

    vec3 nWorld = normalize(worldNormal);
    if (!gl_FrontFacing) nWorld = -nWorld;
    vec3 wo = towardsViewer(worldPosition);
    float exitT = dirpoleFresnelT(eta, dot(wo, nWorld));
    // The maps hold the integral of T_in S_d E over the lit surface (S_d is per steradian), so the
    // radiance leaving towards the eye is that times the exit transmittance.
    vec3 color = exitT * radiosity + environment;
    if (specularStrength > 0.0) {
        for (int i = 0; i < lightCount; ++i) {
            vec3 radiance;
            vec3 l = lightDirectionAt(i, worldPosition, radiance);
            float nDotL = dot(nWorld, l);
            if (nDotL <= 0.0) continue;
            radiance *= volumeTransmittance(i, worldPosition, l) * meshShadow(i, worldPosition, nWorld, l, 0);
            vec3 h = normalize(l + wo);
            // The surface reflects what it does not transmit: 1 - T at the viewing angle.
            color += specularStrength * (1.0 - exitT) * radiance * nDotL * pow(max(dot(nWorld, h), 0.0), shininess);
        }
    }
    fragColor = vec4(max(color, vec3(0.0)), 1.0);  // linear radiance
}
