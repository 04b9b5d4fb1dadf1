// Shader preprocessing: includes, #line numbering, defines, log remapping, loading from disk.
#include "gl/shader_source.h"
#include "support/temp_dir.h"

#include <catch2/catch.hpp>
#include <sss/error.h>

#include <cstdlib>
#include <map>
#include <string>

using namespace sss;
using Catch::Contains;

namespace {

std::string fakeLoad(std::string_view path) {
    static const std::map<std::string, std::string, std::less<>> files = {
        {"main.frag", "#version 450 core\n#include \"a.glsl\"\n#include \"b.glsl\"\nvoid main() {}\n"},
        {"a.glsl", "#include \"b.glsl\"\nfloat a() { return b(); }\n"},
        {"b.glsl", "float b() { return 1.0; }\n"},
        {"broken.frag", "\n\n#include \"missing.glsl\"\n"},
    };
    const auto it = files.find(path);
    if (it == files.end()) throw Error(ErrorKind::Io, "no such test shader " + std::string(path));
    return it->second;
}

}  // namespace

TEST_CASE("shader includes expand once, in order, with #line directives", "[cpu][shaders]") {
    const detail::PreprocessedShader s = detail::preprocessShader("main.frag", {{"MODE", "2"}}, &fakeLoad);
    REQUIRE(s.files == std::vector<std::string>{"main.frag", "a.glsl", "b.glsl"});
    // The preprocessor owns #version and the defines come right after it.
    CHECK(s.text.rfind("#version 450 core\n#define MODE 2\n#line 1 0\n", 0) == 0);
    CHECK(s.text.find("#version 450 core", 1) == std::string::npos);
    // b.glsl is included by a.glsl first and not again by main.frag.
    CHECK(s.text.find("float b()") < s.text.find("float a()"));
    CHECK(s.text.find("float b()") == s.text.rfind("float b()"));
    // Back in main.frag after each include, numbering resumes at the next line.
    CHECK_THAT(s.text, Contains("#line 3 0\n") && Contains("#line 4 0\nvoid main() {}"));
    CHECK_THAT(s.text, Contains("#line 1 2\nfloat b()"));
}

TEST_CASE("a missing include names the including file and line", "[cpu][shaders]") {
    CHECK_THROWS_WITH(detail::preprocessShader("broken.frag", {}, &fakeLoad),
                      Contains("broken.frag:3") && Contains("missing.glsl"));
}

TEST_CASE("driver logs are remapped to file:line", "[cpu][shaders]") {
    const std::vector<std::string> files{"main.frag", "common/lights.glsl"};
    const std::string mesa = detail::remapShaderLog("1:12(5): error: `x' undeclared\n", files);
    CHECK_THAT(mesa, Contains("common/lights.glsl:12:5: error: `x' undeclared"));
    const std::string nvidia = detail::remapShaderLog("0(7) : error C1008: undefined variable \"y\"\n", files);
    CHECK_THAT(nvidia, Contains("main.frag:7: error C1008"));
    CHECK_THAT(detail::remapShaderLog("5:1(1): error: z\n", files), Contains("<source 5>:1:1"));
    CHECK(detail::remapShaderLog("plain line\n", files) == "plain line\n");
}

TEST_CASE("SSS_SHADER_DIR reads shaders from disk instead of the embedded copies", "[cpu][shaders]") {
    // Every library shader is embedded; an unknown name is an error that names it.
    CHECK_FALSE(detail::loadShaderFile("volume/ray_cast.frag").empty());
    CHECK_THROWS_WITH(detail::loadShaderFile("no/such.glsl"), Contains("no/such.glsl"));
    test::TempDir dir;
    dir.write("custom.glsl", "float custom() { return 2.0; }\n");
    setenv("SSS_SHADER_DIR", dir.path().c_str(), 1);
    const std::string fromDisk = detail::loadShaderFile("custom.glsl");
    std::string missing;
    try {
        detail::loadShaderFile("volume/ray_cast.frag");
    } catch (const Error& e) {
        missing = e.what();
    }
    unsetenv("SSS_SHADER_DIR");
    CHECK(fromDisk == "float custom() { return 2.0; }\n");
    CHECK_THAT(missing, Contains("ray_cast.frag") && Contains("SSS_SHADER_DIR"));
}
