#include "mesh/reflectance_table.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <mutex>
#include <utility>

namespace sss::detail {
namespace {

// Nodes in s = sqrt(1 - alpha'), geometric: the reflectance changes fastest near alpha' = 1.
constexpr int kNodes = 96;

ReflectanceTable buildTable(double eta, ScatteringProfile profile) {
    const double sMin = std::sqrt(1.0 - kMaxReducedAlbedo), sMax = std::sqrt(1.0 - kMinReducedAlbedo);
    ReflectanceTable table;
    for (int k = 0; k < kNodes; ++k) table.s.push_back(sMin * std::pow(sMax / sMin, k / double(kNodes - 1)));
    table.reflectance.resize(kNodes);
    table.gathered.resize(kNodes);
    // Three albedos per derivation: the channels are independent, so one call serves three nodes.
    for (int k = 0; k < kNodes; k += 3) {
        ScatteringMaterial m;
        m.eta = eta;
        m.g = 0.0;
        for (int c = 0; c < 3; ++c) {
            const double s = table.s[static_cast<size_t>(std::min(k + c, kNodes - 1))];
            const double albedo = 1.0 - s * s;
            m.sigmaS[c] = albedo;
            m.sigmaA[c] = 1.0 - albedo;
        }
        const DipoleConstants constants = deriveDipoleConstants(m, 1.0, profile);
        const glm::dvec3 total = profileDiffuseReflectance(constants, 1.0);
        const glm::dvec3 gathered = fresnelTransmittance(eta, 1.0) * dipolePlaneIntegral(constants, 1.0);
        for (int c = 0; c < 3 && k + c < kNodes; ++c) {
            table.reflectance[static_cast<size_t>(k + c)] = total[c];
            table.gathered[static_cast<size_t>(k + c)] = gathered[c];
        }
    }
    // The paper's dipole turns back up at low albedo (its extrapolation distance diverges), so
    // its reflectance is monotone only down to its minimum: darker texels are clamped there.
    const auto darkest = std::min_element(table.reflectance.begin(), table.reflectance.end());
    const auto keep = static_cast<std::size_t>(darkest - table.reflectance.begin()) + 1;
    table.s.resize(keep);
    table.reflectance.resize(keep);
    table.gathered.resize(keep);
    return table;
}

}  // namespace

const ReflectanceTable& reflectanceTable(double eta, ScatteringProfile profile) {
    static std::mutex mutex;
    static std::map<std::pair<double, int>, ReflectanceTable> tables;
    const std::lock_guard lock(mutex);
    const auto key = std::make_pair(eta, static_cast<int>(profile));
    auto it = tables.find(key);
    if (it == tables.end()) it = tables.emplace(key, buildTable(eta, profile)).first;
    return it->second;
}

double srgbToLinear(std::uint8_t value) {
    const double c = value / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

TextureSampler::TextureSampler(const Image8& image, bool srgb) : m_width(image.width()), m_height(image.height()) {
    m_texels.reserve(static_cast<std::size_t>(m_width) * static_cast<std::size_t>(m_height));
    for (int y = m_height - 1; y >= 0; --y)
        for (int x = 0; x < m_width; ++x) {
            const glm::u8vec4 t = image.at(x, y);
            m_texels.push_back(srgb ? glm::dvec3(srgbToLinear(t.r), srgbToLinear(t.g), srgbToLinear(t.b))
                                    : glm::dvec3(t.r, t.g, t.b) / 255.0);
        }
}

glm::dvec3 TextureSampler::operator()(glm::dvec2 uv) const {
    const double x = uv.x * m_width - 0.5, y = uv.y * m_height - 0.5;
    const double fx = std::floor(x), fy = std::floor(y);
    const double tx = x - fx, ty = y - fy;
    auto wrap = [](double v, int n) {
        const long long i = static_cast<long long>(v) % n;
        return static_cast<std::size_t>(i < 0 ? i + n : i);
    };
    const std::size_t x0 = wrap(fx, m_width), x1 = wrap(fx + 1.0, m_width);
    const std::size_t y0 = wrap(fy, m_height), y1 = wrap(fy + 1.0, m_height);
    const auto at = [&](std::size_t i, std::size_t j) { return m_texels[j * static_cast<std::size_t>(m_width) + i]; };
    return (1.0 - ty) * ((1.0 - tx) * at(x0, y0) + tx * at(x1, y0)) + ty * ((1.0 - tx) * at(x0, y1) + tx * at(x1, y1));
}

ReflectanceInversion invertReflectance(const ReflectanceTable& t, double reflectance) {
    const auto& r = t.reflectance;
    const std::size_t n = r.size();
    if (reflectance >= r.front()) return {1.0 - t.s.front() * t.s.front(), t.gathered.front()};
    if (reflectance <= r.back()) return {1.0 - t.s.back() * t.s.back(), t.gathered.back()};
    // r descends: the first node at or below the reflectance, then linear in log s between.
    std::size_t k = 1;
    while (k < n - 1 && r[k] > reflectance) ++k;
    const double f = (r[k - 1] - reflectance) / (r[k - 1] - r[k]);
    const double s = t.s[k - 1] * std::pow(t.s[k] / t.s[k - 1], f);
    return {1.0 - s * s, t.gathered[k - 1] + f * (t.gathered[k] - t.gathered[k - 1])};
}

LogGatheredMips::LogGatheredMips(const Image8& reflectance, const ReflectanceTable& table) {
    // 8-bit sRGB: 256 values per channel, each inverted once.
    std::array<double, 256> logOf{};
    for (int v = 0; v < 256; ++v)
        logOf[static_cast<size_t>(v)] = std::log(
            std::max(invertReflectance(table, srgbToLinear(static_cast<std::uint8_t>(v))).gathered, kMinGathered));
    Level base{reflectance.width(), reflectance.height(), {}};
    base.texels.reserve(static_cast<std::size_t>(base.width) * static_cast<std::size_t>(base.height));
    for (int y = base.height - 1; y >= 0; --y)
        for (int x = 0; x < base.width; ++x) {
            const glm::u8vec4 t = reflectance.at(x, y);
            base.texels.emplace_back(logOf[t.r], logOf[t.g], logOf[t.b]);
        }
    m_levels.push_back(std::move(base));
    while (m_levels.back().width > 1 || m_levels.back().height > 1) {
        const Level& fine = m_levels.back();
        Level coarse{std::max(1, fine.width / 2), std::max(1, fine.height / 2), {}};
        coarse.texels.reserve(static_cast<std::size_t>(coarse.width) * static_cast<std::size_t>(coarse.height));
        const int sx = fine.width > 1 ? 2 : 1, sy = fine.height > 1 ? 2 : 1;
        for (int y = 0; y < coarse.height; ++y)
            for (int x = 0; x < coarse.width; ++x) {
                glm::dvec3 sum(0.0);
                for (int j = 0; j < sy; ++j)
                    for (int i = 0; i < sx; ++i)
                        sum += fine.texels[static_cast<std::size_t>(y * sy + j) * static_cast<std::size_t>(fine.width) +
                                           static_cast<std::size_t>(x * sx + i)];
                coarse.texels.push_back(sum / double(sx * sy));
            }
        m_levels.push_back(std::move(coarse));
    }
}

double LogGatheredMips::bilinear(const Level& level, glm::dvec2 uv, int c) const {
    const double x = uv.x * level.width - 0.5, y = uv.y * level.height - 0.5;
    const double fx = std::floor(x), fy = std::floor(y);
    const double tx = x - fx, ty = y - fy;
    auto wrap = [](double v, int n) {
        const long long i = static_cast<long long>(v) % n;
        return static_cast<std::size_t>(i < 0 ? i + n : i);
    };
    const std::size_t x0 = wrap(fx, level.width), x1 = wrap(fx + 1.0, level.width);
    const std::size_t y0 = wrap(fy, level.height), y1 = wrap(fy + 1.0, level.height);
    const auto at = [&](std::size_t i, std::size_t j) { return level.texels[j * static_cast<std::size_t>(level.width) + i][c]; };
    return (1.0 - ty) * ((1.0 - tx) * at(x0, y0) + tx * at(x1, y0)) + ty * ((1.0 - tx) * at(x0, y1) + tx * at(x1, y1));
}

double LogGatheredMips::operator()(glm::dvec2 uv, double level, int c) const {
    const double top = static_cast<double>(m_levels.size() - 1);
    const double l = std::clamp(level, 0.0, top);
    const auto lower = static_cast<std::size_t>(std::floor(l));
    const double t = l - static_cast<double>(lower);
    const double a = bilinear(m_levels[lower], uv, c);
    return t > 0.0 ? (1.0 - t) * a + t * bilinear(m_levels[std::min(lower + 1, m_levels.size() - 1)], uv, c) : a;
}

std::vector<float> LogGatheredMips::baseLevelRgba() const {
    std::vector<float> rgba;
    rgba.reserve(m_levels.front().texels.size() * 4);
    for (const glm::dvec3& t : m_levels.front().texels)
        rgba.insert(rgba.end(), {static_cast<float>(t.x), static_cast<float>(t.y), static_cast<float>(t.z), 0.0f});
    return rgba;
}

double surroundingLevel(double width, double texelsPerUnit) {
    const double texels = width * texelsPerUnit;
    return texels > 1.0 ? std::log2(texels) : 0.0;
}

double meanTexelDensity(const Mesh& mesh, const glm::mat4& model, int width, int height) {
    if (mesh.texcoords().empty()) return 0.0;
    const glm::dmat4 m(model);
    const auto& idx = mesh.indices();
    double surface = 0.0, texture = 0.0;
    for (std::size_t t = 0; t + 2 < idx.size(); t += 3) {
        glm::dvec3 p[3];
        glm::dvec2 uv[3];
        for (int k = 0; k < 3; ++k) {
            p[k] = glm::dvec3(m * glm::dvec4(glm::dvec3(mesh.positions()[idx[t + static_cast<size_t>(k)]]), 1.0));
            uv[k] = glm::dvec2(mesh.texcoords()[idx[t + static_cast<size_t>(k)]]) * glm::dvec2(width, height);
        }
        surface += 0.5 * glm::length(glm::cross(p[1] - p[0], p[2] - p[0]));
        const glm::dvec2 a = uv[1] - uv[0], b = uv[2] - uv[0];
        texture += 0.5 * std::abs(a.x * b.y - a.y * b.x);
    }
    return surface > 0.0 ? std::sqrt(texture / surface) : 0.0;
}

}  // namespace sss::detail
