#pragma once
// Numbers in messages: the shortest text that reads back as the value ("0", "0.25", "1e+30",
// "nan"), never printf's "%f" ("0.000000"), and vectors as "(x, y, z)".
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <string>

namespace sss::detail {

std::string formatNumber(double value);
std::string formatNumber(float value);
std::string formatNumber(long long value);
inline std::string formatNumber(int value) { return formatNumber(static_cast<long long>(value)); }
inline std::string formatNumber(unsigned value) { return formatNumber(static_cast<long long>(value)); }
std::string formatVec(glm::vec3 v);
std::string formatVec(glm::dvec3 v);
std::string formatVec(glm::dvec4 v);

}  // namespace sss::detail
