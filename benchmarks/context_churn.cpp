// sss-context-churn: creates and destroys GL contexts in a loop and reports how the process
// grows per cycle, to tell libsss's own leaks from the driver's (issue: per-context growth).
//
//   sss-context-churn [--mode MODE] [--cycles N]
//   MODE: context            an EglContext alone
//         bare-draw          an EglContext, one raw GL program (no libsss objects) and one draw
//         renderers          an EglContext with libsss volume and mesh renderers drawing a frame
//         one-context        the renderers of "renderers", rebuilt N times in a single context
//         bare-one-context   the program and draw of "bare-draw", repeated N times in a single context
//
// It prints the resident set growth per cycle after a warm-up, the growth of anonymous
// executable mappings (where JIT compilers put machine code) and what libsss still holds on
// the GPU (gpuMemoryInUse, which must be 0 once the renderers are gone).
#include <sss/sss.h>

#include <glad/gl.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <string>

namespace {

struct Footprint {
    long rssKb = 0;
    long anonymousExecutableKb = 0;
};

Footprint footprint() {
    Footprint f;
    std::ifstream status("/proc/self/status");
    for (std::string line; std::getline(status, line);)
        if (line.rfind("VmRSS:", 0) == 0) f.rssKb = std::stol(line.substr(6));
    std::ifstream maps("/proc/self/maps");
    for (std::string line; std::getline(maps, line);) {
        unsigned long begin = 0, end = 0;
        char perms[5] = {};
        if (std::sscanf(line.c_str(), "%lx-%lx %4s", &begin, &end, perms) != 3) continue;
        const bool anonymous = line.find('/') == std::string::npos && line.find('[') == std::string::npos;
        if (anonymous && perms[2] == 'x') f.anonymousExecutableKb += static_cast<long>((end - begin) / 1024);
    }
    return f;
}

// One program and one draw with nothing of libsss but the context.
void bareDraw() {
    const char* vs = "#version 450\nvoid main() { gl_Position = vec4(float(gl_VertexID & 1), float(gl_VertexID >> 1), 0, 1); }";
    const char* fs = "#version 450\nout vec4 c; uniform float k; void main() { c = vec4(k * gl_FragCoord.x); }";
    const GLuint program = glCreateProgram();
    for (auto [type, source] : {std::pair{GL_VERTEX_SHADER, vs}, std::pair{GL_FRAGMENT_SHADER, fs}}) {
        const GLuint shader = glCreateShader(type);
        glShaderSource(shader, 1, &source, nullptr);
        glCompileShader(shader);
        glAttachShader(program, shader);
        glDeleteShader(shader);
    }
    glLinkProgram(program);
    GLuint texture = 0, framebuffer = 0, vertexArray = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &texture);
    glTextureStorage2D(texture, 1, GL_RGBA8, 32, 32);
    glCreateFramebuffers(1, &framebuffer);
    glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, texture, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glViewport(0, 0, 32, 32);
    glCreateVertexArrays(1, &vertexArray);
    glBindVertexArray(vertexArray);
    glUseProgram(program);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glFinish();
    glDeleteVertexArrays(1, &vertexArray);
    glDeleteFramebuffers(1, &framebuffer);
    glDeleteTextures(1, &texture);
    glDeleteProgram(program);
}

void renderersFrame(const sss::Volume& volume, const sss::Mesh& mesh) {
    sss::RenderTarget target(64, 64);
    sss::Camera camera;
    camera.frame(volume.worldBounds());
    sss::VolumeScatteringRenderer volumes({.shading = sss::VolumeShading::Scattering});
    volumes.setVolume(volume);
    volumes.render(camera, target);
    sss::MeshScatteringRenderer meshes(
        {.shading = sss::MeshShading::Scattering, .cameras = 2, .samples = 2, .mapResolution = 64, .lightMapResolution = 64});
    meshes.setMesh(mesh);
    meshes.render(camera, target);
    (void)target.readColor();
}

int run(int argc, char** argv) {
    std::string mode = "renderers";
    int cycles = 200;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--mode" && i + 1 < argc) mode = argv[++i];
        else if (arg == "--cycles" && i + 1 < argc) cycles = std::atoi(argv[++i]);
        else {
            std::fprintf(stderr, "usage: sss-context-churn [--mode context|bare-draw|renderers|one-context|"
                                 "bare-one-context] [--cycles N]\n");
            return 2;
        }
    }
    if (cycles < 40 || (mode != "context" && mode != "bare-draw" && mode != "renderers" && mode != "one-context" &&
                        mode != "bare-one-context")) {
        std::fprintf(stderr, "sss-context-churn: unknown --mode \"%s\" or --cycles below 40\n", mode.c_str());
        return 2;
    }
    const sss::Volume volume = sss::makeBlobsVolume(32);
    const sss::Mesh mesh = sss::makeUvSphere(16, 8);
    std::unique_ptr<sss::EglContext> shared;
    if (mode == "one-context" || mode == "bare-one-context") shared = sss::EglContext::create();
    const int warmUp = 20;
    Footprint start;
    std::string renderer;
    for (int i = 0; i < cycles; ++i) {
        std::unique_ptr<sss::EglContext> own;
        if (!shared) own = sss::EglContext::create();
        if (renderer.empty()) renderer = (shared ? shared : own)->info().renderer;
        if (mode == "bare-draw" || mode == "bare-one-context") bareDraw();
        if (mode == "renderers" || mode == "one-context") renderersFrame(volume, mesh);
        own.reset();
        if (i + 1 == warmUp) start = footprint();
    }
    const Footprint end = footprint();
    const double n = cycles - warmUp;
    std::printf("%s on %s, %d cycles: resident %+.1f kB/cycle, anonymous executable mappings %+.1f kB/cycle "
                "(%ld -> %ld kB), libsss GPU memory held after the loop: %llu bytes\n",
                mode.c_str(), renderer.c_str(), cycles, static_cast<double>(end.rssKb - start.rssKb) / n,
                static_cast<double>(end.anonymousExecutableKb - start.anonymousExecutableKb) / n, start.anonymousExecutableKb,
                end.anonymousExecutableKb, static_cast<unsigned long long>(sss::gpuMemoryInUse()));
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const sss::Error& e) {
        std::fprintf(stderr, "sss-context-churn: %s\n", e.what());
        return 1;
    }
}
