#include "util/format.h"

#include <charconv>
#include <cmath>

namespace sss::detail {
namespace {

template <typename T>
std::string shortest(T value) {
    if (std::isnan(value)) return "nan";
    if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
    char buf[64];
    const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, value);
    return ec == std::errc() ? std::string(buf, end) : std::string("?");
}

}  // namespace

std::string formatNumber(double value) { return shortest(value); }
std::string formatNumber(float value) { return shortest(value); }
std::string formatNumber(long long value) { return std::to_string(value); }

std::string formatVec(glm::vec3 v) {
    return "(" + formatNumber(v.x) + ", " + formatNumber(v.y) + ", " + formatNumber(v.z) + ")";
}
std::string formatVec(glm::dvec3 v) {
    return "(" + formatNumber(v.x) + ", " + formatNumber(v.y) + ", " + formatNumber(v.z) + ")";
}
std::string formatVec(glm::dvec4 v) {
    return "(" + formatNumber(v.x) + ", " + formatNumber(v.y) + ", " + formatNumber(v.z) + ", " + formatNumber(v.w) +
           ")";
}

}  // namespace sss::detail
