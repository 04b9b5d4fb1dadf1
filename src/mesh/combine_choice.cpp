#include "mesh/combine_choice.h"

#include "sss/bssrdf.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include <algorithm>
#include <utility>
#include <vector>

namespace sss::detail {

float surfaceEdgeLength(const Mesh& mesh) {
    const std::vector<glm::vec3>& p = mesh.positions();
    const std::vector<std::uint32_t>& index = mesh.indices();
    std::vector<std::pair<float, double>> edgeAndArea;  // per triangle: longest edge, area
    edgeAndArea.reserve(index.size() / 3);
    double totalArea = 0.0;
    for (std::size_t i = 0; i + 2 < index.size(); i += 3) {
        const glm::vec3 a = p[index[i]], b = p[index[i + 1]], c = p[index[i + 2]];
        const float edge = std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
        const double area = 0.5 * glm::length(glm::cross(glm::dvec3(b - a), glm::dvec3(c - a)));
        edgeAndArea.emplace_back(edge, area);
        totalArea += area;
    }
    if (edgeAndArea.empty()) return 0.0f;
    std::sort(edgeAndArea.begin(), edgeAndArea.end());
    double area = 0.0;
    for (const auto& [edge, triangleArea] : edgeAndArea) {
        area += triangleArea;
        if (area >= 0.9 * totalArea) return edge;
    }
    return edgeAndArea.back().first;  // all degenerate
}

float largestScale(const glm::mat4& model) {
    // The largest singular value of the upper 3x3: power iteration on M^T M, which converges from
    // any start with a component along the top singular vector (three starts cover every case).
    const glm::dmat3 m(model);
    const glm::dmat3 gram = glm::transpose(m) * m;
    double largest = 0.0;
    for (int axis = 0; axis < 3; ++axis) {
        glm::dvec3 v(0.0);
        v[axis] = 1.0;
        v += glm::dvec3(0.31, 0.17, 0.11);
        for (int i = 0; i < 64; ++i) {
            const glm::dvec3 next = gram * v;
            const double length = glm::length(next);
            if (!(length > 0.0)) break;
            v = next / length;
        }
        largest = std::max(largest, glm::length(m * glm::normalize(v)));
    }
    return static_cast<float>(largest);
}

double edgeToDiffusionLength(float edgeLength, const ScatteringMaterial& material, double millimetresPerUnit) {
    // The closed-form dipole is enough here: sigma_tr and R_d do not depend on the calibration.
    const DipoleConstants c = deriveDipoleConstants(material, millimetresPerUnit, ScatteringProfile::Dipole);
    const glm::dvec3 reflectance = dipoleDiffuseReflectance(c);
    const double brightest = std::max({reflectance.x, reflectance.y, reflectance.z});
    double sigmaTr = 0.0;
    for (int i = 0; i < 3; ++i)
        if (reflectance[i] >= 0.1 * brightest) sigmaTr = std::max(sigmaTr, c.sigmaTr[i]);
    return static_cast<double>(edgeLength) * sigmaTr;
}

MeshCombine resolveCombine(MeshCombine requested, double edgeRatio, float nearField, double edgeOverRadius) {
    if (requested != MeshCombine::Automatic) return requested;
    if (edgeRatio <= kVertexEstimateMaxEdgeRatio) return MeshCombine::VertexEstimate;
    const bool followsShape = edgeOverRadius <= kVertexEstimateMaxEdgeOverRadius;
    return nearField > 0.0f && followsShape ? MeshCombine::VertexEstimate : MeshCombine::PerPixel;
}

}  // namespace sss::detail
