#pragma once
// Checks and helpers that every way of making a Mesh shares (Mesh::fromArrays in core, Mesh::load
// in io), so a file and an array are held to the same rules.
#include "sss/api.h"  // SSS_API: sss::io, sss::reference and sss::scene call these in a shared build
#include "sss/bounds.h"
#include "sss/mesh.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace sss::detail {

/// Every coordinate finite and within Mesh::kMaxCoordinate.
SSS_API bool isInRange(glm::vec3 v);
/// Finite and not zero.
SSS_API bool isUsableNormal(glm::vec3 n);
/// The unit vector along a usable normal, without overflow or denormal loss.
SSS_API glm::vec3 unitNormal(glm::vec3 n);
SSS_API Bounds boundsOf(const std::vector<glm::vec3>& positions);
/// Area-weighted vertex normals; vertices without one point away from centre.
SSS_API std::vector<glm::vec3> smoothNormals(const std::vector<glm::vec3>& positions,
                                     const std::vector<uint32_t>& indices, glm::vec3 centre);

}  // namespace sss::detail
