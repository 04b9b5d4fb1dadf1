#include "sss/volume_clip.h"

#include "core/volume_clip_space.h"
#include "sss/error.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sss {
namespace {

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

bool VolumeClip::clipsNothing() const {
    return planes.empty() && cropSpace == CropSpace::Data && cropMin == glm::vec3(0.0f) && cropMax == glm::vec3(1.0f);
}

void validate(const VolumeClip& clip, const std::string& context) {
    const auto fail = [&](const std::string& field, const std::string& reason) {
        throw Error(ErrorKind::InvalidArgument, "VolumeClip", field, reason, context);
    };
    if (clip.planes.size() > static_cast<size_t>(VolumeClip::kMaxPlanes))
        fail("planes", "holds at most " + std::to_string(VolumeClip::kMaxPlanes) + " planes, got " +
                           std::to_string(clip.planes.size()));
    for (size_t i = 0; i < clip.planes.size(); ++i) {
        const ClipPlane& p = clip.planes[i];
        const std::string field = "planes[" + std::to_string(i) + "]";
        if (!finite(p.point) || !finite(p.normal)) fail(field, "must be finite");
        if (glm::dot(p.normal, p.normal) == 0.0f) fail(field + ".normal", "must be non-zero");
    }
    if (!finite(clip.cropMin)) fail("cropMin", "must be finite");
    if (!finite(clip.cropMax)) fail("cropMax", "must be finite");
    const bool data = clip.cropSpace == CropSpace::Data;
    for (int a = 0; a < 3; ++a) {
        const bool inside = !data || (clip.cropMin[a] >= 0.0f && clip.cropMax[a] <= 1.0f);
        if (!(inside && clip.cropMin[a] < clip.cropMax[a]))
            fail("cropMin", std::string("must be below cropMax on every axis") +
                                (data ? ", both in [0, 1] (normalised data coordinates)" : " (world coordinates)") +
                                ", got " + std::string("xyz").substr(static_cast<size_t>(a), 1) + " from " +
                                std::to_string(clip.cropMin[a]) + " to " + std::to_string(clip.cropMax[a]));
    }
}

namespace detail {

bool TextureClip::keeps(glm::dvec3 tc) const {
    if (!active) return true;
    for (const glm::dvec4& p : planes)
        if (glm::dot(glm::dvec3(p), tc) + p.w < 0.0) return false;
    return glm::all(glm::greaterThanEqual(tc, cropMin)) && glm::all(glm::lessThanEqual(tc, cropMax));
}

bool TextureClip::clipSpan(glm::dvec3 origin, glm::dvec3 direction, double& t0, double& t1) const {
    if (!active) return t0 < t1;
    for (const glm::dvec4& p : planes) {
        const double rate = glm::dot(glm::dvec3(p), direction), start = glm::dot(glm::dvec3(p), origin) + p.w;
        if (rate > 0.0) t0 = std::max(t0, -start / rate);
        else if (rate < 0.0) t1 = std::min(t1, -start / rate);
        else if (start < 0.0) return false;
    }
    for (int a = 0; a < 3; ++a) {
        if (direction[a] == 0.0) {
            if (origin[a] < cropMin[a] || origin[a] > cropMax[a]) return false;
            continue;
        }
        const double u = (cropMin[a] - origin[a]) / direction[a], v = (cropMax[a] - origin[a]) / direction[a];
        t0 = std::max(t0, std::min(u, v));
        t1 = std::min(t1, std::max(u, v));
    }
    return t0 < t1;
}

TextureClip textureClip(const VolumeClip& clip, const glm::mat4& model, const Bounds& box) {
    TextureClip t;
    t.active = !clip.clipsNothing();
    t.light = t.active && !clip.clippedMatterCastsShadows;
    // world = A (box.min + tc * size) + b, so n . (world - point) = (A^T n * size) . tc + rest.
    const glm::dmat4 m(model);
    const glm::dmat3 linear(m);
    const glm::dvec3 translation(m[3]);
    const glm::dvec3 size(box.size()), origin(box.min);
    const auto toTexture = [&](const ClipPlane& p) {
        const glm::dvec3 n = glm::transpose(linear) * glm::dvec3(p.normal);
        return glm::dvec4(n * size, glm::dot(n, origin) + glm::dot(glm::dvec3(p.normal), translation - glm::dvec3(p.point)));
    };
    for (const ClipPlane& p : clip.planes) {
        const glm::dvec3 n(p.normal);
        t.planes.push_back(clip.planeSpace == CropSpace::Data ? glm::dvec4(n, -glm::dot(n, glm::dvec3(p.point)))
                                                              : toTexture(p));
    }
    constexpr double open = std::numeric_limits<double>::infinity();
    if (clip.cropSpace == CropSpace::World) {
        // A world box is six planes in texture space, and the texture-space box stays open.
        for (int a = 0; a < 3; ++a) {
            glm::vec3 normal(0.0f);
            normal[a] = 1.0f;
            t.planes.push_back(toTexture({clip.cropMin, normal}));
            t.planes.push_back(toTexture({clip.cropMax, -normal}));
        }
        t.cropMin = glm::dvec3(-open);
        t.cropMax = glm::dvec3(open);
        return t;
    }
    for (int i = 0; i < 3; ++i) {
        t.cropMin[i] = clip.cropMin[i] > 0.0f ? clip.cropMin[i] : -open;
        t.cropMax[i] = clip.cropMax[i] < 1.0f ? clip.cropMax[i] : open;
    }
    return t;
}

}  // namespace detail
}  // namespace sss
