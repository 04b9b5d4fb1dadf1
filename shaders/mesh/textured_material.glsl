// A textured translucent material (sss::TexturedScattering; uniforms and textures set by
// src/mesh/textured_material.cpp): each point's profile from the reflectance texel under it and
// the mean free path. The table, in rows evenly spaced in sqrt(R), holds at reflectance R what depends on the reduced albedo
// alpha'(R) alone: the calibration factors, alpha' itself and `gathered`, the radiosity a flat
// surface of that material sends out per unit irradiance head-on (before exit Fresnel). Lengths
// come from the mean free path: sigma_t' = 1 / (mfp * scale).
// The passes that cache the radiosity (maps, vertices) store it divided by the point's
// `gathered`: the irradiance weighted by the entry points' R^m, blurred by the point's normalised
// profile, which varies smoothly whatever texel the point itself lies on. The combine multiplies
// by the `gathered` of the texel under the pixel and divides by its R^m, so the texture keeps its
// own resolution (docs/textured-materials.md).
#include "common/dirpole.glsl"

// The rule for a pair of points (docs/textured-materials.md): the light from x_i reaching x_o is
// x_o's profile times (R(x_i) / R(x_o))^ENTRY_REFLECTANCE_EXPONENT; 0 is the exit point's
// material alone, 1 weights each entry point by its own reflectance.
#ifndef ENTRY_REFLECTANCE_EXPONENT
#define ENTRY_REFLECTANCE_EXPONENT 0.5  // detail::kEntryReflectanceExponent
#endif
#ifndef MIN_ENTRY_REFLECTANCE
#define MIN_ENTRY_REFLECTANCE 1e-3  // detail::kMinEntryReflectance
#endif
#ifndef TEXTURED_TABLE_ROWS
#define TEXTURED_TABLE_ROWS 256  // kTexturedTableRows
#endif

uniform sampler2D materialReflectance;  // the base colour, decoded to linear reflectance
uniform sampler2D materialPathScale;    // red: factor on the mean free path
uniform sampler2D materialTable;        // 4 texels per row, TEXTURED_TABLE_ROWS rows
uniform vec3 materialSigmaT;            // 1 / mean free path, scene units^-1
// What the untextured reference material (the near field's and the environment's) gathers under
// even light: a point's own `gathered` over it scales those terms to the point.
uniform vec3 referenceGathered;

struct SurfaceMaterial {
    DirpoleParams params;
    vec3 gathered;
    vec3 entryWeight;  // R^ENTRY_REFLECTANCE_EXPONENT: the light buffer stores it per entry point
};

vec3 entryWeightOf(vec3 reflectance) {
    return pow(max(reflectance, vec3(MIN_ENTRY_REFLECTANCE)), vec3(ENTRY_REFLECTANCE_EXPONENT));
}

vec3 entryWeight(vec2 uv, float lod) { return entryWeightOf(textureLod(materialReflectance, uv, lod).rgb); }

vec4 materialRow(float reflectance, int column) {
    float y = (sqrt(clamp(reflectance, 0.0, 1.0)) * float(TEXTURED_TABLE_ROWS - 1) + 0.5) / float(TEXTURED_TABLE_ROWS);
    return textureLod(materialTable, vec2((float(column) + 0.5) * 0.25, y), 0.0);
}

// What the combine pass needs per pixel, without the rest of the profile: the single-scattering
// albedo and what the point gathers under even light (one table texel per channel).
void materialSurface(vec2 uv, float lod, out vec3 albedo, out vec3 gathered, out vec3 entryWeight) {
    vec3 reflectance = textureLod(materialReflectance, uv, lod).rgb;
    entryWeight = entryWeightOf(reflectance);
    for (int c = 0; c < 3; ++c) {
        vec4 t3 = materialRow(reflectance[c], 3);
        albedo[c] = t3.y;
        gathered[c] = t3.z;
    }
}

// `base` supplies what the texture does not change (eta, the Fresnel constants, the disk's
// profileScale, the single-scattering weight and g).
SurfaceMaterial materialAt(DirpoleParams base, vec2 uv, float lod) {
    SurfaceMaterial m;
    m.params = base;
    vec3 reflectance = textureLod(materialReflectance, uv, lod).rgb;
    m.entryWeight = entryWeightOf(reflectance);
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
