#pragma once
// Vertex radiosity: the scattering maps resolved at every vertex of the mesh, for the points no
// map sees. In deep concavities (the Happy Buddha's folds, the dragon's belly) some surface is
// hidden from all K cameras, and the combine pass has nothing to read there. Radiosity varies
// smoothly over the diffusion length, so such points take it from the surface around them: the
// vertices that some map sees keep their own value, and the others are filled breadth-first
// with the mean of their already-known neighbours. The combine pass interpolates these values
// over each triangle and uses them where no layer sees the pixel's point.
#include "gl/buffer.h"
#include "gl/program.h"
#include "mesh/gpu_mesh.h"
#include "mesh/scattering_map_pass.h"
#include "sss/mesh.h"

#include <cstdint>
#include <vector>

namespace sss::detail {

struct MapLookupSettings {
    float depthBias = 0.0f;   ///< window-space depth
    float seamShrink = 0.0f;  ///< model units
    bool operator==(const MapLookupSettings&) const = default;
};

/// The texture units of shaders/mesh/map_lookup.glsl's samplers (0 and 1), without the maps.
void setMapLookupUnits(const gl::Program& program);
/// Sets the uniforms and binds the textures of shaders/mesh/map_lookup.glsl (units 0 and 1).
void setMapLookupUniforms(const gl::Program& program, const ScatteringCameras& cameras, const ScatteringMapPass& maps,
                          const MapLookupSettings& settings);

/// Which vertices share a triangle, in compressed rows: the neighbours of vertex v are
/// neighbours[start[v] .. start[v + 1]).
struct VertexAdjacency {
    std::vector<std::uint32_t> start, neighbours;
    std::size_t vertexCount() const { return start.empty() ? 0 : start.size() - 1; }
};
VertexAdjacency buildVertexAdjacency(const Mesh& mesh);

class VertexRadiosityPass {
public:
    /// `adjacency` is the mesh's (the same vertices GpuMesh::upload() uploads); it must outlive
    /// the pass.
    explicit VertexRadiosityPass(const VertexAdjacency& adjacency);
    /// Resolves the maps at every vertex and fills the vertices no layer sees (reads back to the
    /// CPU: a few hundred kilobytes, once per map update).
    void run(const GpuMesh& mesh, const ScatteringCameras& cameras, const ScatteringMapPass& maps,
             const MapLookupSettings& settings);
    /// rgb radiosity per vertex (a = 1), for shaders/mesh/combine.vert's VertexRadiosity block.
    const gl::Buffer& radiosity() const { return m_radiosity; }
    /// Vertices no layer saw in the last run (filled from neighbours).
    std::size_t unseenVertices() const { return m_unseen; }

private:
    gl::Program m_program;
    gl::Buffer m_resolved, m_radiosity;
    const VertexAdjacency& m_adjacency;
    std::size_t m_vertexCount = 0, m_unseen = 0;
};

}  // namespace sss::detail
