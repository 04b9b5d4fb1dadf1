#pragma once
// Numbers in messages: the shortest text that reads back as the value ("0", "0.25", "1e+30",
// "nan"), never printf's "%f" ("0.000000"), and vectors as "(x, y, z)".
#include "sss/api.h"  // SSS_API: sss::io, sss::reference and sss::scene call these in a shared build
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <string>

namespace sss::detail {

SSS_API std::string formatNumber(double value);
SSS_API std::string formatNumber(float value);
SSS_API std::string formatNumber(long long value);
inline std::string formatNumber(int value) { return formatNumber(static_cast<long long>(value)); }
inline std::string formatNumber(unsigned value) { return formatNumber(static_cast<long long>(value)); }
inline std::string formatNumber(long value) { return formatNumber(static_cast<long long>(value)); }
inline std::string formatNumber(unsigned long long value) { return std::to_string(value); }
inline std::string formatNumber(unsigned long value) { return std::to_string(value); }
SSS_API std::string formatVec(glm::vec3 v);
SSS_API std::string formatVec(glm::dvec3 v);
SSS_API std::string formatVec(glm::dvec4 v);

}  // namespace sss::detail
