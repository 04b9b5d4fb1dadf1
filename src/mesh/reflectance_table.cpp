#include "mesh/reflectance_table.h"

#include <algorithm>
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

}  // namespace sss::detail
