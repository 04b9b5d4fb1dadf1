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
}

}  // namespace sss::detail
