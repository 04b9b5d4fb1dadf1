#include "mesh/radiosity_estimate.h"

#include "lighting/light_uniforms.h"
#include "mesh/dipole_uniforms.h"

#include <string>

namespace sss::detail {

void setRadiosityEstimateUniforms(const gl::Program& p, const RadiosityEstimateInputs& in, unsigned frameSeed) {
    p.set("lightPositions", 0);
    p.set("lightNormals", 1);
    setLightUniforms(p, in.lights);  // lightVector/lightRadiance, as lights.glsl lays them out
    for (size_t i = 0; i < in.lights.size(); ++i)
        p.set("lightViewProjection[" + std::to_string(i) + "]", in.lightViewProjections[i]);
    setDipoleUniforms(p, "dipole", in.dipole);
    setSurfaceShadowUniforms(p, in.shadows, in.lights.size());
    p.set("diskRadius", in.sampling.diskRadius);
    p.set("sigmaStar", in.sampling.sigmaStar);
    p.set("sigmaNear", in.sampling.sigmaNear);
    p.set("samplesPerLight", in.sampling.samplesPerLight);
    p.set("nearRadius", in.sampling.nearRadius);
    p.set("frameSeed", frameSeed);
    if (in.material) {
        in.material->bind(p, in.millimetresPerUnit);
        p.set("lightLogGathered", 2);
        in.lightLogGathered->bind(2);
    }
    in.lightPositions.bind(0);
    in.lightNormals.bind(1);
}

}  // namespace sss::detail
