#pragma once
// Scattering maps (Dal Corso et al. 2017, pass 2): the object seen from K orthographic cameras on
// Halton directions around its bounding-box centre, locked to the model, rendered into the layers
// of an RGBA32F array in one draw. Each texel sums a Monte Carlo estimate of the light scattered
// to its surface point (shaders/mesh/scattering_map.frag); successive frames add new estimates,
// so a static scene converges. The alpha channel counts the frames a texel was covered.
#include "gl/framebuffer.h"
#include "gl/program.h"
#include "gl/texture.h"
#include "mesh/gpu_mesh.h"
#include "mesh/radiosity_estimate.h"

#include <glm/mat4x4.hpp>

#include <cstdint>
#include <optional>
#include <vector>

namespace sss::detail {

inline constexpr int kMaxScatteringCameras = 32;

struct ScatteringCameras {
    std::vector<glm::mat4> viewProjection;  ///< model space -> clip space, per camera
    std::vector<glm::vec3> axis;            ///< model space unit vector towards each camera
};

/// Direction k of K: Halton point (base 2, base 3) of index k+1 mapped to the unit sphere.
glm::vec3 haltonSphereDirection(int k);
ScatteringCameras makeScatteringCameras(int count, const Bounds& modelBounds);

struct ScatteringMapPassInputs {
    const GpuMesh& mesh;
    const glm::mat4& model;
    const ScatteringCameras& cameras;
    const RadiosityEstimateInputs& estimate;
};

class ScatteringMapPass {
public:
    explicit ScatteringMapPass(int cameras);
    int cameras() const { return m_cameras; }

    /// Empties the maps (next accumulate() starts from frame 0) at the given resolution.
    void reset(int resolution);
    /// Adds one frame of estimates.
    void accumulate(const ScatteringMapPassInputs& in);

    int frames() const { return m_frames; }
    const gl::Texture& maps() const { return m_maps; }
    const gl::Texture& depth() const { return m_depth; }

private:
    int m_cameras;
    gl::Program m_depthProgram;  // same geometry, trivial fragment shader: the depth pre-pass
    gl::Program m_program;
    std::optional<gl::Program> m_texturedProgram;  // TEXTURED_MATERIAL 1, linked on first use
    gl::Texture m_maps, m_depth;
    gl::Framebuffer m_framebuffer;
    int m_frames = 0;
};

}  // namespace sss::detail
