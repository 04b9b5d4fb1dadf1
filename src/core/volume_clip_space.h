#pragma once
// A VolumeClip in a volume's normalised data (texture) coordinates, where the ray casters, the
// light volume, the path tracer and the CPU references test their samples: each plane becomes
// dot(n, tc) + d >= 0, and the crop box a box in the same coordinates.
#include "sss/api.h"
#include "sss/bounds.h"
#include "sss/volume_clip.h"

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include <vector>

namespace sss::detail {

struct TextureClip {
    std::vector<glm::dvec4> planes;  ///< (n, d): kept where dot(n, tc) + d >= 0
    /// The crop box. Its faces that coincide with the volume's own are open (+-infinity), so a
    /// sample just outside the volume (a slab's half step, a filter footprint) is not cut.
    glm::dvec3 cropMin{0.0}, cropMax{1.0};
    bool active = false;  ///< anything is cut
    bool light = false;   ///< the cut matter is gone for the light too (casts no shadows)
    bool keeps(glm::dvec3 tc) const;
    /// Whether the light passes through the medium at tc.
    bool lightSeesMedium(glm::dvec3 tc) const { return !light || keeps(tc); }
    /// Narrows [t0, t1] of the ray tc(t) = origin + t direction to the part kept (convex: one
    /// interval); false when none is.
    bool clipSpan(glm::dvec3 origin, glm::dvec3 direction, double& t0, double& t1) const;
};

/// `clip` for a volume of box `box` placed by `model`.
SSS_API TextureClip textureClip(const VolumeClip& clip, const glm::mat4& model, const Bounds& box);

}  // namespace sss::detail
