#pragma once
// Every texture unit a libsss pass binds, in one table. A unit matters only within one program,
// but two samplers of different types on one unit make a draw fail validation, and passes
// that share lighting inputs must agree on where those are. The highest unit used is 31: every
// GL 4.5 driver libsss runs on (Mesa, NVIDIA, AMD, Intel) has 32 per fragment shader.
namespace sss::detail::units {

// Inputs of a pass's own (volume, transfer function, light buffer, scattering maps...) are
// bound from unit 0 up; each pass's .cpp says which. No pass uses more than 4.
inline constexpr int kPassInputs = 0;

// Mesh passes (Blinn-Phong, scattering maps, combine): shaders/common/surface_shadows.glsl.
inline constexpr int kSurfaceMeshShadowDepth = 6;
inline constexpr int kSurfaceMeshShadowIds = 7;
inline constexpr int kVolumeShadows = 16;  // 16..31: volumeShadowLight[kMaxVolumeShadowPairs]
// Textured translucent materials (shaders/mesh/textured_material.glsl), in the mesh passes only:
// the volume ray caster's units below are free there.
inline constexpr int kMaterialReflectance = 8;
inline constexpr int kMaterialPathScale = 9;
inline constexpr int kMaterialTable = 10;
inline constexpr int kMaterialLogGathered = 11;
inline constexpr int kMaterialSurfaceAlbedo = 12;
inline constexpr int kMaterialSurroundings = 13;
// The combine's near-field points (mesh/near_field_cache.h), a buffer texture; a unit the mesh
// passes leave free (the ray caster's there).
inline constexpr int kNearFieldPoints = 14;

// Volume ray cast (shaders/volume/ray_cast.frag) and the eye pass's lit-colour compute.
inline constexpr int kLightVolumes = 4;   // 4..11: lightVolumes[MAX_LIGHTS]
inline constexpr int kMeshShadowDepth = 12;
inline constexpr int kEyeVolume = 13;
inline constexpr int kGradientVolume = 14;
inline constexpr int kPreintegration = 15;
// Post-classified rays read this instead of the pre-integrated table; 16 is free in the ray
// caster, which reads no volume shadows (those units belong to the mesh passes).
inline constexpr int kStepTransferFunction = 16;
// The multiple-scattering cache's light towards the viewer (volume/fluence_cache.h), in the ray
// caster only; or, where it evaluates the cache per sample, the cache's six textures.
inline constexpr int kCacheTowardsViewer = 17;
inline constexpr int kCacheTowardsViewerSlope = 18;
inline constexpr int kCacheTowardsViewerCap = 19;
inline constexpr int kCacheSources = 17;  // 17..22 (FluenceCache::bindSources)
// The classification's opacity alone, which the physical model's light carried back through the
// data reads (RayCastInputs::opacityTable).
inline constexpr int kOpacityTable = 23;

// Light-volume propagation (shaders/volume/light_propagation.comp).
inline constexpr int kLitColour = 4;

}  // namespace sss::detail::units
