#pragma once
// Golden-image comparison. Goldens live in tests/golden/<name>.png, as display images (sRGB) of
// the renderers' linear output. A comparison passes when
//  - the largest per-channel difference is <= maxChannelDelta (0..255), and
//  - the fraction of pixels differing by more than 1 in any channel is <= maxDifferingFraction.
// On failure <name>.actual.png and <name>.diff.png are written to build/tests/output/.
// A missing golden fails. SSS_UPDATE_GOLDENS=1 overwrites (or creates) the golden and passes:
// use it only deliberately, and say why in the commit message.
#include <sss/image.h>

#include <string>

namespace sss::test {

struct GoldenTolerance {
    int maxChannelDelta = 3;              ///< default: small, for llvmpipe/LLVM rounding changes
    double maxDifferingFraction = 0.002;  ///< default: 0.2 % of the pixels
};

/// REQUIREs that the display image of `linear` (the default DisplayTransform: sRGB, exposure 0,
/// no tone mapping) matches tests/golden/<name>.png within `tolerance`.
void requireMatchesGolden(const Image& linear, const std::string& name, GoldenTolerance tolerance = {});

}  // namespace sss::test
