#include "mesh/combine_pass.h"

#include "lighting/camera_uniforms.h"
#include "lighting/light_uniforms.h"
#include "lighting/texture_units.h"
#include "mesh/dipole_uniforms.h"

#include <glm/matrix.hpp>

#include <string>

namespace sss::detail {

const gl::Program& CombinePass::program(bool perVertex, bool surfaceShadows, bool textured, bool vertexEffective,
                                        int nearField) const {
    std::optional<gl::Program>& slot = m_programs[16 * nearField + (vertexEffective ? 8 : 0) + (textured ? 4 : 0) +
                                                  (perVertex ? 2 : 0) + (surfaceShadows ? 1 : 0)];
    if (!slot) {
        ShaderDefines defines = texturedMaterialDefines(textured);
        defines.insert(defines.end(), {{"MAX_CAMERAS", std::to_string(kMaxScatteringCameras)},
                                       {"NEAR_FIELD_NODES", std::to_string(kNearFieldNodes)},
                                       {"NEAR_FIELD_TAPS", std::to_string(kNearFieldTaps)},
                                       {"PER_VERTEX", perVertex ? "1" : "0"},
                                       {"SURFACE_SHADOWS", surfaceShadows ? "1" : "0"},
                                       {"VERTEX_EFFECTIVE", vertexEffective ? "1" : "0"},
                                       {"NEAR_FIELD", std::to_string(nearField)}});
        slot = gl::Program::link({{GL_VERTEX_SHADER, "mesh/combine.vert"}, {GL_FRAGMENT_SHADER, "mesh/combine.frag"}},
                                 defines);
    }
    return *slot;
}

void CombinePass::run(const CombineInputs& in, const CombineSettings& s) const {
    const bool vertexEffective = s.material && in.vertexEffective;
    const int nearField = s.nearFieldCache ? 2 : s.nearField.radius > 0.0f ? 1 : 0;
    const gl::Program& p = program(s.perVertex, castsSurfaceShadows(in.shadows, in.lights.size()), s.material != nullptr,
                                   vertexEffective, nearField);
    p.set("model", in.model);
    p.set("viewProjection", in.camera.projection(in.aspect) * in.camera.view());
    p.set("normalMatrix", glm::mat3(glm::transpose(glm::inverse(in.model))));
    setCameraUniforms(p, in.camera);
    if (in.maps)
        setMapLookupUniforms(p, in.cameras, *in.maps, s.lookup);
    else
        setMapLookupUnits(p);  // never sampled (perVertex), but the samplers need their own units
    p.set("eta", s.eta);
    p.set("specularStrength", s.specularStrength);
    p.set("shininess", s.shininess);
    p.set("environment", s.environment);
    p.set("accumulatedRadianceScale", in.accumulatedRadianceScale);
    setDipoleUniforms(p, "dipole", s.dipole);
    setNearFieldUniforms(p, s.nearField);
    if (s.material) s.material->bind(p, s.millimetresPerUnit);
    p.set("lightTexelWorld", in.lightBuffer.texelWorld(in.mesh, in.model));
    p.set("lightPositions", units::kPassInputs + 2);
    p.set("lightNormals", units::kPassInputs + 3);
    for (size_t i = 0; i < in.lightBuffer.viewProjections().size(); ++i)
        p.set("lightViewProjection[" + std::to_string(i) + "]", in.lightBuffer.viewProjections()[i]);
    in.lightBuffer.positions().bind(units::kPassInputs + 2);
    in.lightBuffer.normals().bind(units::kPassInputs + 3);
    setLightUniforms(p, in.lights);
    setSurfaceShadowUniforms(p, in.shadows, in.lights.size());
    in.vertexRadiosity.bindStorage(0);
    if (vertexEffective) in.vertexEffective->bindStorage(1);
    if (s.nearFieldCache) {
        s.nearFieldCache->bind(p, /*withRadiosity=*/s.material == nullptr);
        in.mesh.drawCornersOpaque(p);
    } else {
        in.mesh.drawOpaque(p);
    }
    for (GLuint b : {0, 1, 4}) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, 0);
}

}  // namespace sss::detail
