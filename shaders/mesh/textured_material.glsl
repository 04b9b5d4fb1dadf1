// A textured translucent material (sss::TexturedScattering; uniforms and textures set by
// src/mesh/textured_material.cpp): each point's profile from the reflectance texel under it and
// the mean free path. The table, in rows evenly spaced in sqrt(R), holds at reflectance R what depends on the reduced albedo
// alpha'(R) alone: the calibration factors, alpha' itself and `gathered`, the radiosity a flat
// surface of that material sends out per unit irradiance head-on (before exit Fresnel). Lengths
// come from the mean free path: sigma_t' = 1 / (mfp * scale).
// The rule for points of different texels (mesh/reflectance_table.h, docs/textured-materials.md):
// x_o's profile normalised to unit `gathered`, times the geometric mean of the entry points'
// `gathered` weighted by the light each brings (share 1 - SURROUNDING_SHARE) and of the texture's
// around x_o (SURROUNDING_SHARE). The light buffer holds ln gathered per entry texel; the passes
// that cache the radiosity (maps, vertices) apply the entries' part, the combine the
// surroundings' part per pixel from materialLogGathered's mip chain.
#include "common/dirpole.glsl"

#ifndef MIN_GATHERED
#define MIN_GATHERED 1e-6  // detail::kMinGathered
#endif
#ifndef SURROUNDING_SHARE
#define SURROUNDING_SHARE 0.5  // detail::kSurroundingShare
#endif
#ifndef SURROUNDING_NARROW
#define SURROUNDING_NARROW 0.25  // detail::kSurroundingWidths
#define SURROUNDING_WIDE 2.0
#endif
#ifndef TEXTURED_TABLE_ROWS
#define TEXTURED_TABLE_ROWS 256  // kTexturedTableRows
#endif

uniform sampler2D materialReflectance;  // the base colour, decoded to linear reflectance
uniform sampler2D materialPathScale;    // red: factor on the mean free path
uniform sampler2D materialTable;        // 4 texels per row, TEXTURED_TABLE_ROWS rows
uniform vec3 materialSigmaT;            // 1 / mean free path, scene units^-1
uniform sampler2D materialLogGathered;  // ln gathered per texel, mipmapped (detail::LogGatheredMips)
uniform float materialTexelsPerUnit;    // texels per scene unit on the mesh (detail::meanTexelDensity)
// Per texel, mipmapped (shaders/mesh/textured_surface.comp): what the combine reads.
uniform sampler2D materialSurfaceAlbedo;  // rgb: the single-scattering albedo; a: the surroundings' blur level
uniform sampler2D materialSurroundings;   // rgb: surroundingFactor at the texel's own sigma_tr
uniform float materialSurfaceRefine;      // log2 of their texels per reflectance texel
// What the untextured reference material (the near field's and the environment's) gathers under
// even light: a point's own `gathered` over it scales those terms to the point.
uniform vec3 referenceGathered;

struct SurfaceMaterial {
    DirpoleParams params;
    vec3 gathered;
};

vec4 materialRow(float reflectance, int column) {
    float y = (sqrt(clamp(reflectance, 0.0, 1.0)) * float(TEXTURED_TABLE_ROWS - 1) + 0.5) / float(TEXTURED_TABLE_ROWS);
    return textureLod(materialTable, vec2((float(column) + 0.5) * 0.25, y), 0.0);
}

// What the combine pass needs per pixel, without the rest of the profile: the single-scattering
// albedo and what the point gathers under even light (one table texel per channel).
void materialSurface(vec2 uv, float lod, out vec3 albedo, out vec3 gathered) {
    vec3 reflectance = textureLod(materialReflectance, uv, lod).rgb;
    for (int c = 0; c < 3; ++c) {
        vec4 t3 = materialRow(reflectance[c], 3);
        albedo[c] = t3.y;
        gathered[c] = t3.z;
    }
}

// The effective transport coefficient of a point of that albedo (g = 0: reduced and unreduced agree).
vec3 materialSigmaTr(vec2 uv, float lod, vec3 albedo) {
    float scale = max(textureLod(materialPathScale, uv, lod).r, 1.0 / 255.0);
    return materialSigmaT / scale * sqrt(3.0 * max(vec3(1.0) - albedo, vec3(0.0)));
}

// `base` supplies what the texture does not change (eta, the Fresnel constants, the disk's
// profileScale, the single-scattering weight and g).
SurfaceMaterial materialAt(DirpoleParams base, vec2 uv, float lod) {
    SurfaceMaterial m;
    m.params = base;
    vec3 reflectance = textureLod(materialReflectance, uv, lod).rgb;
    float scale = max(textureLod(materialPathScale, uv, lod).r, 1.0 / 255.0);
    for (int c = 0; c < 3; ++c) {
        vec4 t0 = materialRow(reflectance[c], 0), t1 = materialRow(reflectance[c], 1);
        vec4 t2 = materialRow(reflectance[c], 2), t3 = materialRow(reflectance[c], 3);
        m.params.incidenceScale[0][c] = t0.x;
        m.params.incidenceScale[1][c] = t0.y;
        m.params.incidenceScale[2][c] = t0.z;
        m.params.incidenceScale[3][c] = t0.w;
        m.params.incidenceScale[4][c] = t1.x;
        m.params.incidenceScale[5][c] = t1.y;
        m.params.transmissionScale[0][c] = t1.z;
        m.params.transmissionScale[1][c] = t1.w;
        m.params.transmissionScale[2][c] = t2.x;
        m.params.transmissionScale[3][c] = t2.y;
        m.params.transmissionScale[4][c] = t2.z;
        m.params.transmissionScale[5][c] = t2.w;
        m.params.transmissionScale[6][c] = t3.x;
        float albedo = t3.y;
        float sigmaT = materialSigmaT[c] / scale;
        float D = 1.0 / (3.0 * sigmaT);
        m.params.D[c] = D;
        m.params.sigmaTr[c] = sigmaT * sqrt(3.0 * max(1.0 - albedo, 0.0));
        m.params.de[c] = 2.131 * D / sqrt(max(albedo, 1e-12));
        m.params.sigmaT[c] = sigmaT;  // g = 0: reduced and unreduced agree
        m.params.albedo[c] = albedo;
        m.gathered[c] = t3.z;
    }
    return m;
}

// ln gathered at a point, from level 0 of the chain: what the light buffer stores per entry texel.
vec3 logGathered(vec2 uv) { return textureLod(materialLogGathered, uv, 0.0).rgb; }

// The entries' part of the rule, from their light-weighted mean ln gathered.
vec3 entriesFactor(vec3 meanLog) { return exp((1.0 - SURROUNDING_SHARE) * meanLog); }

float surroundingLevel(float width) {
    float texels = width * materialTexelsPerUnit;
    return texels > 1.0 ? log2(texels) : 0.0;
}

// The surroundings' part of the rule at a point of transport coefficient sigmaTr (per scene
// unit): per channel the mean of the chain at two levels (detail::kSurroundingWidths).
vec3 surroundingFactor(vec2 uv, vec3 sigmaTr) {
    vec3 meanLog;
    for (int c = 0; c < 3; ++c) {
        float diffusionLength = 1.0 / max(sigmaTr[c], 1e-12);
        meanLog[c] = 0.5 * (textureLod(materialLogGathered, uv, surroundingLevel(SURROUNDING_NARROW * diffusionLength))[c] +
                            textureLod(materialLogGathered, uv, surroundingLevel(SURROUNDING_WIDE * diffusionLength))[c]);
    }
    return exp(SURROUNDING_SHARE * meanLog);
}
