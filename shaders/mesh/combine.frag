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

uniform sampler2DArray scatteringMaps;   // rgb: radiosity summed over frames, a: frames (coverage)
uniform sampler2DArray scatteringDepth;  // depth of each layer's camera view
uniform int cameraCount;
uniform mat4 cameraViewProjection[MAX_CAMERAS];  // model space -> clip space of camera k
uniform vec3 cameraAxis[MAX_CAMERAS];            // model space, from the object towards camera k
uniform float depthBias;     // window-space depth
uniform float seamShrink;    // model units
uniform float eta;
uniform float specularStrength;
uniform float shininess;
uniform vec3 environment;    // a uniform environment's radiance times the total diffuse reflectance

layout(location = 0) out vec4 fragColor;

void main() {
    vec3 n = normalize(modelNormal);
    vec2 texel = 1.0 / vec2(textureSize(scatteringDepth, 0).xy);
    vec3 weighted = vec3(0.0), covered = vec3(0.0);
    float visibility = 0.0, coverage = 0.0;
    for (int k = 0; k < cameraCount; ++k) {
        // Move the lookup away from the silhouette as seen by camera k, where a texel may belong
        // to the background or to the other side of the object.
        vec3 axis = cameraAxis[k];
        vec3 p = modelPosition - seamShrink * (n - axis * dot(n, axis));
        vec4 clip = cameraViewProjection[k] * vec4(p, 1.0);
        vec3 window = clip.xyz / clip.w * 0.5 + 0.5;
        // 3x3 percentage-closer filter: the fraction of neighbours at least as far as this point.
        float v = 0.0;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                float stored = texture(scatteringDepth, vec3(window.xy + vec2(dx, dy) * texel, float(k))).r;
                v += window.z - depthBias <= stored ? 1.0 : 0.0;
            }
        v /= 9.0;
        vec4 map = texture(scatteringMaps, vec3(window.xy, float(k)));
        if (map.a <= 0.0) continue;     // the camera saw no surface there
        vec3 radiosity = map.rgb / map.a;  // mean over accumulated frames and covered texels
        weighted += v * radiosity;
        visibility += v;
        covered += radiosity;
        coverage += 1.0;
    }
    // A point no camera sees (deep concavities with few cameras) borrows the mean of the layers
    // that cover its pixel rather than going black.
    vec3 radiosity = visibility > 0.0 ? weighted / visibility : (coverage > 0.0 ? covered / coverage : vec3(0.0));

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
