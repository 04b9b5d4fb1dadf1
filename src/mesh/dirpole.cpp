// The directional dipole evaluated on the CPU in double by compiling the very text the shaders
// use (shaders/common/dirpole.glsl): `real` = double, `real3` = glm::dvec3, GLSL built-ins = glm.
#include "sss/bssrdf.h"

#include "sss/error.h"

#include <glm/glm.hpp>

#include <cmath>
#include <sstream>
#include <string>

namespace sss {
namespace dirpole_cpp {
using namespace glm;
using real = double;
using real3 = glm::dvec3;
#define SSS_CPP 1
#include "../../shaders/common/dirpole.glsl"
#undef SSS_CPP
}  // namespace dirpole_cpp

namespace {

dirpole_cpp::DirpoleParams toParams(const DipoleConstants& c) {
    dirpole_cpp::DirpoleParams p;
    p.sigmaTr = c.sigmaTr;
    p.D = c.D;
    p.de = c.de;
    p.sigmaT = c.sigmaT;
    p.eta = c.eta;
    p.cPhi = c.cPhi;
    p.cE = c.cE;
    p.A = c.A;
    p.normalization = c.normalization;
    p.profileScale = c.profileScale;
    for (int i = 0; i < kProfileIncidenceNodes; ++i) p.incidenceScale[i] = c.incidenceScale[static_cast<size_t>(i)];
    for (int i = 0; i < kProfileThicknessNodes; ++i)
        p.transmissionScale[i] = c.transmissionScale[static_cast<size_t>(i)];
    p.albedo = c.albedo;
    p.g = c.g;
    p.singleScattering = c.singleScattering;
    return p;
}

void checkPoint(const glm::dvec3& v, const char* name) {
    if (std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z)) return;
    std::ostringstream s;
    s << "BSSRDF evaluation: " << name << " must be finite, got (" << v.x << ", " << v.y << ", " << v.z << ')';
    throw Error(ErrorKind::InvalidArgument, s.str());
}

glm::dvec3 unit(const glm::dvec3& v, const char* name) {
    checkPoint(v, name);
    const double len = glm::length(v);
    if (!(len > 0.0) || !std::isfinite(len))
        throw Error(ErrorKind::InvalidArgument, std::string("BSSRDF evaluation: ") + name + " must be a non-zero direction");
    return v / len;
}

}  // namespace

double fresnelTransmittance(double eta, double cosTheta) { return dirpole_cpp::dirpoleFresnelT(eta, cosTheta); }

glm::dvec3 evaluateSd(const DipoleConstants& constants, const glm::dvec3& xi, const glm::dvec3& ni,
                      const glm::dvec3& wi, const glm::dvec3& xo, const glm::dvec3& no) {
    checkPoint(xi, "xi");
    checkPoint(xo, "xo");
    return dirpole_cpp::dirpoleSd(toParams(constants), xi, unit(ni, "ni"), unit(wi, "wi"), xo, unit(no, "no"));
}

glm::dvec3 evaluateBssrdf(const DipoleConstants& constants, const glm::dvec3& xi, const glm::dvec3& ni,
                          const glm::dvec3& wi, const glm::dvec3& xo, const glm::dvec3& no, const glm::dvec3& wo) {
    checkPoint(xi, "xi");
    checkPoint(xo, "xo");
    return dirpole_cpp::dirpoleBssrdf(toParams(constants), xi, unit(ni, "ni"), unit(wi, "wi"), xo, unit(no, "no"),
                                      unit(wo, "wo"));
}

glm::dvec3 evaluateSingleScattering(const DipoleConstants& constants, const glm::dvec3& n, const glm::dvec3& wi,
                                    const glm::dvec3& wo) {
    return dirpole_cpp::dirpoleSingleScattering(toParams(constants), unit(n, "n"), unit(wi, "wi"), unit(wo, "wo"));
}

}  // namespace sss
