// Renders the procedural sphere headless with an installed libsss; exit code 0 on success.
#include <sss/sss.h>

#include <cstdio>

int main() {
    try {
        auto context = sss::EglContext::create();
        sss::RenderTarget target(32, 32);
        target.clear({0, 0, 0, 1});
        sss::MeshScatteringRenderer renderer;
        renderer.setMesh(sss::makeUvSphere());
        renderer.render(sss::Camera{}, target);
        const float centre = target.readColor().at(16, 16).r;
        std::printf("centre pixel red = %.3f\n", centre);
        return centre > 0.1f ? 0 : 1;
    } catch (const sss::Error& e) {
        std::fprintf(stderr, "consumer: %s\n", e.what());
        return 1;
    }
}
