#pragma once
// What the volume accuracy tables share (sss-bench --accuracy volume, light-volume, surfaces):
// the view, the scaling that forgives the paper model its units, and timed GPU images.
#include <sss/sss.h>

#include <sss/volume_path_tracer.h>

#include <glm/vec3.hpp>

#include <string>

class BenchmarkContext;

namespace volume_accuracy {

/// The best single factor k minimising |k test - reference| over all pixels and channels: how
/// far a model is off in shape once its overall brightness is forgiven.
double bestScale(const sss::Image& test, const sss::Image& reference);
/// `image` with its rgb times k.
sss::Image scaled(sss::Image image, double k);
/// Per channel, the sum of test over the sum of reference.
glm::dvec3 meanRatio(const sss::Image& test, const sss::Image& reference);
/// From 30 degrees aside and 20 above, framed tightly.
sss::Camera volumeAccuracyCamera(const sss::Volume& volume, int width, int height);
/// One directional light from above, behind and to the right of the viewer.
sss::DirectionalLight volumeAccuracyLight();

/// A path-traced truth and its own expected relRMSE (from its standard errors).
struct PathTracedTruth {
    sss::Image image{1, 1};
    double relativeRmseEstimate = 0.0;
};
/// renderVolumePathTraced of the scene (the data at 256 TF entries, identity model), or its copy
/// in --reference-cache: `name`.exr and `name`-stderr.exr (the standard error per pixel). `name`
/// must hold everything the truth depends on.
PathTracedTruth cachedPathTraced(BenchmarkContext& bench, const std::string& name, const sss::Volume& volume,
                                 const sss::TransferFunction& tf, const sss::DirectionalLight& light,
                                 const sss::Camera& camera, int width, int height,
                                 const sss::VolumePathTracerOptions& options);

/// A GPU volume image and its median frame time.
struct TimedImage {
    sss::Image image;
    double medianMs = 0.0;
};
/// One untimed frame (compilation, light volume), then three timed ones. With `rebuild` the timed
/// frames alternate the light with its nudged twin, so each one rebuilds the light volume; the
/// image is then rendered with `light` again.
TimedImage renderVolumeTimed(const sss::Volume& volume, const sss::TransferFunction& tf, const sss::DirectionalLight& light,
                             const sss::VolumeRenderOptions& options, const sss::Camera& camera, int width, int height,
                             bool rebuild);

}  // namespace volume_accuracy
