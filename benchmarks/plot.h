#pragma once
// A small log-log scatter plot written to PNG, for the time-against-error sweeps: no plotting
// library is packaged for this project, and the plots only need points, lines, axes and numbers.
#include <sss/image.h>

#include <filesystem>
#include <string>
#include <vector>

struct PlotSeries {
    std::string label;
    std::vector<std::pair<double, double>> points;  ///< (x, y), both > 0
    unsigned color = 0x1f77b4;                       ///< 0xRRGGBB
    bool connect = true;                             ///< draw lines between consecutive points
};

struct PlotSpec {
    std::string title, xLabel, yLabel;
    std::vector<PlotSeries> series;
    int width = 720, height = 480;
};

/// Renders the plot (log10 axes with decade ticks and labels, legend) and saves it as PNG.
void savePlot(const PlotSpec& spec, const std::filesystem::path& path);
