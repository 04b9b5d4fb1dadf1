#pragma once
// Internal: a mesh carried into world space in double for the CPU mesh renderers (the mesh
// reference and the mesh random walk), with the checks of the model matrix both need.
#include "sss/error.h"
#include "sss/mesh.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace sss::detail {

struct WorldMesh {
    std::vector<glm::dvec3> positions;
    std::vector<glm::dvec3> normals;  // not normalised
    glm::dvec3 lo{0.0}, hi{0.0};      // the positions' bounds
    double sceneSize = 0.0;           // the bounds' diagonal
    double side = 1.0;                // -1 where the model matrix mirrors: geometric normals flip with it
};

/// Throws InvalidArgument, prefixed by `who`, for a model matrix that is not finite, is singular
/// or takes a position past the doubles.
inline WorldMesh toWorldMesh(const Mesh& mesh, const glm::mat4& model, const std::string& who) {
    const auto invalid = [&](const std::string& problem) {
        throw Error(ErrorKind::InvalidArgument, who + ": " + problem);
    };
    const glm::dmat4 m(model);
    const glm::dmat3 m3(m);
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) invalid("the model matrix must be finite");
    const double det = glm::determinant(m3);
    if (!std::isfinite(det) || std::abs(det) < 1e-300) invalid("the model matrix must not be singular");
    const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(m3));

    WorldMesh world;
    world.positions.resize(mesh.vertexCount());
    world.normals.resize(mesh.vertexCount());
    world.lo = glm::dvec3(std::numeric_limits<double>::infinity());
    world.hi = -world.lo;
    for (size_t i = 0; i < mesh.vertexCount(); ++i) {
        world.positions[i] = glm::dvec3(m * glm::dvec4(glm::dvec3(mesh.positions()[i]), 1.0));
        world.normals[i] = normalMatrix * glm::dvec3(mesh.normals()[i]);
        world.lo = glm::min(world.lo, world.positions[i]);
        world.hi = glm::max(world.hi, world.positions[i]);
    }
    world.sceneSize = glm::length(world.hi - world.lo);
    if (!std::isfinite(world.sceneSize)) invalid("the model matrix makes mesh positions non-finite");
    world.side = det < 0.0 ? -1.0 : 1.0;
    return world;
}

}  // namespace sss::detail
