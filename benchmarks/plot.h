#pragma once
// A small log-log scatter plot (the time-against-error sweeps) or a grouped bar chart on a log
// axis (errors per material or scene), written to PNG: no plotting library is packaged for this
// project, and the plots only need points, bars, lines, axes and numbers.
#include <sss/image.h>

#include <filesystem>
#include <string>
#include <vector>

/// Colours for series that have no meaning of their own, in order.
inline constexpr unsigned kPlotPalette[] = {0x1f77b4, 0xff7f0e, 0x2ca02c, 0xd62728, 0x9467bd, 0x8c564b, 0xe377c2, 0x7f7f7f};

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
    /// Non-empty: a bar chart instead, one group per category (named under the x axis), one bar
    /// per series in each group; series[s].points[k].second is category k's value (x unused,
    /// values <= 0 draw no bar). The y axis is log10, as in the scatter plot.
    std::vector<std::string> categories{};
};

/// Renders the plot (log10 axes with decade ticks and labels, legend) and saves it as PNG.
void savePlot(const PlotSpec& spec, const std::filesystem::path& path);
