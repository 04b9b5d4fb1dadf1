// Combine (Dal Corso et al. 2017, pass 3): look the visible point up in every scattering map
// like a shadow map, average the layers that see it, apply the exit Fresnel factor, add the
// calibrated profile's single scattering, the profile's near field with the vertex estimate
// (shaders/mesh/near_field.glsl) and an optional specular highlight; writes linear radiance.
//
// Defines (src/mesh/combine_pass.cpp):
//   PER_VERTEX 0|1      : 1: the vertices' radiosity only, no map lookups (MeshCombine::PerVertex
//                         and VertexEstimate)
//   SURFACE_SHADOWS 0|1 : whether other meshes or volumes shadow this one (common/surface_shadows.glsl)
//   TEXTURED_MATERIAL 0|1: a textured material (mesh/textured_material.glsl): the cached radiosity
//                         takes the rule's surroundings' part per pixel; single scattering follows
//                         the pixel's material, the near field and the environment the whole rule
//   VERTEX_EFFECTIVE 0|1: a textured vertex estimate: the rule's entries' part per vertex for
//                         those (otherwise the pixel's own gathered stands in for the entries)
//   NEAR_FIELD 0|1|2    : the near field (mesh/near_field.glsl): none, evaluated here, or
//                         interpolated from its points (src/mesh/near_field_cache.h)
#ifndef PER_VERTEX
#define PER_VERTEX 0
#endif
#ifndef TEXTURED_MATERIAL
#define TEXTURED_MATERIAL 0
#endif
#ifndef VERTEX_EFFECTIVE
#define VERTEX_EFFECTIVE 0
#endif
#ifndef NEAR_FIELD
#define NEAR_FIELD 1
#endif
// Untextured, the near field's points hold the vertices' radiosity too (mesh/near_field_radiosity.comp).
#define RADIOSITY_IN_POINTS (NEAR_FIELD == 2 && !TEXTURED_MATERIAL)
#if RADIOSITY_IN_POINTS && !PER_VERTEX
#error "the points hold the vertices' radiosity, not the maps'"
#endif
#include "common/camera.glsl"
#include "common/lights.glsl"
#include "common/dirpole.glsl"
#include "common/surface_shadows.glsl"
#include "mesh/near_field.glsl"
#if TEXTURED_MATERIAL
#include "mesh/textured_material.glsl"
#endif

in vec3 modelPosition;
in vec3 modelNormal;
in vec3 worldPosition;
in vec3 worldNormal;
in vec2 texcoord;

#if !PER_VERTEX
#include "mesh/map_lookup.glsl"
#endif

#if !RADIOSITY_IN_POINTS
in vec3 vertexRadiosity;     // the vertex-radiosity pass's value, interpolated
#endif
#if VERTEX_EFFECTIVE
in vec3 vertexEffective;
#endif
uniform float eta;
uniform float specularStrength;
uniform float shininess;
uniform vec3 environment;    // a uniform environment's radiance times the total diffuse reflectance
uniform vec3 accumulatedRadianceScale;  // the lights' radiance now over the maps' and points' (per channel)
uniform DirpoleParams dipole;  // single scattering (dipole.singleScattering = 0: none)

// A compile-time constant: skipped behind a uniform instead, the per-pixel near field's code
// still cost a quarter of a fixed frame on llvmpipe.
#define PER_PIXEL_NEAR_FIELD (NEAR_FIELD == 1)
#if NEAR_FIELD == 2
#include "mesh/near_field_points.glsl"
uniform samplerBuffer nearFieldPoints;  // per point nearFieldTexelsPerPoint (near_field_cache.comp)
uniform int nearFieldTexelsPerPoint;
flat in uint nearFieldEntry;            // this fragment's triangle's (combine.vert)
in vec2 nearFieldWeights;               // of its corners b and c

// The three grid points around a pixel and their weights.
struct PointBlend {
    ivec3 first;  // each point's first texel
    vec3 weight;
};

// The grid points around this fragment in its triangle.
PointBlend pointsAround() {
    int r = nearFieldDivisions(nearFieldEntry), first = nearFieldFirstPoint(nearFieldEntry);
    vec2 w = clamp(nearFieldWeights, 0.0, 1.0);
    w /= max(w.x + w.y, 1.0);
    vec2 g = w * float(r);
    ivec2 cell = min(ivec2(g), ivec2(r - 1));
    if (cell.x + cell.y >= r) cell.x = r - 1 - cell.y;  // on the far edge: the cell below it
    vec2 f = g - vec2(cell);
    PointBlend b;
    if (f.x + f.y <= 1.0) {
        b.first = ivec3(nearFieldPointIndex(cell.x, cell.y, r), nearFieldPointIndex(cell.x + 1, cell.y, r),
                        nearFieldPointIndex(cell.x, cell.y + 1, r));
        b.weight = vec3(1.0 - f.x - f.y, f.x, f.y);
    } else {
        b.first = ivec3(nearFieldPointIndex(cell.x + 1, cell.y + 1, r), nearFieldPointIndex(cell.x, cell.y + 1, r),
                        nearFieldPointIndex(cell.x + 1, cell.y, r));
        b.weight = vec3(f.x + f.y - 1.0, 1.0 - f.x, 1.0 - f.y);
    }
    b.first = (first + b.first) * nearFieldTexelsPerPoint;
    return b;
}

// Texel k of the three points, blended.
vec4 blendedPointTexel(PointBlend b, int k) {
    return b.weight.x * texelFetch(nearFieldPoints, b.first.x + k) + b.weight.y * texelFetch(nearFieldPoints, b.first.y + k) +
           b.weight.z * texelFetch(nearFieldPoints, b.first.z + k);
}

// Light l's selfVisibility at the points; `nearTexel` is texel 0, which holds light 0's.
float pointVisibility(PointBlend b, vec4 nearTexel, int l) {
    return l == 0 ? nearTexel.a : blendedPointTexel(b, 1 + (l - 1) / 4)[(l - 1) % 4];
}
#endif

layout(location = 0) out vec4 fragColor;

void main() {
    // Cached combine: the vertices' radiosity only. Otherwise the maps, and a point no layer sees
    // (deep concavities) takes the radiosity interpolated from its triangle's vertices, which the
    // vertex pass filled in from the surface around them.
#if RADIOSITY_IN_POINTS
    vec3 radiosity = vec3(0.0);  // added with the near field below
#else
    vec3 radiosity = vertexRadiosity;
#endif
#if !PER_VERTEX
    MapLookup maps = lookUpScatteringMaps(modelPosition, normalize(modelNormal));
    if (maps.weight > 0.0) radiosity = maps.radiosity;
#endif

#if TEXTURED_MATERIAL
    // At the reflectance texture's level of detail, as the passes that cache the radiosity read
    // it; the surroundings, a blur themselves, only where the pixel is wider than that blur.
    float lod = textureQueryLod(materialReflectance, texcoord).y + materialSurfaceRefine;
    vec4 surface = textureLod(materialSurfaceAlbedo, texcoord, lod);
    DirpoleParams profile = dipole;  // single scattering needs only the pixel's albedo
    profile.albedo = surface.rgb;
    vec3 surroundings = textureLod(materialSurroundings, texcoord, max(lod - surface.a, 0.0)).rgb;
    radiosity *= surroundings;
#if VERTEX_EFFECTIVE
    vec3 entries = vertexEffective;
#else
    vec3 entries = surroundings;  // stands in for the entries' part (the environment's light is even)
#endif
    vec3 referenceScale = entries * surroundings / max(referenceGathered, vec3(1e-6));
    // The near field also by the pixel's material's share within its radius, as the vertices.
    vec3 nearFieldScale = referenceScale * nearFieldShareAt(surface.rgb);
#else
    DirpoleParams profile = dipole;
    vec3 referenceScale = vec3(1.0), nearFieldScale = vec3(1.0);
#endif
    vec3 nWorld = normalize(worldNormal);
    if (!gl_FrontFacing) nWorld = -nWorld;
    vec3 wo = towardsViewer(worldPosition);
    float exitT = dirpoleFresnelT(eta, dot(wo, nWorld));
    // The maps hold the integral of T_in S_d E over the lit surface (S_d is per steradian), so the
    // radiance leaving towards the eye is that times the exit transmittance.
    vec3 color = exitT * accumulatedRadianceScale * radiosity + environment * referenceScale;
    // One pass over the lights for the per-pixel terms: each light's direction, radiance and
    // shadows are found once.
    bool single = profile.singleScattering > 0.0, specular = specularStrength > 0.0;
#if NEAR_FIELD == 2
    PointBlend points = pointsAround();
    vec4 nearTexel = blendedPointTexel(points, 0);
    color += exitT * nearFieldScale * accumulatedRadianceScale * nearTexel.rgb;
#endif
    if (single || specular || PER_PIXEL_NEAR_FIELD) {
        for (int i = 0; i < lightCount; ++i) {
            vec3 radiance;
            vec3 l = lightDirectionAt(i, worldPosition, radiance);
            vec3 nearVisible, nearCovered, nearLit;
            if (PER_PIXEL_NEAR_FIELD) {
                nearFieldTaps(i, worldPosition, nWorld, l, 0.0, nearVisible, nearCovered, nearLit);
                color += exitT * radiance * nearFieldScale *
                         nearFieldBehindRadiosity(i, worldPosition, nWorld, l, eta, nearCovered);
            }
            float nDotL = dot(nWorld, l);
            if (nDotL <= 0.0) continue;
            radiance *= nDotL * volumeTransmittance(i, worldPosition, l) * meshShadow(i, worldPosition, nWorld, l, 0);
            if (single) {
#if NEAR_FIELD == 2
                float visible = pointVisibility(points, nearTexel, i);
#else
                float visible = selfVisibility(i, worldPosition, nWorld, l);
#endif
                if (visible > 0.0) color += visible * radiance * dirpoleSingleScattering(profile, nWorld, l, wo);
            }
            if (PER_PIXEL_NEAR_FIELD)
                color += exitT * radiance * nearVisible * nearFieldAt(nDotL) * nearFieldScale;
            if (specular) {
                vec3 h = normalize(l + wo);
                // The surface reflects what it does not transmit: 1 - T at the viewing angle.
                color += specularStrength * (1.0 - exitT) * radiance * pow(max(dot(nWorld, h), 0.0), shininess);
            }
        }
    }
    fragColor = vec4(max(color, vec3(0.0)), 1.0);  // linear radiance
}
