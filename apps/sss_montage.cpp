// sss-montage: puts PNG images side by side in a grid (a row of materials, a contact sheet).
// Run `sss-montage --help` for the options. Exit codes: 0 ok, 1 a file failure, 2 bad usage.
// No GL: it reads and writes PNGs with the library's Image8.
#include "common/scene_inputs.h"

#include <sss/image.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

namespace {

using namespace examples;

constexpr const char* kUsage = R"(usage: sss-montage [options] --out FILE.png IMAGE.png...

Puts the images into a grid, left to right and top to bottom, each scaled to fit its tile
(aspect kept, area-averaged when shrunk, centred) with a gap between tiles.

  --out FILE.png            output image (required)
  --columns N               tiles per row (default: all images in one row)
  --tile WxH                tile size in pixels (default: the first image's size)
  --gap PX                  space between tiles and around the grid (default: 4)
  --background R,G,B        colour of the gaps, sRGB 0..1 (default: 0.1,0.1,0.12, the
                            sss-render background)
  --label TEXT              a caption drawn into the bottom-left corner of the next image's
                            tile (give it once per image, in order; "" for none). A built-in
                            5x7 pixel font: letters (shown in capitals), digits and - . , ( )
                            / : + % _ = '; other characters show as a blank
  --help                    this text
)";

struct Args {
    std::string out;
    std::vector<std::string> inputs, labels;
    int columns = 0, tileWidth = 0, tileHeight = 0, gap = 4;
    glm::vec3 background{0.1f, 0.1f, 0.12f};
};

Args parseArgs(int argc, char** argv) {
    Args a;
    for (OptionCursor args(argc, argv); args.next();) {
        const std::string& opt = args.option();
        auto value = [&args] { return args.value(); };
        if (args.isHelp()) {
            std::cout << kUsage;
            std::exit(0);
        } else if (opt == "--out") a.out = value();
        else if (opt == "--columns") {
            a.columns = parseInt(opt, value());
            if (a.columns < 1) throw UsageError("--columns: must be >= 1");
        } else if (opt == "--tile") {
            const std::string v = value();
            const auto parts = split(v, 'x');
            if (parts.size() != 2) throw UsageError("--tile: expected WxH, got \"" + v + "\"");
            a.tileWidth = parseInt(opt, parts[0]);
            a.tileHeight = parseInt(opt, parts[1]);
            if (a.tileWidth < 1 || a.tileHeight < 1 || a.tileWidth > 4096 || a.tileHeight > 4096)
                throw UsageError("--tile: width and height must be in 1..4096, got \"" + v + "\"");
        } else if (opt == "--gap") {
            a.gap = parseInt(opt, value());
            if (a.gap < 0 || a.gap > 1024) throw UsageError("--gap: must be in 0..1024");
        } else if (opt == "--background") a.background = parseVec3(opt, value());
        else if (opt == "--label") a.labels.push_back(value());
        else if (opt.size() > 1 && opt[0] == '-') throw UsageError("unknown option \"" + opt + "\" (see --help)");
        else a.inputs.push_back(opt);
    }
    if (a.out.empty()) throw UsageError("--out FILE.png is required");
    if (a.inputs.empty()) throw UsageError("no input images");
    if (a.labels.size() > a.inputs.size())
        throw UsageError("--label: " + std::to_string(a.labels.size()) + " labels for " +
                         std::to_string(a.inputs.size()) + " images");
    return a;
}

// A 5x7 pixel font: each glyph is 7 rows of 5 columns, '#' set.
struct Glyph {
    char c;
    const char* rows;
};
constexpr Glyph kFont[] = {
    {'A', ".###." "#...#" "#...#" "#####" "#...#" "#...#" "#...#"},
    {'B', "####." "#...#" "#...#" "####." "#...#" "#...#" "####."},
    {'C', ".###." "#...#" "#...." "#...." "#...." "#...#" ".###."},
    {'D', "####." "#...#" "#...#" "#...#" "#...#" "#...#" "####."},
    {'E', "#####" "#...." "#...." "####." "#...." "#...." "#####"},
    {'F', "#####" "#...." "#...." "####." "#...." "#...." "#...."},
    {'G', ".###." "#...#" "#...." "#.###" "#...#" "#...#" ".####"},
    {'H', "#...#" "#...#" "#...#" "#####" "#...#" "#...#" "#...#"},
    {'I', ".###." "..#.." "..#.." "..#.." "..#.." "..#.." ".###."},
    {'J', "..###" "...#." "...#." "...#." "...#." "#..#." ".##.."},
    {'K', "#...#" "#..#." "#.#.." "##..." "#.#.." "#..#." "#...#"},
    {'L', "#...." "#...." "#...." "#...." "#...." "#...." "#####"},
    {'M', "#...#" "##.##" "#.#.#" "#.#.#" "#...#" "#...#" "#...#"},
    {'N', "#...#" "#...#" "##..#" "#.#.#" "#..##" "#...#" "#...#"},
    {'O', ".###." "#...#" "#...#" "#...#" "#...#" "#...#" ".###."},
    {'P', "####." "#...#" "#...#" "####." "#...." "#...." "#...."},
    {'Q', ".###." "#...#" "#...#" "#...#" "#.#.#" "#..#." ".##.#"},
    {'R', "####." "#...#" "#...#" "####." "#.#.." "#..#." "#...#"},
    {'S', ".####" "#...." "#...." ".###." "....#" "....#" "####."},
    {'T', "#####" "..#.." "..#.." "..#.." "..#.." "..#.." "..#.."},
    {'U', "#...#" "#...#" "#...#" "#...#" "#...#" "#...#" ".###."},
    {'V', "#...#" "#...#" "#...#" "#...#" "#...#" ".#.#." "..#.."},
    {'W', "#...#" "#...#" "#...#" "#.#.#" "#.#.#" "#.#.#" ".#.#."},
    {'X', "#...#" "#...#" ".#.#." "..#.." ".#.#." "#...#" "#...#"},
    {'Y', "#...#" "#...#" ".#.#." "..#.." "..#.." "..#.." "..#.."},
    {'Z', "#####" "....#" "...#." "..#.." ".#..." "#...." "#####"},
    {'0', ".###." "#...#" "#..##" "#.#.#" "##..#" "#...#" ".###."},
    {'1', "..#.." ".##.." "..#.." "..#.." "..#.." "..#.." ".###."},
    {'2', ".###." "#...#" "....#" "...#." "..#.." ".#..." "#####"},
    {'3', "#####" "...#." "..#.." "...#." "....#" "#...#" ".###."},
    {'4', "...#." "..##." ".#.#." "#..#." "#####" "...#." "...#."},
    {'5', "#####" "#...." "####." "....#" "....#" "#...#" ".###."},
    {'6', "..##." ".#..." "#...." "####." "#...#" "#...#" ".###."},
    {'7', "#####" "....#" "...#." "..#.." ".#..." ".#..." ".#..."},
    {'8', ".###." "#...#" "#...#" ".###." "#...#" "#...#" ".###."},
    {'9', ".###." "#...#" "#...#" ".####" "....#" "...#." ".##.."},
    {'-', "....." "....." "....." "#####" "....." "....." "....."},
    {'.', "....." "....." "....." "....." "....." ".##.." ".##.."},
    {',', "....." "....." "....." "....." ".##.." "..#.." ".#..."},
    {'(', "...#." "..#.." ".#..." ".#..." ".#..." "..#.." "...#."},
    {')', ".#..." "..#.." "...#." "...#." "...#." "..#.." ".#..."},
    {'/', "....." "....#" "...#." "..#.." ".#..." "#...." "....."},
    {':', "....." ".##.." ".##.." "....." ".##.." ".##.." "....."},
    {'+', "....." "..#.." "..#.." "#####" "..#.." "..#.." "....."},
    {'%', "##..." "##..#" "...#." "..#.." ".#..." "#..##" "...##"},
    {'_', "....." "....." "....." "....." "....." "....." "#####"},
    {'=', "....." "....." "#####" "....." "#####" "....." "....."},
    {'\'', "..#.." "..#.." ".#..." "....." "....." "....." "....."},
};

const char* glyphRows(char c) {
    if (c >= 'a' && c <= 'z') c = char(c - 'a' + 'A');
    for (const Glyph& g : kFont)
        if (g.c == c) return g.rows;
    return nullptr;  // a space, or a character the font lacks
}

// Draws text with its bottom-left corner at (x, bottom), each font pixel as scale x scale
// pixels, light on a dark outline so it reads on any picture; clipped to the image.
void drawText(sss::Image8& image, const std::string& text, int x, int bottom, int scale) {
    const int top = bottom - 7 * scale;
    auto plot = [&](int px, int py, glm::u8vec4 colour) {
        if (px >= 0 && py >= 0 && px < image.width() && py < image.height()) image.at(px, py) = colour;
    };
    for (int pass = 0; pass < 2; ++pass) {  // outline first, then the glyphs over it
        for (std::size_t k = 0; k < text.size(); ++k) {
            const char* rows = glyphRows(text[k]);
            if (!rows) continue;
            const int left = x + int(k) * 6 * scale;
            for (int r = 0; r < 7; ++r)
                for (int c = 0; c < 5; ++c) {
                    if (rows[r * 5 + c] != '#') continue;
                    for (int dy = 0; dy < scale; ++dy)
                        for (int dx = 0; dx < scale; ++dx) {
                            const int px = left + c * scale + dx, py = top + r * scale + dy;
                            if (pass == 1) plot(px, py, glm::u8vec4(235, 235, 235, 255));
                            else
                                for (int oy = -1; oy <= 1; ++oy)
                                    for (int ox = -1; ox <= 1; ++ox) plot(px + ox, py + oy, glm::u8vec4(0, 0, 0, 255));
                        }
                }
        }
    }
}

// Scales src to w x h: each output pixel averages the source area it covers (a box filter,
// exact for shrinking; enlarging repeats pixels).
sss::Image8 resized(const sss::Image8& src, int w, int h) {
    sss::Image8 dst(w, h);
    const double sx = double(src.width()) / w, sy = double(src.height()) / h;
    for (int y = 0; y < h; ++y) {
        const double y0 = y * sy, y1 = (y + 1) * sy;
        for (int x = 0; x < w; ++x) {
            const double x0 = x * sx, x1 = (x + 1) * sx;
            glm::dvec4 sum(0.0);
            double weight = 0.0;
            for (int j = int(y0); j < std::min(int(std::ceil(y1)), src.height()); ++j) {
                const double wy = std::min(y1, j + 1.0) - std::max(y0, double(j));
                for (int i = int(x0); i < std::min(int(std::ceil(x1)), src.width()); ++i) {
                    const double wx = std::min(x1, i + 1.0) - std::max(x0, double(i));
                    sum += glm::dvec4(src.at(i, j)) * (wx * wy);
                    weight += wx * wy;
                }
            }
            dst.at(x, y) = glm::u8vec4(glm::round(sum / std::max(weight, 1e-12)));
        }
    }
    return dst;
}

int run(const Args& a) {
    std::vector<sss::Image8> images;
    for (const std::string& path : a.inputs) images.push_back(sss::Image8::loadPng(path));
    const int n = int(images.size());
    const int columns = a.columns > 0 ? std::min(a.columns, n) : n;
    const int rows = (n + columns - 1) / columns;
    const int tw = a.tileWidth > 0 ? a.tileWidth : images.front().width();
    const int th = a.tileHeight > 0 ? a.tileHeight : images.front().height();
    const long width = long(columns) * tw + long(columns + 1) * a.gap, height = long(rows) * th + long(rows + 1) * a.gap;
    if (width > sss::kMaxImageSide || height > sss::kMaxImageSide)
        throw UsageError("the montage would be " + std::to_string(width) + "x" + std::to_string(height) +
                         " pixels, over 16384 on a side: use --tile or --columns");
    const glm::u8vec4 fill(glm::round(glm::clamp(a.background, 0.0f, 1.0f) * 255.0f), 255);
    sss::Image8 sheet(int(width), int(height), fill);
    for (int k = 0; k < n; ++k) {
        const sss::Image8& image = images[std::size_t(k)];
        const double scale = std::min(double(tw) / image.width(), double(th) / image.height());
        const int w = std::max(1, int(std::lround(image.width() * scale)));
        const int h = std::max(1, int(std::lround(image.height() * scale)));
        const sss::Image8 tile = (w == image.width() && h == image.height()) ? image : resized(image, w, h);
        const int left = a.gap + (k % columns) * (tw + a.gap) + (tw - w) / 2;
        const int top = a.gap + (k / columns) * (th + a.gap) + (th - h) / 2;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                // Transparent pixels show the background.
                const glm::u8vec4 p = tile.at(x, y);
                const float alpha = p.a / 255.0f;
                sheet.at(left + x, top + y) = glm::u8vec4(
                    glm::round(glm::vec3(p) * alpha + glm::vec3(fill) * (1.0f - alpha)), 255);
            }
        if (std::size_t(k) < a.labels.size()) {
            const int fontScale = th >= 160 ? 2 : 1, inset = 3 * fontScale;
            // Cut to the image's width so it never runs into the next tile.
            const std::size_t fits = std::size_t(std::max(0, (w - 2 * inset + fontScale) / (6 * fontScale)));
            drawText(sheet, a.labels[std::size_t(k)].substr(0, fits), left + inset, top + h - inset, fontScale);
        }
    }
    sheet.savePng(a.out);
    std::printf("wrote %s (%dx%d, %d image(s) in %d column(s))\n", a.out.c_str(), sheet.width(), sheet.height(), n,
                columns);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return runReportingErrors("sss-montage", [&] { return run(parseArgs(argc, argv)); });
}
