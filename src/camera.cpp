#include "sss/camera.h"

#include "format.h"

#include "sss/error.h"

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

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

void Camera::frame(const Bounds& bounds) {
    if (bounds.empty()) throw Error(ErrorKind::InvalidArgument, "Camera::frame: bounds is empty");
    const glm::vec3 c = bounds.center();
    float r = bounds.radius();
    if (!std::isfinite(r) || !std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z))
        throw Error(ErrorKind::InvalidArgument,
                    "Camera::frame: bounds min " + str(bounds.min) + ", max " + str(bounds.max) +
                        (isFinite(bounds.min) && isFinite(bounds.max)
                             ? " are too large: their radius overflows float (keep coordinates within +-1e18)"
                             : " are not finite"));
    r = std::max(r, 1e-3f);
    m_target = c;
    m_distance = r / std::sin(glm::radians(0.5f * m_fovY));
    m_orthoHeight = 2.0f * r;
    // distance > r always (sin < 1), so near > 0; the margins leave room to orbit and zoom a bit.
    m_near = std::max(0.5f * (m_distance - r), 1e-4f * m_distance);
    m_far = 2.0f * (m_distance + r);
}

}  // namespace sss
