#include "mesh/dipole_uniforms.h"

namespace sss::detail {

void setDipoleUniforms(const gl::Program& p, const std::string& name, const DipoleConstants& c) {
    p.set(name + ".sigmaTr", glm::vec3(c.sigmaTr));
    p.set(name + ".D", glm::vec3(c.D));
    p.set(name + ".de", glm::vec3(c.de));
    p.set(name + ".sigmaT", glm::vec3(c.sigmaT));
    p.set(name + ".eta", static_cast<float>(c.eta));
    p.set(name + ".cPhi", static_cast<float>(c.cPhi));
    p.set(name + ".cE", static_cast<float>(c.cE));
    p.set(name + ".A", static_cast<float>(c.A));
    p.set(name + ".normalization", static_cast<float>(c.normalization));
    p.set(name + ".profileScale", glm::vec3(c.profileScale));
    for (int i = 0; i < kProfileIncidenceNodes; ++i)
        p.set(name + ".incidenceScale[" + std::to_string(i) + "]", glm::vec3(c.incidenceScale[static_cast<size_t>(i)]));
    for (int i = 0; i < kProfileThicknessNodes; ++i)
        p.set(name + ".transmissionScale[" + std::to_string(i) + "]",
              glm::vec3(c.transmissionScale[static_cast<size_t>(i)]));
    p.set(name + ".albedo", glm::vec3(c.albedo));
    p.set(name + ".g", static_cast<float>(c.g));
    p.set(name + ".singleScattering", static_cast<float>(c.singleScattering));
}

}  // namespace sss::detail
