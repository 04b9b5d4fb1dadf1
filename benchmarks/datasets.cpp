// The thesis data sets as the tables use them.

#include "bench.h"

#include <glm/gtc/matrix_transform.hpp>

#include <chrono>
#include <cstdio>
#include <functional>
#include <iostream>
#include <map>
#include <string_view>

std::optional<sss::Mesh> loadThesisMesh(BenchmarkContext& bench, const std::string& table, const std::string& model) {
    static const std::map<std::string, std::string> files = {
        {"bunny", "meshes/stanford-bunny.obj"},
        {"dragon", "meshes/dragon_50k.obj"},
        {"buddha", "meshes/happy_buddha_50k.obj"},
        // The largest mesh here (202k triangles); the thesis's Hebe (412k) is not available.
        {"dragon-vrip", "meshes/dragon_vrip_res2.obj"},
    };
    std::optional<sss::Mesh> mesh;
    if (model == "sphere") {
        mesh = sss::makeUvSphere();  // the thesis sphere: 382 vertices, 800 triangles
    } else {
        const auto path = bench.findData(table, model, files.at(model));
        if (!path) return std::nullopt;
        mesh = sss::Mesh::load(*path);
    }
    // Same size for all (the bunny's), centred: one sampling radius then fits every model.
    const sss::Bounds b = mesh->bounds();
    const float scale = 0.1f / std::max(b.radius(), 1e-9f);
    return mesh->transformed(glm::scale(glm::mat4(1.0f), glm::vec3(scale)) * glm::translate(glm::mat4(1.0f), -b.center()));
}

std::optional<std::pair<sss::Volume, std::string>> loadThesisVolume(BenchmarkContext& bench, const std::string& table,
                                                                    const std::string& model) {
    struct Entry {
        std::string file, preset;
        sss::RawLoadOptions options;
    };
    sss::RawLoadOptions ct;
    ct.spacing = glm::vec3(0.957f, 0.957f, 1.5f);  // mm, from the data manifest
    const std::map<std::string, Entry> entries = {
        {"bucky", {"volumes/bucky_32x32x32_uint8.raw", "bucky", {}}},
        {"bonsai", {"volumes/bonsai_256x256x256_uint8.raw", "bonsai", {}}},
        {"engine", {"volumes/engine_256x256x256_uint8.raw", "engine", {}}},
        {"cthead", {"volumes/invesalius_cthead_256x256x108_uint8.raw", "ct-skin", ct}},
    };
    if (model == "blobs") return std::pair{sss::makeBlobsVolume(48), std::string("bucky")};  // quick mode
    const Entry& e = entries.at(model);
    const auto path = bench.findData(table, model, e.file);
    if (!path) return std::nullopt;
    return std::pair{sss::Volume::loadRaw(*path, e.options), e.preset};
}

std::string dimsText(glm::ivec3 dims) {
    return std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" + std::to_string(dims.z);
}

std::optional<FramedVolume> loadFramedVolume(BenchmarkContext& bench, const std::string& table, const std::string& model) {
    auto loaded = loadThesisVolume(bench, table, model);
    if (!loaded) return std::nullopt;
    const sss::Camera camera = framedCamera(loaded->first.worldBounds());
    return FramedVolume{std::move(loaded->first), loaded->second, camera, keyLight(camera)};
}

void showVolume(sss::VolumeScatteringRenderer& renderer, const FramedVolume& scene) {
    renderer.setVolume(scene.volume);
    renderer.setTransferFunction(sss::TransferFunction::preset(scene.preset));
    renderer.setLights({scene.key});
}

void forEachShownVolume(BenchmarkContext& bench, const std::string& table, const std::vector<std::string>& models,
                        const ShownVolumeMeasure& measure) {
    const std::vector<std::string> quickModels{"blobs"};
    for (const std::string& model : bench.options().quick ? quickModels : models) {
        if (!bench.wanted(model)) continue;
        const std::optional<FramedVolume> scene = loadFramedVolume(bench, table, model);
        if (!scene) continue;
        sss::VolumeScatteringRenderer renderer;
        showVolume(renderer, *scene);
        measure(model, *scene, renderer);
    }
}

std::string viewAndLightTag(const sss::Camera& camera, const sss::DirectionalLight& light) {
    std::string bytes;
    auto add = [&](const auto& value) { bytes.append(reinterpret_cast<const char*>(&value), sizeof(value)); };
    add(camera.view());
    add(camera.projection(1.0f));
    add(light.direction);
    add(light.color);
    add(light.intensity);
    char text[17];
    std::snprintf(text, sizeof(text), "%016zx", std::hash<std::string_view>{}(bytes));
    return std::string(text, 8);
}

sss::Image cachedReference(const Options& o, const std::string& name, const std::function<sss::Image()>& render) {
    const std::filesystem::path cached = o.referenceCache / name;
    std::error_code ec;
    if (!o.referenceCache.empty() && std::filesystem::is_regular_file(cached, ec)) return sss::Image::loadExr(cached);
    const auto start = std::chrono::steady_clock::now();
    sss::Image reference = render();
    std::cerr << "sss-bench: " << name << " rendered in "
              << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s\n";
    if (!o.referenceCache.empty()) {
        std::filesystem::create_directories(o.referenceCache);
        reference.saveExr(cached);
    }
    return reference;
}
