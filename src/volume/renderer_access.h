#pragma once
// The internal hooks through which a hybrid scene (src/hybrid) hands shared lighting to a
// volume renderer and reads its light volumes. Implemented in volume_scattering_renderer.cpp.
#include "lighting/shadows.h"
#include "sss/bounds.h"
#include "sss/volume_scattering_renderer.h"

#include <optional>

namespace sss::detail {

struct VolumeRendererAccess {
    /// Shadows the ray caster applies to each light's light volume (null: none).
    static void setMeshShadows(VolumeScatteringRenderer& r, const MeshShadowMaps* shadows);
    /// Brings the light volumes up to date without ray casting (scattering modes only).
    static void updateLightVolumes(VolumeScatteringRenderer& r);
    /// The light volumes and placement, or null when the renderer is not in a scattering mode.
    static std::optional<VolumeShadows> shadows(const VolumeScatteringRenderer& r);
    static Bounds worldBounds(const VolumeScatteringRenderer& r);
};

}  // namespace sss::detail
