#pragma once
// The near field (src/mesh/near_field.h) and each light's visibility (for the single
// scattering) evaluated once per light change at a grid of points on every triangle
// (shaders/mesh/near_field_cache.comp) and interpolated per pixel by the combine pass, instead
// of evaluated at every pixel of every frame. They depend on the lights and the surface only, so
// a camera move reads them back: three points per pixel instead of about 50 light-buffer reads.
// The points lie `spacing` apart, a light-buffer texel or two: the light buffer holds no finer
// detail. Knowing their triangle, the points also follow how its normals turn across the
// terminator (nearFieldRingLit in shaders/mesh/near_field.glsl). Measurements: docs/near-field.md.
#include "gl/buffer.h"
#include "gl/program.h"
#include "gl/texture.h"
#include "lighting/shadows.h"
#include "mesh/gpu_mesh.h"
#include "mesh/light_buffer_pass.h"
#include "mesh/near_field.h"
#include "sss/mesh.h"

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <optional>
#include <vector>

namespace sss::detail {

inline constexpr int kMaxNearFieldDivisions = 8;  // per triangle edge (3 bits in the packed layout)

/// Per triangle, how many points its grid has per edge less one (R), from its longest edge and
/// the spacing (both model units): ceil(longest / spacing), 1..kMaxNearFieldDivisions.
int nearFieldDivisions(float longestEdge, float spacing);

/// The grid's layout: per triangle its first point's index << 3 | (R - 1); per point its triangle.
/// Triangle t holds (R + 1)(R + 2) / 2 points (shaders/mesh/near_field_points.glsl).
struct NearFieldPointLayout {
    std::vector<uint32_t> triangles;
    std::vector<uint32_t> pointTriangles;
};
NearFieldPointLayout layoutNearFieldPoints(const std::vector<float>& longestEdges, float spacing);

struct NearFieldCacheInputs {
    const GpuMesh& mesh;
    const glm::mat4& model;
    const std::vector<Light>& lights;
    const LightBufferPass& lightBuffer;
    const SurfaceShadows* shadows = nullptr;  ///< hybrid scenes
    const NearFieldTable& nearField;
    float eta = 1.3f;
    float spacing = 0.0f;                     ///< between the points, model units (> 0)
};

class NearFieldCache {
public:
    /// Keeps each triangle's longest edge; creates no GL object before the first evaluate().
    explicit NearFieldCache(const Mesh& mesh);
    /// Evaluates the near field at every point, laying the points out again if the spacing changed.
    void evaluate(const NearFieldCacheInputs& in);
    std::size_t pointCount() const { return m_pointCount; }
    /// Adds the vertices' radiosity (rgb per vertex), interpolated to every point, to the points'
    /// near field, for an untextured combine to read both from the points; after evaluate() and
    /// whenever the radiosity changed (shaders/mesh/near_field_radiosity.comp).
    void addRadiosity(const GpuMesh& mesh, const gl::Buffer& vertexRadiosity);
    /// For the combine (NEAR_FIELD 2, drawn with GpuMesh::drawCornersOpaque): the points, with
    /// the radiosity added or without, as a buffer texture on their unit
    /// (lighting/texture_units.h), the triangles' entries as storage buffer 4
    /// (shaders/mesh/combine.vert).
    void bind(const gl::Program& program, bool withRadiosity) const;

private:
    std::optional<gl::Program> m_program, m_radiosityProgram;  // linked on first use
    std::vector<float> m_longestEdges;
    gl::Buffer m_triangles, m_pointTriangles, m_values;
    std::vector<glm::vec4> m_ringTables;  // packNearFieldRings of the table last uploaded
    gl::Buffer m_rings;                   // m_ringTables on the GPU
    gl::Buffer m_withRadiosity;  // m_values with the radiosity added (addRadiosity, RGBA32F), or larger
    gl::Texture m_valuesView, m_withRadiosityView;  // the combine reads the points as a buffer texture
    float m_spacing = 0.0f;
    std::size_t m_pointCount = 0;
    int m_texelsPerPoint = 0;  // RGBA16F: the near field and light 0's visibility, then 4 lights' each
};

}  // namespace sss::detail
