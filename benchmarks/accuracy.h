#pragma once
// sss-bench --accuracy: the renderers measured against physical ground truth (random walks).
#include "plot.h"

#include <sss/sss.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

struct AccuracyOptions {
    bool quick = false;    ///< fewer materials and paths (ctest)
    bool gpu = true;       ///< render the GPU column (needs a current GL context)
    std::string renderer;  ///< GL renderer name, for the report
    int width = 96, height = 72;  ///< mesh images
    int pathsPerPixel = 1024;     ///< mesh random walk, per pixel and channel; volume path tracer: x 4
    std::filesystem::path imageDir;  ///< if set, the mesh images go there (PNG, display-encoded)
};

struct AccuracyReport {
    nlohmann::ordered_json json;  ///< the records
    std::string markdown;
    PlotSpec plot;
};

/// Presets x channels x incidence 0/45/75 degrees: random walk, dipole, calibrated, GPU.
AccuracyReport runSlabAccuracy(const AccuracyOptions& options);

class BenchmarkContext;
/// GPU renders with both profiles against the mesh random walk (renderMeshRandomWalk): the
/// bunny front-lit and back-lit (skin1, 3 cm) and a thin potato slab lit from behind.
AccuracyReport runMeshAccuracy(BenchmarkContext& bench, const AccuracyOptions& options);
/// GPU volume images (the paper's light volume, physical single scattering) against the path
/// tracer's single- and multiple-scattering truths: bucky, bonsai, engine, a high-albedo box.
AccuracyReport runVolumeAccuracy(BenchmarkContext& bench, const AccuracyOptions& options);
/// GPU light-volume images (paper model with ambient 0 and diffuse 1, physical single
/// scattering) against the CPU reference of the same model, whose shadow rays replace the light
/// volume: bucky, bonsai, engine; GPU defaults and an exact ray.
AccuracyReport runLightVolumeAccuracy(BenchmarkContext& bench, const AccuracyOptions& options);
/// Opaque surfaces under a side light (the shell with ct-bone, the bonsai): both volume models
/// against path-traced single scattering, with the rings' contrast beside the truth's.
AccuracyReport runSurfaceAccuracy(BenchmarkContext& bench, const AccuracyOptions& options);
