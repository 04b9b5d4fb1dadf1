#pragma once
/// @file
/// Image comparison for golden tests (8-bit) and accuracy measurements (float).

#include "sss/api.h"
#include "sss/image.h"

SSS_BEGIN_API

namespace sss {

/// How far an 8-bit image is from an expected one.
struct ImageDifference {
    int maxChannelDelta = 0;         ///< largest |actual - expected| over all pixels and RGBA channels, 0..255
    double differingFraction = 0.0;  ///< fraction of pixels whose largest channel delta > the threshold
    double meanAbsDelta = 0.0;       ///< mean |actual - expected| over all pixels and RGBA channels, 0..255
    int width = 0;                   ///< image width
    int height = 0;                  ///< image height
};

/// Compares two RGBA 8-bit images channel by channel. A pixel "differs" when its largest
/// channel delta exceeds perPixelThreshold (default 1, so off-by-one rounding is tolerated).
/// @throws Error InvalidArgument if the sizes differ (naming both) or perPixelThreshold < 0.
ImageDifference compareImages(const Image8& actual, const Image8& expected, int perPixelThreshold = 1);

/// A visual diff of expected's size: pixels whose largest channel delta is <= perPixelThreshold
/// show expected as dimmed grey (60% luminance); differing pixels are red, brighter for larger
/// deltas (red = 96 + 159 * delta / largest delta in the image). Alpha is 255.
/// @throws Error InvalidArgument as compareImages.
Image8 diffImage(const Image8& actual, const Image8& expected, int perPixelThreshold = 1);

/// Float error metrics over the RGB channels (alpha is ignored).
struct ErrorMetrics {
    double relRmse = 0.0;      ///< sqrt(sum (t - r)^2 / sum r^2); 0 if both are all zero, +inf if only the reference is
    double psnr = 0.0;         ///< 10 log10(peak^2 / MSE) in dB, peak = largest reference value (1 if that is <= 0); +inf if identical
    double maxAbsError = 0.0;  ///< largest |t - r|
    /// Specks: the share of the reference's covered pixels (alpha > 0, luminance > 0) where the
    /// test's luminance is below half the reference's: visibility failures, black spots.
    double speckShare = 0.0;
    /// Specks a viewer can see: the same share among the covered pixels whose reference
    /// luminance is at least 1 % of the covered pixels' 99th percentile. speckShare also counts
    /// pixels deep in shadow, where both images are nearly black and a reference's own noise
    /// decides.
    double visibleSpeckShare = 0.0;
};

/// Error of `test` against `reference` over RGB. Non-finite test values make the metrics
/// non-finite. @throws Error InvalidArgument if the sizes differ (naming both).
ErrorMetrics computeErrorMetrics(const Image& test, const Image& reference);

/// Specks where a Monte Carlo reference resolves its own value: the share of speckShare's pixels
/// whose reference luminance is at least four times its standard error (the channels' standard
/// errors weighted like the luminance and summed, as the channels share their samples), so that
/// "below half the reference" lies at least two standard errors out. Elsewhere a second
/// reference from other random streams is itself below half the first at a few per cent of the
/// pixels (the 2 m scenes of docs/near-field.md), and a test there says nothing.
/// `referenceStandardError`: per-pixel rgb standard errors (MeshReferenceResult::standardError).
/// @throws Error InvalidArgument if the sizes differ (naming them).
double resolvedSpeckShare(const Image& test, const Image& reference, const Image& referenceStandardError);

}  // namespace sss

SSS_END_API
