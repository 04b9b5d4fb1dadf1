#include "plot.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>

namespace {

// 5x7 bitmap glyphs (one byte per row, low 5 bits, MSB on the left) for the characters plots use.
const std::map<char, std::array<unsigned char, 7>>& font() {
    static const std::map<char, std::array<unsigned char, 7>> glyphs = {
        {'0', {14, 17, 19, 21, 25, 17, 14}}, {'1', {4, 12, 4, 4, 4, 4, 14}},   {'2', {14, 17, 1, 2, 4, 8, 31}},
        {'3', {31, 2, 4, 2, 1, 17, 14}},     {'4', {2, 6, 10, 18, 31, 2, 2}},  {'5', {31, 16, 30, 1, 1, 17, 14}},
        {'6', {6, 8, 16, 30, 17, 17, 14}},   {'7', {31, 1, 2, 4, 8, 8, 8}},    {'8', {14, 17, 17, 14, 17, 17, 14}},
        {'9', {14, 17, 17, 15, 1, 2, 12}},   {'.', {0, 0, 0, 0, 0, 12, 12}},   {'-', {0, 0, 0, 31, 0, 0, 0}},
        {'+', {0, 4, 4, 31, 4, 4, 0}},       {'(', {2, 4, 8, 8, 8, 4, 2}},     {')', {8, 4, 2, 2, 2, 4, 8}},
        {'=', {0, 0, 31, 0, 31, 0, 0}},      {',', {0, 0, 0, 0, 12, 4, 8}},    {':', {0, 12, 12, 0, 12, 12, 0}},
        {'/', {1, 1, 2, 4, 8, 16, 16}},      {'%', {24, 25, 2, 4, 8, 19, 3}},  {'|', {4, 4, 4, 4, 4, 4, 4}},      {'^', {4, 10, 17, 0, 0, 0, 0}},   {' ', {0, 0, 0, 0, 0, 0, 0}},
        {'a', {0, 0, 14, 1, 15, 17, 15}},    {'b', {16, 16, 22, 25, 17, 17, 30}}, {'c', {0, 0, 14, 16, 16, 17, 14}},
        {'d', {1, 1, 13, 19, 17, 17, 15}},   {'e', {0, 0, 14, 17, 31, 16, 14}}, {'f', {6, 9, 8, 28, 8, 8, 8}},
        {'g', {0, 15, 17, 17, 15, 1, 14}},   {'h', {16, 16, 22, 25, 17, 17, 17}}, {'i', {4, 0, 12, 4, 4, 4, 14}},
        {'k', {16, 16, 18, 20, 24, 20, 18}}, {'l', {12, 4, 4, 4, 4, 4, 14}},   {'m', {0, 0, 26, 21, 21, 17, 17}},
        {'n', {0, 0, 22, 25, 17, 17, 17}},   {'o', {0, 0, 14, 17, 17, 17, 14}}, {'p', {0, 0, 30, 17, 30, 16, 16}},
        {'r', {0, 0, 22, 25, 16, 16, 16}},   {'s', {0, 0, 14, 16, 14, 1, 30}}, {'t', {8, 8, 28, 8, 8, 9, 6}},
        {'u', {0, 0, 17, 17, 17, 19, 13}},   {'v', {0, 0, 17, 17, 17, 10, 4}}, {'w', {0, 0, 17, 17, 21, 21, 10}},
        {'x', {0, 0, 17, 10, 4, 10, 17}},    {'y', {0, 0, 17, 17, 15, 1, 14}}, {'z', {0, 0, 31, 2, 4, 8, 31}},
        {'E', {31, 16, 16, 30, 16, 16, 31}}, {'K', {17, 18, 20, 24, 20, 18, 17}}, {'M', {17, 27, 21, 21, 17, 17, 17}},
        {'N', {17, 17, 25, 21, 19, 17, 17}}, {'R', {30, 17, 17, 30, 20, 18, 17}}, {'S', {15, 16, 16, 14, 1, 1, 30}},
        {'T', {31, 4, 4, 4, 4, 4, 4}},       {'L', {16, 16, 16, 16, 16, 16, 31}}, {'V', {17, 17, 17, 17, 17, 10, 4}},
        {'G', {14, 17, 16, 23, 17, 17, 15}}, {'C', {14, 17, 16, 16, 16, 17, 14}}, {'A', {14, 17, 17, 31, 17, 17, 17}},
        {'B', {30, 17, 17, 30, 17, 17, 30}}, {'D', {30, 17, 17, 17, 17, 17, 30}}, {'F', {31, 16, 16, 30, 16, 16, 16}},
        {'H', {17, 17, 17, 31, 17, 17, 17}}, {'I', {14, 4, 4, 4, 4, 4, 14}},   {'O', {14, 17, 17, 17, 17, 17, 14}},
        {'W', {17, 17, 17, 21, 21, 21, 10}}, {'j', {2, 0, 6, 2, 2, 18, 12}},   {'q', {0, 0, 13, 19, 15, 1, 1}}, {'P', {30, 17, 17, 30, 16, 16, 16}}, {'U', {17, 17, 17, 17, 17, 17, 14}},
    };
    return glyphs;
}

struct Canvas {
    sss::Image8 image;
    void pixel(int x, int y, unsigned rgb) {
        if (x < 0 || y < 0 || x >= image.width() || y >= image.height()) return;
        image.at(x, y) = {static_cast<unsigned char>(rgb >> 16), static_cast<unsigned char>(rgb >> 8),
                          static_cast<unsigned char>(rgb), 255};
    }
    void line(int x0, int y0, int x1, int y1, unsigned rgb) {
        const int steps = std::max(std::abs(x1 - x0), std::abs(y1 - y0));
        for (int i = 0; i <= steps; ++i) {
            const double t = steps ? static_cast<double>(i) / steps : 0.0;
            pixel(static_cast<int>(std::lround(x0 + t * (x1 - x0))), static_cast<int>(std::lround(y0 + t * (y1 - y0))), rgb);
        }
    }
    void disc(int cx, int cy, int r, unsigned rgb) {
        for (int y = -r; y <= r; ++y)
            for (int x = -r; x <= r; ++x)
                if (x * x + y * y <= r * r) pixel(cx + x, cy + y, rgb);
    }
    // Text with its top-left corner at (x, y); unknown characters draw as blanks.
    void text(int x, int y, const std::string& s, unsigned rgb) {
        for (char ch : s) {
            const auto it = font().find(ch);
            if (it != font().end())
                for (int row = 0; row < 7; ++row)
                    for (int col = 0; col < 5; ++col)
                        if (it->second[static_cast<size_t>(row)] & (16 >> col)) pixel(x + col, y + row, rgb);
            x += 6;
        }
    }
    void textVertical(int x, int y, const std::string& s, unsigned rgb) {  // bottom to top
        for (char ch : s) {
            const auto it = font().find(ch);
            if (it != font().end())
                for (int row = 0; row < 7; ++row)
                    for (int col = 0; col < 5; ++col)
                        if (it->second[static_cast<size_t>(row)] & (16 >> col)) pixel(x + row, y - col, rgb);
            y -= 6;
        }
    }
};

std::string decadeLabel(int exponent) {
    if (exponent >= -2 && exponent <= 3) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%g", std::pow(10.0, exponent));
        return buf;
    }
    return "1e" + std::to_string(exponent);
}

}  // namespace

void savePlot(const PlotSpec& spec, const std::filesystem::path& path) {
    Canvas c{sss::Image8(spec.width, spec.height, {255, 255, 255, 255})};
    const bool bars = !spec.categories.empty();
    double xMin = 1e300, xMax = -1e300, yMin = 1e300, yMax = -1e300;
    for (const PlotSeries& s : spec.series)
        for (auto [x, y] : s.points)
            if ((bars || x > 0) && y > 0) {
                xMin = std::min(xMin, x), xMax = std::max(xMax, x);
                yMin = std::min(yMin, y), yMax = std::max(yMax, y);
            }
    if (xMin > xMax) xMin = 1, xMax = 10, yMin = 1, yMax = 10;
    // Whole decades around the data.
    const int x0 = static_cast<int>(std::floor(std::log10(xMin))), x1 = std::max(x0 + 1, static_cast<int>(std::ceil(std::log10(xMax))));
    const int y0 = static_cast<int>(std::floor(std::log10(yMin))), y1 = std::max(y0 + 1, static_cast<int>(std::ceil(std::log10(yMax))));
    const int left = 70, right = spec.width - 190, top = 40, bottom = spec.height - 50;
    auto px = [&](double x) { return left + static_cast<int>((std::log10(x) - x0) / (x1 - x0) * (right - left)); };
    auto py = [&](double y) { return bottom - static_cast<int>((std::log10(y) - y0) / (y1 - y0) * (bottom - top)); };

    const unsigned grid = 0xdddddd, ink = 0x222222;
    const int groups = static_cast<int>(spec.categories.size());
    const double groupWidth = bars ? double(right - left) / groups : 0.0;
    if (bars) {
        for (int k = 0; k < groups; ++k) {
            const std::string& label = spec.categories[static_cast<size_t>(k)];
            const int centre = left + static_cast<int>((k + 0.5) * groupWidth);
            c.text(centre - static_cast<int>(label.size()) * 3, bottom + 6, label, ink);
        }
    } else {
        for (int e = x0; e <= x1; ++e) {
            const int x = px(std::pow(10.0, e));
            c.line(x, top, x, bottom, grid);
            const std::string label = decadeLabel(e);
            c.text(x - static_cast<int>(label.size()) * 3, bottom + 6, label, ink);
        }
    }
    for (int e = y0; e <= y1; ++e) {
        const int y = py(std::pow(10.0, e));
        c.line(left, y, right, y, grid);
        const std::string label = decadeLabel(e);
        c.text(left - 6 - static_cast<int>(label.size()) * 6, y - 3, label, ink);
    }
    c.line(left, bottom, right, bottom, ink);
    c.line(left, top, left, bottom, ink);
    c.text(left, 14, spec.title, ink);
    c.text((left + right) / 2 - static_cast<int>(spec.xLabel.size()) * 3, bottom + 24, spec.xLabel, ink);
    c.textVertical(14, (top + bottom) / 2 + static_cast<int>(spec.yLabel.size()) * 3, spec.yLabel, ink);

    int legendY = top;
    const int nSeries = static_cast<int>(spec.series.size());
    for (int si = 0; si < nSeries; ++si) {
        const PlotSeries& s = spec.series[static_cast<size_t>(si)];
        if (bars) {
            // Bars share 80 % of the group's width; each rises from the axis to its value.
            const double barWidth = 0.8 * groupWidth / std::max(nSeries, 1);
            for (size_t k = 0; k < s.points.size() && static_cast<int>(k) < groups; ++k) {
                const double y = s.points[k].second;
                if (!(y > 0)) continue;
                const int xa = left + static_cast<int>((static_cast<double>(k) + 0.1) * groupWidth + si * barWidth);
                const int xb = std::max(xa, static_cast<int>(xa + barWidth) - 1);
                const int yTop = std::max(top, py(y));
                for (int x = xa; x <= xb; ++x) c.line(x, bottom - 1, x, yTop, s.color);
            }
            for (int y = -3; y <= 3; ++y) c.line(right + 13, legendY + 3 + y, right + 19, legendY + 3 + y, s.color);
        } else {
            std::pair<int, int> previous{-1, -1};
            for (auto [x, y] : s.points) {
                if (!(x > 0 && y > 0)) continue;
                const std::pair<int, int> p{px(x), py(y)};
                if (s.connect && previous.first >= 0) c.line(previous.first, previous.second, p.first, p.second, s.color);
                c.disc(p.first, p.second, 3, s.color);
                previous = p;
            }
            c.disc(right + 16, legendY + 3, 3, s.color);
        }
        c.text(right + 26, legendY, s.label, ink);
        legendY += 14;
    }
    c.image.savePng(path);
}
