#pragma once
// sss-bench --accuracy: the renderers measured against physical ground truth (random walks).
#include "plot.h"

#include <sss/sss.h>

#include <nlohmann/json.hpp>

#include <string>

struct AccuracyOptions {
    bool quick = false;    ///< fewer materials and paths (ctest)
    bool gpu = true;       ///< render the GPU column (needs a current GL context)
    std::string renderer;  ///< GL renderer name, for the report
};

struct AccuracyReport {
    nlohmann::ordered_json json;  ///< the records
    std::string markdown;
    PlotSpec plot;
};

/// Presets x channels x incidence 0/45/75 degrees: random walk, dipole, calibrated, GPU.
AccuracyReport runSlabAccuracy(const AccuracyOptions& options);
