#include "gl/shader_source.h"

#include "sss/error.h"

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

namespace sss::detail {
namespace {

std::filesystem::path shaderDirOverride() {
    const char* v = std::getenv("SSS_SHADER_DIR");
    if (!v || !*v || std::strcmp(v, "0") == 0) return {};
    if (std::strcmp(v, "1") == 0) return SSS_SHADER_SOURCE_DIR;
    return v;
}

struct Expander {
    std::string (*load)(std::string_view);
    std::vector<std::string> files;
    std::set<std::string> included;
    std::string out;

    void expand(const std::string& path, const std::string& includedFrom, int includeLine) {
        if (!included.insert(path).second) return;  // each file once, like #pragma once
        std::string text;
        try {
            text = load(path);
        } catch (const Error& e) {
            if (includedFrom.empty()) throw;
            throw Error(ErrorKind::Io, includedFrom + ":" + std::to_string(includeLine) + ": cannot include \"" +
                                           path + "\": " + e.what());
        }
        const int index = static_cast<int>(files.size());
        files.push_back(path);
        out += "#line 1 " + std::to_string(index) + "\n";
        std::istringstream lines(text);
        std::string line;
        int lineNumber = 0;
        static const std::regex includeRe(R"(^\s*#\s*include\s+"([^"]+)\"\s*$)");
        static const std::regex versionRe(R"(^\s*#\s*version\b.*$)");
        while (std::getline(lines, line)) {
            ++lineNumber;
            std::smatch m;
            if (std::regex_match(line, m, includeRe)) {
                expand(m[1].str(), path, lineNumber);
                out += "#line " + std::to_string(lineNumber + 1) + " " + std::to_string(index) + "\n";
            } else if (std::regex_match(line, versionRe)) {
                // The preprocessor owns #version; keep line numbers by emitting an empty line.
                out += "\n";
            } else {
                out += line;
                out += '\n';
            }
        }
    }
};

}  // namespace

std::string loadShaderFile(std::string_view path) {
    const std::filesystem::path dir = shaderDirOverride();
    if (!dir.empty()) {
        const std::filesystem::path file = dir / std::filesystem::path(path);
        std::ifstream in(file, std::ios::binary);
        if (!in) throw Error(ErrorKind::Io, file.string() + ": cannot open shader file (SSS_SHADER_DIR)");
        std::ostringstream ss;
        ss << in.rdbuf();
        return ss.str();
    }
    for (const EmbeddedShader& s : embeddedShaders())
        if (s.path == path) return std::string(s.source);
    throw Error(ErrorKind::Io, "shader \"" + std::string(path) + "\" is not among the embedded shaders");
}

PreprocessedShader preprocessShader(std::string_view path, const ShaderDefines& defines,
                                    std::string (*load)(std::string_view)) {
    Expander e{load, {}, {}, "#version 450 core\n"};
    for (const auto& [name, value] : defines) e.out += "#define " + name + " " + value + "\n";
    e.expand(std::string(path), "", 0);
    return {std::move(e.out), std::move(e.files)};
}

std::string remapShaderLog(std::string_view log, const std::vector<std::string>& files) {
    static const std::regex mesaRe(R"(^(\d+):(\d+)\((\d+)\): (.*)$)");
    static const std::regex nvidiaRe(R"(^(\d+)\((\d+)\) : (.*)$)");
    std::istringstream lines{std::string(log)};
    std::string line, out;
    auto fileName = [&](const std::string& n) {
        const size_t i = std::stoul(n);
        return i < files.size() ? files[i] : "<source " + n + ">";
    };
    while (std::getline(lines, line)) {
        std::smatch m;
        if (std::regex_match(line, m, mesaRe))
            out += fileName(m[1]) + ":" + m[2].str() + ":" + m[3].str() + ": " + m[4].str();
        else if (std::regex_match(line, m, nvidiaRe))
            out += fileName(m[1]) + ":" + m[2].str() + ": " + m[3].str();
        else
            out += line;
        out += '\n';
    }
    return out;
}

}  // namespace sss::detail
