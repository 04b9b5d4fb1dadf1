// Single-pass GPU ray casting, front to back, with the transfer function (post-classification).
// Variants (defines set by src/volume/ray_cast_pass.cpp):
//   SHADING_GRADIENT 0|1 : 0 = emission-absorption, 1 = gradient (Blinn-)Phong shading
#include "common/lights.glsl"
#include "common/blinn_phong.glsl"
#include "volume/ray_setup.glsl"

in vec2 ndc;

uniform sampler3D volumeTexture;
uniform sampler2D transferFunction;   // 1 row of TF_ENTRIES entries, entry i at value i/(N-1)
uniform float transferFunctionEntries;
uniform vec2 valueScaleOffset;        // TF coordinate = sample * x + y (data range -> [0,1])
uniform vec3 boxMin;
uniform vec3 boxMax;
uniform ivec3 volumeDims;
uniform float stepLength;             // model units
uniform float opacityExponent;        // stepLength / reference length (one voxel)
uniform float earlyTermination;       // stop when accumulated opacity reaches this
uniform int jitterEnabled;
uniform int maxSteps;
uniform sampler2D sceneDepth;         // depth of what the target already holds (opaque meshes)

#if SHADING_GRADIENT
uniform mat4 modelToWorld;
uniform mat3 normalToWorld;
uniform vec3 cameraPosition;
uniform float ambientStrength;
uniform float diffuseStrength;
uniform vec3 specularColor;
uniform float shininess;
uniform float gradientThreshold;   // |gradient| (per voxel) below which shading fades out
#endif

layout(location = 0) out vec4 fragColor;   // premultiplied colour, alpha = opacity

vec3 toTexture(vec3 p) { return (p - boxMin) / (boxMax - boxMin); }

vec4 classify(float value) {
    float x = clamp(value * valueScaleOffset.x + valueScaleOffset.y, 0.0, 1.0);
    float u = (x * (transferFunctionEntries - 1.0) + 0.5) / transferFunctionEntries;
    return texture(transferFunction, vec2(u, 0.5));
}

#if SHADING_GRADIENT
vec3 shade(vec3 p, vec3 tc, vec3 color) {
    // Central differences, one voxel apart on each axis; gradient in value units per voxel.
    vec3 h = 1.0 / vec3(volumeDims);
    vec3 g = vec3(texture(volumeTexture, tc + vec3(h.x, 0, 0)).r - texture(volumeTexture, tc - vec3(h.x, 0, 0)).r,
                  texture(volumeTexture, tc + vec3(0, h.y, 0)).r - texture(volumeTexture, tc - vec3(0, h.y, 0)).r,
                  texture(volumeTexture, tc + vec3(0, 0, h.z)).r - texture(volumeTexture, tc - vec3(0, 0, h.z)).r) *
             0.5 * valueScaleOffset.x;
    float magnitude = length(g);
    vec3 worldPosition = (modelToWorld * vec4(p, 1.0)).xyz;
    vec3 v = normalize(cameraPosition - worldPosition);
    // Surfaces face from high to low values; scale the model-space gradient by the box so
    // anisotropic boxes get correct normals.
    vec3 outward = normalToWorld * (-g * vec3(volumeDims) / (boxMax - boxMin));
    float outwardLength = length(outward);
    // A zero gradient has no direction (normalize would give NaN); fall back to the view vector.
    vec3 n = outwardLength > 1e-12 ? outward / outwardLength : v;
    if (dot(n, v) < 0.0) n = -n;   // two-sided: shade the side facing the viewer
    vec3 lit = ambientStrength * color;
    for (int i = 0; i < lightCount; ++i) {
        vec3 radiance;
        vec3 l = lightDirectionAt(i, worldPosition, radiance);
        lit += blinnPhong(n, l, v, radiance, diffuseStrength * color, specularColor, shininess);
    }
    // Homogeneous regions have no meaningful normal: fade to the unshaded colour there.
    return mix(color, lit, smoothstep(0.0, gradientThreshold, magnitude));
}
#endif

void main() {
    Ray ray = pixelRay(ndc);
    vec2 span = intersectBox(ray, boxMin, boxMax);
    // Rays end at opaque geometry already in the target: a mesh in front hides the volume, a
    // mesh inside it cuts the rays at its surface.
    float depth = texelFetch(sceneDepth, ivec2(gl_FragCoord.xy), 0).r;
    if (depth < 1.0) {
        vec4 hitWorld = inverseViewProjection * vec4(ndc, depth * 2.0 - 1.0, 1.0);
        vec3 hitModel = (worldToModel * vec4(hitWorld.xyz / hitWorld.w, 1.0)).xyz;
        span.y = min(span.y, dot(hitModel - ray.origin, ray.direction));
    }
    vec3 color = vec3(0.0);
    float alpha = 0.0;
    if (span.x < span.y) {
        float t = span.x + (jitterEnabled != 0 ? pixelJitter(gl_FragCoord.xy) : 0.5) * stepLength;
        for (int i = 0; i < maxSteps && t < span.y; ++i, t += stepLength) {
            vec3 p = ray.origin + t * ray.direction;
            vec3 tc = toTexture(p);
            float value = texture(volumeTexture, tc).r;
            vec4 tf = classify(value);
            if (tf.a <= 0.0) continue;
            // Opacity correction: the TF's opacity is defined per voxel length.
            float a = 1.0 - pow(1.0 - min(tf.a, 1.0), opacityExponent);
#if SHADING_GRADIENT
            vec3 c = shade(p, tc, tf.rgb);
#else
            vec3 c = tf.rgb;
#endif
            color += (1.0 - alpha) * a * c;
            alpha += (1.0 - alpha) * a;
            if (alpha >= earlyTermination) break;
        }
    }
    fragColor = vec4(color, alpha);
}
