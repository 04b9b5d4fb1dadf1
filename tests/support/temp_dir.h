#pragma once
#include <filesystem>
#include <string>
#include <string_view>

namespace sss::test {

/// A fresh directory under the system temp dir, removed with everything in it on destruction.
class TempDir {
public:
    TempDir();
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::filesystem::path& path() const { return m_path; }
    /// Writes `contents` to path()/name and returns the full path.
    std::filesystem::path write(std::string_view name, std::string_view contents) const;

private:
    std::filesystem::path m_path;
};

}  // namespace sss::test
