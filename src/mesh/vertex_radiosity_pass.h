#pragma once
// Vertex radiosity: the scattering maps resolved at every vertex of the mesh, for the points no
// map sees. In deep concavities (the Happy Buddha's folds, the dragon's belly) some surface is
// hidden from all K cameras, and the combine pass has nothing to read there. Radiosity varies
// smoothly over the diffusion length, so such points take it from the surface around them: the
// vertices that some map sees keep their own value, and the others are filled breadth-first
// with the mean of their already-known neighbours, in rounds on the GPU (no read-back). The
// combine pass interpolates these values over each triangle and uses them where no layer sees
// the pixel's point.
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
    /// `adjacency` is the mesh's (the same vertices GpuMesh::upload() uploads); it is uploaded.
    explicit VertexRadiosityPass(const VertexAdjacency& adjacency);
    /// Resolves the maps at every vertex and fills the vertices no layer sees, all on the GPU.
    void run(const GpuMesh& mesh, const ScatteringCameras& cameras, const ScatteringMapPass& maps,
             const MapLookupSettings& settings);
    /// The fill alone (run() ends with it): every vertex whose radiosity() is unknown (a = 0)
    /// takes the mean of its known neighbours, ring by ring, for kFillRounds rounds.
    void fill();
    /// rgb radiosity per vertex, for shaders/mesh/combine.vert's VertexRadiosity block; a: 1 seen
    /// by a map, r + 1 filled in round r, 0 left unknown (no map sees its part of the mesh).
    const gl::Buffer& radiosity() const { return m_radiosity; }

    /// Rounds of the fill each run dispatches. Each round reaches one ring of neighbours
    /// further; the thesis meshes needed at most 14 (Happy Buddha, K = 4), and rounds after the
    /// last one that filled anything return at once. Vertices further than this from every
    /// vertex a map sees stay unknown (black).
    static constexpr int kFillRounds = 64;

private:
    gl::Program m_resolve, m_fill;
    gl::Buffer m_radiosity, m_neighbourStart, m_neighbours, m_filled;
    std::size_t m_vertexCount = 0;
};

}  // namespace sss::detail
