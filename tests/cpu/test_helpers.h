#pragma once
// Helpers for the CPU tests: binary files in a support TempDir and an ErrorKind matcher.

#include "sss/error.h"
#include "support/temp_dir.h"

#include <catch2/catch.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace sss::test {

/// Writes bytes to dir.path()/name and returns the full path.
inline std::filesystem::path writeBytes(const TempDir& dir, std::string_view name, const std::vector<uint8_t>& bytes) {
    return dir.write(name, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

/// Matches an sss::Error of the given kind.
class KindIs : public Catch::MatcherBase<sss::Error> {
public:
    explicit KindIs(sss::ErrorKind kind) : m_kind(kind) {}
    bool match(const sss::Error& e) const override { return e.kind() == m_kind; }
    std::string describe() const override { return "has ErrorKind " + std::to_string(static_cast<int>(m_kind)); }

private:
    sss::ErrorKind m_kind;
};

}  // namespace sss::test

/// Requires that expr throws sss::Error of `kind` whose what() satisfies `matcher`.
#define REQUIRE_SSS_ERROR(expr, kind, matcher)                                  \
    do {                                                                        \
        REQUIRE_THROWS_MATCHES(expr, sss::Error, sss::test::KindIs(kind));      \
        REQUIRE_THROWS_WITH(expr, matcher);                                     \
    } while (false)
