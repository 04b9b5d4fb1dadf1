#include "common/camera.glsl"
#include "common/lights.glsl"
#include "common/blinn_phong.glsl"
#include "common/surface_shadows.glsl"

in vec3 worldPosition;
in vec3 worldNormal;

uniform vec3 ambient;
uniform vec3 diffuseColor;
uniform vec3 specularColor;
uniform float shininess;

layout(location = 0) out vec4 fragColor;

void main() {
    vec3 v = towardsViewer(worldPosition);
    vec3 n = normalize(worldNormal);
    // Two-sided lighting: back faces seen through open meshes are lit like front faces.
    if (!gl_FrontFacing) n = -n;
    vec3 color = ambient * diffuseColor;
    for (int i = 0; i < lightCount; ++i) {
        vec3 radiance;
        vec3 l = lightDirectionAt(i, worldPosition, radiance);
        radiance *= volumeTransmittance(i, worldPosition, l);
        if (dot(n, l) > 0.0) radiance *= meshShadow(i, worldPosition, n, l, 1);
        color += blinnPhong(n, l, v, radiance, diffuseColor, specularColor, shininess);
    }
    fragColor = vec4(max(color, vec3(0.0)), 1.0);  // linear radiance
}
