#include "sss/image_compare.h"

#include "sss/error.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

namespace sss {
namespace {

std::string sizeStr(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

template <typename A, typename B>
void checkSameSize(const char* what, const A& actual, const B& expected, const char* nameA, const char* nameB) {
    if (actual.width() != expected.width() || actual.height() != expected.height())
        throw Error(ErrorKind::InvalidArgument, std::string(what) + ": image sizes differ: " + nameA + " is " +
                                                    sizeStr(actual.width(), actual.height()) + ", " + nameB +
                                                    " is " + sizeStr(expected.width(), expected.height()));
}

void checkThreshold(const char* what, int threshold) {
    if (threshold < 0)
        throw Error(ErrorKind::InvalidArgument,
                    std::string(what) + ": perPixelThreshold must be >= 0, got " + std::to_string(threshold));
}

int pixelDelta(const uint8_t* a, const uint8_t* b) {
    int d = 0;
    for (int c = 0; c < 4; ++c) d = std::max(d, std::abs(int(a[c]) - int(b[c])));
    return d;
}

}  // namespace

ImageDifference compareImages(const Image8& actual, const Image8& expected, int perPixelThreshold) {
    checkSameSize("compareImages", actual, expected, "actual", "expected");
    checkThreshold("compareImages", perPixelThreshold);
    const std::vector<uint8_t>& a = actual.data();
    const std::vector<uint8_t>& e = expected.data();
    ImageDifference d;
    d.width = actual.width();
    d.height = actual.height();
    uint64_t sum = 0, differing = 0;
    for (std::size_t i = 0; i < a.size(); i += 4) {
        for (std::size_t c = 0; c < 4; ++c) sum += uint64_t(std::abs(int(a[i + c]) - int(e[i + c])));
        const int delta = pixelDelta(&a[i], &e[i]);
        d.maxChannelDelta = std::max(d.maxChannelDelta, delta);
        if (delta > perPixelThreshold) ++differing;
    }
    const double pixels = double(a.size() / 4);
    d.differingFraction = double(differing) / pixels;
    d.meanAbsDelta = double(sum) / double(a.size());
    return d;
}

Image8 diffImage(const Image8& actual, const Image8& expected, int perPixelThreshold) {
    checkSameSize("diffImage", actual, expected, "actual", "expected");
    checkThreshold("diffImage", perPixelThreshold);
    const std::vector<uint8_t>& a = actual.data();
    const std::vector<uint8_t>& e = expected.data();
    int maxDelta = 1;
    for (std::size_t i = 0; i < a.size(); i += 4) maxDelta = std::max(maxDelta, pixelDelta(&a[i], &e[i]));
    Image8 out(expected.width(), expected.height());
    std::vector<uint8_t>& o = out.data();
    for (std::size_t i = 0; i < a.size(); i += 4) {
        const int delta = pixelDelta(&a[i], &e[i]);
        if (delta > perPixelThreshold) {
            o[i] = static_cast<uint8_t>(96 + 159 * delta / maxDelta);
            o[i + 1] = o[i + 2] = 0;
        } else {
            const double lum = 0.299 * e[i] + 0.587 * e[i + 1] + 0.114 * e[i + 2];
            o[i] = o[i + 1] = o[i + 2] = static_cast<uint8_t>(std::lround(0.6 * lum));
        }
        o[i + 3] = 255;
    }
    return out;
}

namespace {

double luminance(const float* c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

// The covered pixels' luminance at quantile q of their sorted values (0 if none is covered).
double coveredLuminancePercentile(const std::vector<float>& reference, double q) {
    std::vector<double> covered;
    for (std::size_t i = 0; i < reference.size(); i += 4)
        if (reference[i + 3] > 0.0f) covered.push_back(luminance(&reference[i]));
    if (covered.empty()) return 0.0;
    const auto at = covered.begin() + static_cast<std::ptrdiff_t>(q * static_cast<double>(covered.size() - 1));
    std::nth_element(covered.begin(), at, covered.end());
    return *at;
}

// Below this share of the 99th percentile a pixel's speck is not counted as visible.
constexpr double kVisibleSpeckFloor = 0.01;

// The share of the covered pixels with a reference luminance above `floor` (and above 0) where
// the test's is below half of it.
double speckShare(const std::vector<float>& test, const std::vector<float>& reference, double floor) {
    std::size_t counted = 0, specks = 0;
    for (std::size_t i = 0; i < test.size(); i += 4) {
        const double ref = luminance(&reference[i]);
        if (!(reference[i + 3] > 0.0f) || !(ref > 0.0) || ref < floor) continue;
        ++counted;
        specks += luminance(&test[i]) < 0.5 * ref ? 1 : 0;
    }
    return counted ? double(specks) / double(counted) : 0.0;
}

}  // namespace

double resolvedSpeckShare(const Image& test, const Image& reference, const Image& referenceStandardError) {
    checkSameSize("resolvedSpeckShare", test, reference, "test", "reference");
    checkSameSize("resolvedSpeckShare", referenceStandardError, reference, "referenceStandardError", "reference");
    const std::vector<float>& t = test.data();
    const std::vector<float>& r = reference.data();
    const std::vector<float>& e = referenceStandardError.data();
    std::size_t counted = 0, specks = 0;
    for (std::size_t i = 0; i < t.size(); i += 4) {
        const double ref = luminance(&r[i]);
        if (!(r[i + 3] > 0.0f) || !(ref > 0.0) || !(ref >= 4.0 * luminance(&e[i]))) continue;
        ++counted;
        specks += luminance(&t[i]) < 0.5 * ref ? 1 : 0;
    }
    return counted ? double(specks) / double(counted) : 0.0;
}

ErrorMetrics computeErrorMetrics(const Image& test, const Image& reference) {
    checkSameSize("computeErrorMetrics", test, reference, "test", "reference");
    const std::vector<float>& t = test.data();
    const std::vector<float>& r = reference.data();
    double sumSq = 0.0, refSq = 0.0, peak = 0.0, maxAbs = 0.0;
    for (std::size_t i = 0; i < t.size(); i += 4) {
        for (std::size_t c = 0; c < 3; ++c) {
            const double diff = double(t[i + c]) - double(r[i + c]);
            sumSq += diff * diff;
            refSq += double(r[i + c]) * double(r[i + c]);
            peak = std::max(peak, double(r[i + c]));
            // std::max would drop a NaN difference; keep it visible instead.
            if (std::isnan(diff) || std::abs(diff) > maxAbs) maxAbs = std::abs(diff);
        }
    }
    const double inf = std::numeric_limits<double>::infinity();
    ErrorMetrics m;
    if (refSq > 0.0) m.relRmse = std::sqrt(sumSq / refSq);
    else m.relRmse = sumSq == 0.0 ? 0.0 : inf;
    const double mse = sumSq / double(t.size() / 4 * 3);
    if (peak <= 0.0) peak = 1.0;
    m.psnr = mse == 0.0 ? inf : 10.0 * std::log10(peak * peak / mse);
    m.maxAbsError = maxAbs;
    m.speckShare = speckShare(t, r, 0.0);
    m.visibleSpeckShare = speckShare(t, r, kVisibleSpeckFloor * coveredLuminancePercentile(r, 0.99));
    return m;
}

}  // namespace sss
