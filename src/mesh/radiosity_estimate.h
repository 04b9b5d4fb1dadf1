#pragma once
// What the radiosity estimator (shaders/mesh/radiosity_estimate.glsl) reads: the lights, the
// light buffer that says which surface each light sees, the profile and the disk sampling. Both
// the scattering maps (per texel) and the evaluate-once vertex estimate (per vertex) use it.
#include "gl/program.h"
#include "gl/texture.h"
#include "lighting/shadows.h"
#include "mesh/textured_material.h"
#include "sss/bssrdf.h"
#include "sss/light.h"

#include <glm/mat4x4.hpp>

#include <vector>

namespace sss::detail {

struct ScatteringSampling {
    float diskRadius = 0.0f;   ///< R, scene units
    float sigmaStar = 0.0f;    ///< far-field sampling rate, scene units^-1
    float sigmaNear = 0.0f;    ///< near-field sampling rate, >= sigmaStar
    int samplesPerLight = 1;   ///< proposals per light per frame
    float nearRadius = 0.0f;   ///< where estimateRadiositySplit splits the disk, scene units
};

struct RadiosityEstimateInputs {
    const std::vector<Light>& lights;
    /// The LightBufferPass's views, positions and normals for the same lights.
    const std::vector<glm::mat4>& lightViewProjections;
    const gl::Texture& lightPositions;
    const gl::Texture& lightNormals;
    const DipoleConstants& dipole;
    const ScatteringSampling& sampling;
    const SurfaceShadows* shadows = nullptr;  ///< hybrid scenes
    /// A textured material: each point gathers with its own profile (programs compiled with
    /// TEXTURED_MATERIAL 1); `dipole` is then its widest material, which chose the sampling.
    const TexturedMaterialGpu* material = nullptr;
    const gl::Texture* lightLogGathered = nullptr;  ///< LightBufferPass::logGathered, with `material`
    double millimetresPerUnit = 1000.0;  ///< scales the textured material's mean free path
};

/// Sets the estimator's uniforms on `program` and binds the light buffer to texture units 0 and 1.
/// `frameSeed` numbers the accumulated frame (0: the first).
void setRadiosityEstimateUniforms(const gl::Program& program, const RadiosityEstimateInputs& in, unsigned frameSeed);

}  // namespace sss::detail
