#pragma once
// Every texture unit a libsss pass binds, in one table. A unit matters only within one program,
// but two samplers of different types on one unit make a draw fail validation, and passes
// that share lighting inputs must agree on where those are.
namespace sss::detail::units {

// Inputs of a pass's own (volume, transfer function, light buffer, scattering maps...) are
// bound from unit 0 up; each pass's .cpp says which. No pass uses more than 4.
inline constexpr int kPassInputs = 0;

// Mesh passes (Blinn-Phong, scattering maps, combine): shaders/common/volume_shadow.glsl.
inline constexpr int kVolumeShadows = 8;  // 8..15: volumeShadowLight[MAX_LIGHTS]

// Volume ray cast (shaders/volume/ray_cast.frag) and the eye pass's lit-colour compute.
inline constexpr int kLightVolumes = 4;   // 4..11: lightVolumes[MAX_LIGHTS]
inline constexpr int kMeshShadowDepth = 12;
inline constexpr int kEyeVolume = 13;

// Light-volume propagation (shaders/volume/light_propagation.comp).
inline constexpr int kLitColour = 4;

}  // namespace sss::detail::units
