// With the optional readers left out, each of their formats fails with ErrorKind::Unsupported,
// naming the format and the build option; OBJ and PNG still work. Exit code 0 when all hold.
#include <sss/error.h>
#include <sss/image.h>
#include <sss/isosurface.h>
#include <sss/mesh.h>
#include <sss/volume.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

namespace {

int failures = 0;

void expectUnsupported(const char* what, const std::string& needle, const std::function<void()>& call) {
    try {
        call();
        std::printf("FAILED: %s: no error\n", what);
        ++failures;
    } catch (const sss::Error& e) {
        const bool ok = e.kind() == sss::ErrorKind::Unsupported && std::string(e.what()).find(needle) != std::string::npos;
        std::printf("%s: %s: %s\n", ok ? "ok" : "FAILED", what, e.what());
        failures += ok ? 0 : 1;
    }
}

}  // namespace

int main() {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "sss_io_without_readers";
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "tri.ply") << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                      "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                                      "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    std::ofstream(dir / "v.nrrd") << "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 1 1 1\nencoding: raw\n\n";
    std::ofstream(dir / "v.vti") << "<VTKFile type=\"ImageData\"></VTKFile>\n";
    std::ofstream(dir / "tri.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    expectUnsupported("PLY", "PLY files need libsss built with SSS_WITH_ASSIMP=ON",
                      [&] { (void)sss::Mesh::load(dir / "tri.ply"); });
    expectUnsupported("NRRD", "NRRD files need libsss built with SSS_WITH_TEEM=ON",
                      [&] { (void)sss::Volume::load(dir / "v.nrrd"); });
    expectUnsupported("VTI", "(.vti) files need libsss built with SSS_WITH_VTK=ON",
                      [&] { (void)sss::Volume::load(dir / "v.vti"); });
    expectUnsupported("isosurface", "extractIsosurface needs libsss built with SSS_WITH_VTK=ON", [&] {
        const sss::Volume volume = sss::Volume::fromData({2, 1, 1}, sss::VoxelType::UInt8, {0, 255});
        sss::IsosurfaceOptions o;
        o.value = 100.0;
        (void)sss::extractIsosurface(volume, o);
    });
    expectUnsupported("EXR", "OpenEXR files need libsss built with SSS_WITH_OPENEXR=ON",
                      [&] { sss::Image(2, 2).saveExr(dir / "x.exr"); });
    try {
        const sss::Mesh mesh = sss::Mesh::load(dir / "tri.obj");
        sss::Image8(2, 2).savePng(dir / "x.png");
        std::printf("ok: OBJ (%zu triangles) and PNG still work\n", mesh.triangleCount());
    } catch (const sss::Error& e) {
        std::printf("FAILED: OBJ or PNG: %s\n", e.what());
        ++failures;
    }
    return failures == 0 ? 0 : 1;
}
