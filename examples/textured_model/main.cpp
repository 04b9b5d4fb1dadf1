// Writes the project's textured translucent test model: a UV sphere with a painted base-colour
// texture (six coloured gores and white caps, like a beach ball, with thin dark seams and a row
// of dots a few millimetres wide), as OBJ + MTL (map_Kd) + PNG.
// sss-render then renders it as a textured translucent material:
//   textured-model out/  &&  sss-render --mesh out/painted_ball.obj --mode sss --material skin1
// The gores' boundaries are where the rule for points of different texels shows
// (docs/textured-materials.md): light crosses them under the surface.
#include <sss/image.h>

#include <glm/vec3.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <stdexcept>
#include <string>

namespace {

constexpr int kSegments = 96, kRings = 48;  // the sphere's longitude and latitude steps
constexpr double kRadius = 0.1;              // metres (sss-render's default scale): a 20 cm ball

// u around the ball (0..1), v from the south pole (0) to the north pole (1).
glm::u8vec4 paint(double u, double v) {
    static const glm::u8vec4 gores[6] = {{200, 40, 35, 255}, {240, 200, 40, 255}, {40, 90, 190, 255},
                                         {235, 235, 225, 255}, {50, 150, 70, 255}, {235, 120, 30, 255}};
    const glm::u8vec4 seam{40, 30, 30, 255};
    const double circumference = 2.0 * std::numbers::pi * kRadius * 1000.0;  // mm
    const double equator = circumference * std::sin(std::numbers::pi * v);    // this latitude's, mm
    const double gore = u * 6.0;
    // Seams 2 mm wide along the gores' edges and round the caps.
    if (std::abs(gore - std::round(gore)) * equator / 6.0 < 1.0) return seam;
    if (std::abs(v - 0.1) * circumference / 2.0 < 1.0 || std::abs(v - 0.9) * circumference / 2.0 < 1.0) return seam;
    if (v < 0.1 || v > 0.9) return {240, 240, 232, 255};  // the caps
    // A row of dots 1.5 to 6 mm across along the equator of each gore.
    const double along = (gore - std::floor(gore) - 0.5) * equator / 6.0, across = (v - 0.5) * circumference / 2.0;
    const double dot = 0.75 + 0.75 * std::floor(gore);
    if (along * along + across * across < dot * dot) return seam;
    return gores[static_cast<int>(gore) % 6];
}

sss::Image8 texture(int width, int height) {
    sss::Image8 image(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            image.at(x, y) = paint((x + 0.5) / width, 1.0 - (y + 0.5) / height);  // row 0 is v = 1
    return image;
}

void writeObj(const std::filesystem::path& path, const std::string& mtl) {
    std::ofstream obj(path);
    obj << "# libsss textured translucent test model (examples/textured_model)\nmtllib " << mtl << "\nusemtl painted\n";
    for (int j = 0; j <= kRings; ++j) {
        const double theta = std::numbers::pi * j / kRings;  // from the south pole
        for (int i = 0; i <= kSegments; ++i) {
            const double phi = 2.0 * std::numbers::pi * i / kSegments;
            const glm::dvec3 n(std::sin(theta) * std::cos(phi), -std::cos(theta), -std::sin(theta) * std::sin(phi));
            obj << "v " << kRadius * n.x << ' ' << kRadius * n.y << ' ' << kRadius * n.z << '\n'
                << "vn " << n.x << ' ' << n.y << ' ' << n.z << '\n'
                << "vt " << double(i) / kSegments << ' ' << double(j) / kRings << '\n';
        }
    }
    // One vertex per (v, vt, vn) triple: the seam at u = 0 / 1 keeps both texture coordinates.
    for (int j = 0; j < kRings; ++j)
        for (int i = 0; i < kSegments; ++i) {
            const int a = j * (kSegments + 1) + i + 1, b = a + 1, c = a + kSegments + 1, d = c + 1;
            obj << "f " << a << '/' << a << '/' << a << ' ' << b << '/' << b << '/' << b << ' ' << d << '/' << d << '/'
                << d << '\n'
                << "f " << a << '/' << a << '/' << a << ' ' << d << '/' << d << '/' << d << ' ' << c << '/' << c << '/'
                << c << '\n';
        }
    if (!obj) throw std::runtime_error(path.string() + ": cannot write");
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: textured-model OUT_DIR\n");
        return 2;
    }
    try {
        const std::filesystem::path dir = argv[1];
        std::filesystem::create_directories(dir);
        texture(2048, 1024).savePng(dir / "painted_ball.png");
        std::ofstream(dir / "painted_ball.mtl") << "newmtl painted\nKd 1 1 1\nmap_Kd painted_ball.png\n";
        writeObj(dir / "painted_ball.obj", "painted_ball.mtl");
        std::printf("wrote %s\n", (dir / "painted_ball.obj").string().c_str());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "textured-model: %s\n", e.what());
        return 1;
    }
    return 0;
}
