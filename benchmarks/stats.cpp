#include "bench.h"

#include <algorithm>
#include <cmath>
#include <numeric>

Stats summarize(std::vector<double> samples) {
    if (samples.empty()) throw std::invalid_argument("summarize: no samples");
    std::sort(samples.begin(), samples.end());
    const std::size_t n = samples.size();
    Stats s;
    s.runs = static_cast<int>(n);
    s.minMs = samples.front();
    s.maxMs = samples.back();
    s.medianMs = n % 2 == 1 ? samples[n / 2] : 0.5 * (samples[n / 2 - 1] + samples[n / 2]);
    s.meanMs = std::accumulate(samples.begin(), samples.end(), 0.0) / static_cast<double>(n);
    if (n > 1) {
        double sq = 0.0;
        for (double x : samples) sq += (x - s.meanMs) * (x - s.meanMs);
        s.stddevMs = std::sqrt(sq / static_cast<double>(n - 1));
    }
    return s;
}
