// What the combine pass reads per pixel of a textured material (src/mesh/textured_material.cpp),
// per texel of the reflectance texture's level 0 (or a finer grid, materialSurfaceRefine): the
// single-scattering albedo, and the textured rule's surroundings' part (shaders/mesh/
// textured_material.glsl). Computed when the material, its scale or the mesh's texture density
// change; mipmapped after. The albedo's alpha holds the mip level that the surroundings' own
// narrower square spans, so the combine filters them only over what their own blur does not.
layout(local_size_x = 8, local_size_y = 8) in;

#define TEXTURED_MATERIAL 1
#include "mesh/textured_material.glsl"

layout(rgba16f, binding = 0) writeonly uniform image2D surfaceAlbedo;
layout(rgba16f, binding = 1) writeonly uniform image2D surfaceSurroundings;

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(surfaceAlbedo);
    if (any(greaterThanEqual(texel, size))) return;
    vec2 uv = (vec2(texel) + 0.5) / vec2(size);
    vec3 albedo, gathered;
    materialSurface(uv, 0.0, albedo, gathered);
    vec3 sigmaTr = materialSigmaTr(uv, 0.0, albedo);
    float narrowest = SURROUNDING_NARROW / max(max(sigmaTr.r, max(sigmaTr.g, sigmaTr.b)), 1e-12);
    float blurLevel = surroundingLevel(narrowest) + materialSurfaceRefine;
    imageStore(surfaceAlbedo, texel, vec4(albedo, blurLevel));
    imageStore(surfaceSurroundings, texel, vec4(surroundingFactor(uv, sigmaTr), 1.0));
}
