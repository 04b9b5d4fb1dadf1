#include "sss/camera.h"

#include "util/format.h"

#include "sss/error.h"

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <sstream>
#include <string>
#include <utility>

namespace sss {
namespace {

constexpr float kMaxPitch = 89.0f;
constexpr float kMinDistance = 1e-6f;

template <typename T>
std::string str(const T& v) {
    return detail::formatNumber(v);
}

std::string str(glm::vec3 v) { return detail::formatVec(v); }

bool isFinite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void requireFinite(float v, const char* what) {
    if (!std::isfinite(v))
        throw Error(ErrorKind::InvalidArgument, std::string(what) + " must be finite, got " + str(v));
}

void requirePositive(float v, const char* what) {
    if (!std::isfinite(v) || v <= 0.0f)
        throw Error(ErrorKind::InvalidArgument, std::string(what) + " must be finite and > 0, got " + str(v));
}

float wrapDegrees(float deg) {
    float w = std::fmod(deg + 180.0f, 360.0f);
    if (w < 0.0f) w += 360.0f;
    return w - 180.0f;
}

}  // namespace

void Camera::setTarget(glm::vec3 target) {
    if (!std::isfinite(target.x) || !std::isfinite(target.y) || !std::isfinite(target.z))
        throw Error(ErrorKind::InvalidArgument, "Camera::setTarget: target must be finite, got " + str(target));
    m_target = target;
}

void Camera::setDistance(float distance) {
    requirePositive(distance, "Camera::setDistance: distance");
    m_distance = distance;
}

void Camera::setYaw(float degrees) {
    requireFinite(degrees, "Camera::setYaw: yaw");
    m_yaw = wrapDegrees(degrees);
}

void Camera::setPitch(float degrees) {
    requireFinite(degrees, "Camera::setPitch: pitch");
    m_pitch = std::clamp(degrees, -kMaxPitch, kMaxPitch);
}

void Camera::setFovY(float degrees) {
    if (!(degrees > 0.0f && degrees < 180.0f))
        throw Error(ErrorKind::InvalidArgument, "Camera::setFovY: fovY must be in (0, 180) degrees, got " + str(degrees));
    m_fovY = degrees;
}

void Camera::setOrthoHeight(float height) {
    requirePositive(height, "Camera::setOrthoHeight: orthoHeight");
    m_orthoHeight = height;
}

void Camera::setClipPlanes(float nearPlane, float farPlane) {
    requirePositive(nearPlane, "Camera::setClipPlanes: near");
    requireFinite(farPlane, "Camera::setClipPlanes: far");
    if (!(farPlane > nearPlane))
        throw Error(ErrorKind::InvalidArgument, "Camera::setClipPlanes: far must be > near, got near " +
                                                    str(nearPlane) + ", far " + str(farPlane));
    m_near = nearPlane;
    m_far = farPlane;
}

glm::vec3 Camera::position() const {
    const float yaw = glm::radians(m_yaw), pitch = glm::radians(m_pitch);
    const glm::vec3 d(std::sin(yaw) * std::cos(pitch), std::sin(pitch), std::cos(yaw) * std::cos(pitch));
    return m_target + m_distance * d;
}

glm::vec3 Camera::forward() const { return glm::normalize(m_target - position()); }

// |pitch| <= 89 keeps forward away from +y, so the cross products are well defined.
glm::vec3 Camera::right() const { return glm::normalize(glm::cross(forward(), glm::vec3(0, 1, 0))); }

glm::vec3 Camera::up() const { return glm::cross(right(), forward()); }

glm::mat4 Camera::view() const { return glm::lookAtRH(position(), m_target, glm::vec3(0, 1, 0)); }

glm::mat4 Camera::projection(float aspect) const {
    if (!std::isfinite(aspect) || aspect <= 0.0f)
        throw Error(ErrorKind::InvalidArgument, "Camera::projection: aspect must be finite and > 0, got " + str(aspect));
    // Explicit _NO (clip z in [-1, 1]) so a GLM_FORCE_DEPTH_ZERO_TO_ONE elsewhere cannot change it.
    glm::mat4 p;
    if (m_projection == Projection::Perspective) {
        p = glm::perspectiveRH_NO(glm::radians(m_fovY), aspect, m_near, m_far);
    } else {
        const float h = 0.5f * m_orthoHeight, w = h * aspect;
        p = glm::orthoRH_NO(-w, w, -h, h, m_near, m_far);
    }
    // A shift in NDC (x_ndc += offset.x): a translation applied after the projection.
    if (m_subpixelOffset == glm::vec2(0.0f)) return p;
    return glm::translate(glm::mat4(1.0f), glm::vec3(m_subpixelOffset, 0.0f)) * p;
}

void Camera::setSubpixelOffset(glm::vec2 offset) {
    requireFinite(offset.x, "Camera::setSubpixelOffset: offset.x");
    requireFinite(offset.y, "Camera::setSubpixelOffset: offset.y");
    m_subpixelOffset = offset;
}

void Camera::orbit(float dYawDeg, float dPitchDeg) {
    requireFinite(dYawDeg, "Camera::orbit: dYawDeg");
    requireFinite(dPitchDeg, "Camera::orbit: dPitchDeg");
    m_yaw = wrapDegrees(m_yaw + dYawDeg);
    m_pitch = std::clamp(m_pitch + dPitchDeg, -kMaxPitch, kMaxPitch);
}

void Camera::zoom(float factor) {
    requirePositive(factor, "Camera::zoom: factor");
    m_distance = std::max(m_distance * factor, kMinDistance);
    m_orthoHeight = std::max(m_orthoHeight * factor, kMinDistance);
}

void Camera::pan(glm::vec2 delta) {
    requireFinite(delta.x, "Camera::pan: delta.x");
    requireFinite(delta.y, "Camera::pan: delta.y");
    m_target += (right() * delta.x + up() * delta.y) * m_distance;
}

namespace {

// The bounds' centre and bounding-sphere radius (at least 1e-3); throws naming the caller if
// the bounds are empty or not finite.
std::pair<glm::vec3, float> checkedSphere(const Bounds& bounds, const char* caller) {
    if (bounds.empty()) throw Error(ErrorKind::InvalidArgument, std::string(caller) + ": bounds is empty");
    const glm::vec3 c = bounds.center();
    const float r = bounds.radius();
    if (!std::isfinite(r) || !isFinite(c))
        throw Error(ErrorKind::InvalidArgument,
                    std::string(caller) + ": bounds min " + str(bounds.min) + ", max " + str(bounds.max) +
                        (isFinite(bounds.min) && isFinite(bounds.max)
                             ? " are too large: their radius overflows float (keep coordinates within +-1e18)"
                             : " are not finite"));
    return {c, std::max(r, 1e-3f)};
}

}  // namespace

void Camera::frame(const Bounds& bounds) {
    const auto [c, r] = checkedSphere(bounds, "Camera::frame");
    m_target = c;
    m_distance = r / std::sin(glm::radians(0.5f * m_fovY));
    m_orthoHeight = 2.0f * r;
    // distance > r always (sin < 1), so near > 0; the margins leave room to orbit and zoom a bit.
    m_near = std::max(0.5f * (m_distance - r), 1e-4f * m_distance);
    m_far = 2.0f * (m_distance + r);
}

void Camera::frameTight(const Bounds& bounds, float aspect, float margin) {
    const auto [c, r] = checkedSphere(bounds, "Camera::frameTight");
    // A point-like or flat box still gets some extent, so every corner has a positive depth.
    const glm::vec3 half = glm::max(0.5f * bounds.size(), glm::vec3(1e-3f));
    glm::vec3 corners[8];
    for (int i = 0; i < 8; ++i)
        corners[i] = c + glm::vec3((i & 1) ? half.x : -half.x, (i & 2) ? half.y : -half.y, (i & 4) ? half.z : -half.z);
    frameTight(std::span<const glm::vec3>(corners), aspect, margin);
}

void Camera::frameTight(std::span<const glm::vec3> points, float aspect, float margin) {
    if (points.empty()) throw Error(ErrorKind::InvalidArgument, "Camera::frameTight: no points to frame");
    Bounds bounds;
    for (const glm::vec3& p : points) bounds.extend(p);
    const auto [c, r] = checkedSphere(bounds, "Camera::frameTight");
    requirePositive(aspect, "Camera::frameTight: aspect");
    if (!(margin >= 0.0f && margin <= 0.5f))
        throw Error(ErrorKind::InvalidArgument, "Camera::frameTight: margin must be in [0, 0.5], got " + str(margin));
    // The view basis depends on yaw and pitch only, not on the target or the distance.
    const glm::vec3 f = forward(), x = right(), y = up();

    if (m_projection == Projection::Orthographic) {
        glm::vec2 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
        for (const glm::vec3& p : points) {
            const glm::vec2 s(glm::dot(p, x), glm::dot(p, y));
            lo = glm::min(lo, s);
            hi = glm::max(hi, s);
        }
        const glm::vec2 mid = 0.5f * (lo + hi);
        m_target = mid.x * x + mid.y * y + glm::dot(c, f) * f;
        m_orthoHeight = std::max({hi.y - lo.y, (hi.x - lo.x) / aspect, 2e-3f}) / (1.0f - margin);
        m_distance = r / std::sin(glm::radians(0.5f * m_fovY));
    } else {
        // In the basis (x, y, f) a point (a, b, z) is in view from the eye (ex, ey, ez) when
        // |a - ex| <= tx (z - ez) and |b - ey| <= ty (z - ez). Each side plane of the frustum,
        // moved until it touches the points, is a - tx z = R (right) or -a - tx z = L (left);
        // the eye lies on both: ex - tx ez = R and -ex - tx ez = L. Likewise top and bottom.
        const float ty = std::tan(glm::radians(0.5f * m_fovY)) * (1.0f - margin), tx = ty * aspect;
        float right = std::numeric_limits<float>::lowest(), left = right, top = right, bottom = right;
        float zMin = std::numeric_limits<float>::max();
        for (const glm::vec3& p : points) {
            const float a = glm::dot(p, x), b = glm::dot(p, y), z = glm::dot(p, f);
            right = std::max(right, a - tx * z);
            left = std::max(left, -a - tx * z);
            top = std::max(top, b - ty * z);
            bottom = std::max(bottom, -b - ty * z);
            zMin = std::min(zMin, z);
        }
        const float ex = 0.5f * (right - left), ey = 0.5f * (top - bottom);
        // The pair that needs the eye further back decides; the other pair then has room. Points
        // on a line along the view axis would put the eye on the nearest one: keep it in front.
        const float ez = std::min({-(right + left) / (2.0f * tx), -(top + bottom) / (2.0f * ty), zMin - 1e-3f * r});
        const glm::vec3 eye = ex * x + ey * y + ez * f;
        m_distance = std::max(glm::dot(c, f) - ez, kMinDistance);
        m_target = eye + m_distance * f;
        m_orthoHeight = 2.0f * r;
    }
    // As in frame(): near halfway to the nearest point, far well beyond the farthest.
    float nearest = std::numeric_limits<float>::max(), farthest = 0.0f;
    const glm::vec3 eye = position();
    for (const glm::vec3& p : points) {
        nearest = std::min(nearest, glm::dot(p - eye, f));
        farthest = std::max(farthest, glm::dot(p - eye, f));
    }
    m_near = std::max(0.5f * nearest, 1e-4f * m_distance);
    m_far = std::max(2.0f * farthest, 2.0f * (m_distance + r));
}

}  // namespace sss
