// Textured translucent materials (issue 32): the same mesh with a base-colour texture and in the
// uniform material of the texture's mean colour, side by side in one run: the change frame
// (light buffer, radiosity, combine) and the fixed frame (combine only), per combine. The goal:
// textured fixed frames at most 1.2x untextured.

#include "bench.h"

#include <sss/materials.h>
#include <sss/mesh_scattering_renderer.h>
#include <sss/procedural.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace {

constexpr const char* kTable = "textured";

// Tiles of six colours with thin dark seams, 1024 x 1024: detail at the scale of the texels.
std::shared_ptr<const sss::Image8> tiles() {
    static const glm::u8vec4 colours[6] = {{200, 40, 35, 255}, {240, 200, 40, 255}, {40, 90, 190, 255},
                                           {235, 235, 225, 255}, {50, 150, 70, 255}, {235, 120, 30, 255}};
    auto image = std::make_shared<sss::Image8>(1024, 1024);
    for (int y = 0; y < 1024; ++y)
        for (int x = 0; x < 1024; ++x)
            image->at(x, y) = (x % 128 < 4 || y % 128 < 4) ? glm::u8vec4(40, 30, 30, 255) : colours[(x / 128 + 3 * (y / 128)) % 6];
    return image;
}

// The mesh with planar texture coordinates along z over its bounds and the tiles as base colour.
sss::Mesh textured(const sss::Mesh& mesh) {
    const sss::Bounds b = mesh.bounds();
    std::vector<glm::vec2> texcoords;
    texcoords.reserve(mesh.vertexCount());
    for (const glm::vec3& p : mesh.positions())
        texcoords.push_back(glm::vec2((p.x - b.min.x) / b.size().x, (p.y - b.min.y) / b.size().y));
    return sss::Mesh::fromArrays(mesh.positions(), mesh.indices(), mesh.normals(), mesh.name(), std::move(texcoords))
        .withBaseColour(tiles());
}

}  // namespace

void runTexturedTable(BenchmarkContext& bench) {
    const bool quick = bench.options().quick;
    const std::vector<std::string> models = quick ? std::vector<std::string>{"sphere"} : std::vector<std::string>{"bunny", "buddha"};
    for (const std::string& model : models) {
        if (!bench.wanted(model)) continue;
        const std::optional<sss::Mesh> plain = loadThesisMesh(bench, kTable, model);
        if (!plain) continue;
        const sss::Mesh mesh = textured(*plain);
        const sss::Camera camera = framedCamera(mesh.bounds());
        const sss::DirectionalLight key = keyLight(camera);
        const sss::TexturedScattering material = sss::texturedScattering(sss::materialPreset("skin1"));
        // The defaults per combine, and the vertex estimate without the near field in both: at the
        // defaults the uniform material's shorter diffusion length can switch the near field on
        // where the texture's widest texel leaves it out, so that row compares like with like.
        struct Variant {
            sss::MeshCombine combine;
            bool nearField;
            const char* name;
            const char* slug;
        };
        for (const Variant& variant :
             {Variant{sss::MeshCombine::VertexEstimate, true, "vertex-estimate", "vertex-estimate"},
              Variant{sss::MeshCombine::PerPixel, true, "maps", "maps"},
              Variant{sss::MeshCombine::VertexEstimate, false, "vertex-estimate, no near field", "vertex-estimate-no-near-field"}}) {
            sss::MeshRenderOptions options;
            options.shading = sss::MeshShading::Scattering;
            options.combine = variant.combine;
            if (!variant.nearField) options.nearField = 0.0f;
            options.accumulationFrames = 1;
            options.millimetresPerUnit = 1000.0;
            if (quick) options.mapResolution = options.lightMapResolution = 256;
            const std::string name = variant.name;
            std::pair<Measurement, Measurement> times[2];
            for (int t = 0; t < 2; ++t) {
                sss::MeshScatteringRenderer renderer(options);
                renderer.setMesh(mesh);
                if (t == 0)
                    renderer.setScatteringMaterial(material);
                else
                    renderer.setScatteringMaterial(sss::materialPreset("skin1"));
                const std::string id =
                    std::string(kTable) + "-" + model + "-" + variant.slug + (t == 0 ? "-textured" : "-uniform");
                times[t] = measureChangeAndFixed(bench, renderer, camera, key, id);
            }
            Record r;
            r.table = kTable;
            r.model = model;
            r.mode = "sss";
            r.params = name + ", textured (median = fixed)";
            r.dataSize = std::to_string(mesh.vertexCount()) + " v, 1024^2 texture";
            r.width = bench.options().width;
            r.height = bench.options().height;
            r.measurement = times[0].second;
            r.details = {{"method", name},
                         {"textured_fixed_ms", times[0].second.stats.medianMs},
                         {"uniform_fixed_ms", times[1].second.stats.medianMs},
                         {"fixed_ratio", times[0].second.stats.medianMs / times[1].second.stats.medianMs},
                         {"textured_change_ms", times[0].first.stats.medianMs},
                         {"uniform_change_ms", times[1].first.stats.medianMs},
                         {"change_ratio", times[0].first.stats.medianMs / times[1].first.stats.medianMs},
                         {"material", "skin1 mean free path; uniform: skin1"}};
            bench.addRecord(std::move(r));
        }
    }
}
