// The range checks and texts of the option tables (sss/option_table.h).
#include "sss/option_table.h"

#include "util/format.h"

#include "sss/error.h"

#include <cctype>
#include <cmath>

namespace sss {
namespace {

std::string number(double v) { return detail::formatNumber(v); }

bool inRange(const OptionRange& r, double v) {
    const bool aboveMin = r.minExclusive ? v > r.min : v >= r.min;
    const bool belowMax = r.maxExclusive ? v < r.max : v <= r.max;
    return aboveMin && belowMax;
}

template <class T>
void check(const detail::OptionCheck& c, T value, bool integer) {
    const double v = static_cast<double>(value);
    if ((integer || std::isfinite(v)) && inRange(c.range, v)) return;
    std::string rule = describeRange(c.range, integer);
    if (!c.unit.empty()) rule += " (" + std::string(c.unit) + ")";
    if (c.vector) rule += " in every channel";
    throw Error(ErrorKind::InvalidArgument, std::string(c.owner), std::string(c.field),
                "must be " + rule + ", got " + detail::formatNumber(value));
}

}  // namespace

std::string describeRange(const OptionRange& r, bool integer) {
    const bool hasMin = std::isfinite(r.min), hasMax = std::isfinite(r.max);
    if (integer) {
        if (hasMin && hasMax) return "in " + number(r.min) + ".." + number(r.max);
        if (hasMin) return ">= " + number(r.min);
        if (hasMax) return "<= " + number(r.max);
        return "an integer";
    }
    if (hasMin && hasMax)
        return std::string("in ") + (r.minExclusive ? "(" : "[") + number(r.min) + ", " + number(r.max) +
               (r.maxExclusive ? ")" : "]");
    if (hasMin) return std::string("finite and ") + (r.minExclusive ? "> " : ">= ") + number(r.min);
    if (hasMax) return std::string("finite and ") + (r.maxExclusive ? "< " : "<= ") + number(r.max);
    return "finite";
}

std::string snakeCase(std::string_view name) {
    std::string out;
    for (char c : name) {
        if (std::isupper(static_cast<unsigned char>(c))) {
            out += '_';
            out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        } else {
            out += c;
        }
    }
    return out;
}

namespace detail {
void checkOptionValue(const OptionCheck& c, int value) { check(c, value, true); }
void checkOptionValue(const OptionCheck& c, float value) { check(c, value, false); }
void checkOptionValue(const OptionCheck& c, double value) { check(c, value, false); }
}  // namespace detail

}  // namespace sss
