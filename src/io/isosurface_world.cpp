#include "sss/error.h"
#include "sss/isosurface.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace sss {

WorldIsosurface extractIsosurfaceInWorldBox(const Volume& volume, const IsosurfaceOptions& options,
                                            double millimetresPerVolumeUnit) {
    if (!(std::isfinite(millimetresPerVolumeUnit) && millimetresPerVolumeUnit > 0.0))
        throw Error(ErrorKind::InvalidArgument, "extractIsosurfaceInWorldBox", "millimetresPerVolumeUnit",
                    "must be finite and > 0, got " + std::to_string(millimetresPerVolumeUnit));
    const glm::dvec3 extent = glm::dvec3(volume.dims()) * glm::dvec3(volume.spacing());
    const double largestSide = std::max({extent.x, extent.y, extent.z});
    const auto scale = static_cast<float>(1.0 / largestSide);
    return {extractIsosurface(volume, options).transformed(glm::scale(glm::mat4(1.0f), glm::vec3(scale))),
            millimetresPerVolumeUnit * largestSide};
}

}  // namespace sss
