#pragma once
// Shared helpers for the CPU tests: a self-deleting temp directory and an ErrorKind matcher.

#include "sss/error.h"

#include <catch2/catch.hpp>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

namespace sss::test {

/// A fresh directory under the system temp dir, removed with everything in it on destruction.
class TempDir {
public:
    TempDir() {
        std::random_device rd;
        const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
        m_path = std::filesystem::temp_directory_path() /
                 ("sss_cpu_test_" + std::to_string(stamp) + "_" + std::to_string(rd()));
        std::filesystem::create_directories(m_path);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(m_path, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    const std::filesystem::path& path() const { return m_path; }

    /// Writes text to `name` inside the directory and returns the full path.
    std::filesystem::path writeText(const std::string& name, const std::string& text) const {
        std::filesystem::path p = m_path / name;
        std::ofstream(p, std::ios::binary) << text;
        return p;
    }

    /// Writes bytes to `name` inside the directory and returns the full path.
    std::filesystem::path writeBytes(const std::string& name, const std::vector<uint8_t>& bytes) const {
        std::filesystem::path p = m_path / name;
        std::ofstream out(p, std::ios::binary);
        out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
        return p;
    }

private:
    std::filesystem::path m_path;
};

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
