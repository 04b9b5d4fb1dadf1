#include "lighting/shadows.h"

#include "core/light_geometry.h"
#include "lighting/light_uniforms.h"
#include "lighting/texture_units.h"

#include <algorithm>
#include <string>

namespace sss::detail {

std::uint64_t SurfaceShadows::revision() const {
    // FNV-1a over everything the shadows are made of; 0 stays "no shadows".
    if (!meshes && volumes.empty()) return 0;
    std::uint64_t hash = 1469598103934665603ull;
    auto mix = [&](std::uint64_t value) {
        hash ^= value;
        hash *= 1099511628211ull;
    };
    mix(meshes ? meshes->revision : 0);
    mix(selfId);
    for (const VolumeShadows& v : volumes) mix(v.revision);
    return hash == 0 ? 1 : hash;
}

namespace {

bool meshShadowsEnabled(const SurfaceShadows* shadows, std::size_t lightCount) {
    return castsMeshShadows(shadows ? shadows->meshes : nullptr, lightCount);
}

bool shadowsWith(const VolumeShadows& v, std::size_t lightCount) {
    return v.lightVolumes && v.lightVolumes->size() >= lightCount;
}

}  // namespace

bool castsSurfaceShadows(const SurfaceShadows* shadows, std::size_t lightCount) {
    if (meshShadowsEnabled(shadows, lightCount)) return true;
    if (!shadows || lightCount == 0) return false;
    return std::any_of(shadows->volumes.begin(), shadows->volumes.end(),
                       [&](const VolumeShadows& v) { return shadowsWith(v, lightCount); });
}

void setSurfaceShadowUniforms(const gl::Program& program, const SurfaceShadows* shadows, std::size_t lightCount) {
    // Samplers keep their own units even when unused: two samplers of different types on one
    // unit (they default to unit 0) make every draw fail validation.
    program.set("meshShadowDepth", units::kSurfaceMeshShadowDepth);
    program.set("meshShadowIds", units::kSurfaceMeshShadowIds);
    for (int i = 0; i < kMaxVolumeShadowPairs; ++i)
        program.set("volumeShadowLight[" + std::to_string(i) + "]", units::kVolumeShadows + i);

    const MeshShadowMaps* meshes = shadows ? shadows->meshes : nullptr;
    const bool meshesEnabled = meshShadowsEnabled(shadows, lightCount);
    program.set("meshShadowEnabled", meshesEnabled ? 1 : 0);
    if (meshesEnabled) {
        for (std::size_t i = 0; i < lightCount; ++i)
            program.set("meshShadowWorldToClip[" + std::to_string(i) + "]", meshes->worldToClip[i]);
        program.set("meshShadowTexel", meshes->texelWorldSize);
        program.set("meshShadowSelf", shadows->selfId);
        meshes->depth.bind(units::kSurfaceMeshShadowDepth);
        meshes->ids.bind(units::kSurfaceMeshShadowIds);
    }

    int volumes = 0;
    if (shadows && lightCount > 0) {
        const int fit = kMaxVolumeShadowPairs / static_cast<int>(lightCount);
        for (const VolumeShadows& v : shadows->volumes) {
            if (volumes >= fit) break;
            if (!shadowsWith(v, lightCount)) continue;
            program.set("volumeShadowWorldToTexture[" + std::to_string(volumes) + "]", v.worldToTexture);
            for (std::size_t i = 0; i < lightCount; ++i)
                (*v.lightVolumes)[i].bind(
                    static_cast<GLuint>(units::kVolumeShadows + volumes * static_cast<int>(lightCount) + static_cast<int>(i)));
            ++volumes;
        }
    }
    program.set("volumeShadowCount", volumes);
}

bool castsMeshShadows(const MeshShadowMaps* shadows, std::size_t lightCount) {
    return shadows && shadows->depth && shadows->worldToClip.size() >= lightCount;
}

std::uint64_t meshShadowRevision(const MeshShadowMaps* shadows, std::size_t lightCount) {
    return castsMeshShadows(shadows, lightCount) ? shadows->revision : 0;
}

void setMeshVisibilityUniforms(const gl::Program& program, const MeshShadowMaps& shadows,
                               const std::vector<Light>& lights) {
    program.set("meshShadowDepth", units::kMeshShadowDepth);
    for (std::size_t i = 0; i < lights.size(); ++i) {
        const std::string index = "[" + std::to_string(i) + "]";
        program.set("worldToShadowClip" + index, shadows.worldToClip[i]);
        const auto* directional = std::get_if<DirectionalLight>(&lights[i]);
        program.set("meshShadowLight" + index, directional ? glm::vec4(-glm::normalize(directional->direction), 0.0f)
                                                           : glm::vec4(*lightPosition(lights[i]), 1.0f));
    }
    program.set("meshShadowTexel", shadows.texelWorldSize);
    shadows.depth.bind(units::kMeshShadowDepth);
}

}  // namespace sss::detail
