#pragma once
/// @file
/// Orbit camera: view and projection matrices (OpenGL conventions: right-handed, clip z in
/// [-1, 1]).

#include "sss/api.h"
#include "sss/bounds.h"

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <span>

SSS_BEGIN_API

namespace sss {

/// Projection kind of a Camera.
enum class Projection { Perspective, Orthographic };

/// A camera orbiting a target point. The eye is at target + distance * d, where
/// d = (sin(yaw) cos(pitch), sin(pitch), cos(yaw) cos(pitch)); yaw turns around +y, pitch
/// lifts the eye. Up is +y. The default camera (target 0, distance 3, yaw 0, pitch 0) sits at
/// (0,0,3) and looks along -z. All angles are in degrees. Setters validate and throw
/// Error(InvalidArgument) naming the parameter; no setter leaves the camera half-changed.
class Camera {
public:
    /// Target (0,0,0), distance 3, yaw 0, pitch 0, fovY 45, orthoHeight 2, near 0.01, far 100,
    /// perspective.
    Camera() = default;

    glm::vec3 target() const { return m_target; }           ///< point the camera looks at
    float distance() const { return m_distance; }           ///< eye-to-target distance, > 0
    float yaw() const { return m_yaw; }                     ///< degrees, wrapped to [-180, 180)
    float pitch() const { return m_pitch; }                 ///< degrees, in [-89, 89]
    float fovY() const { return m_fovY; }                   ///< vertical field of view, degrees
    float orthoHeight() const { return m_orthoHeight; }     ///< view height for Orthographic
    float nearPlane() const { return m_near; }              ///< near clip distance, > 0
    float farPlane() const { return m_far; }                ///< far clip distance, > near
    Projection projectionType() const { return m_projection; }  ///< perspective or orthographic

    /// @throws Error InvalidArgument if not finite.
    void setTarget(glm::vec3 target);
    /// @throws Error InvalidArgument unless finite and > 0.
    void setDistance(float distance);
    /// Wraps to [-180, 180). @throws Error InvalidArgument if not finite.
    void setYaw(float degrees);
    /// Clamps to [-89, 89] (keeps the view matrix well defined). @throws if not finite.
    void setPitch(float degrees);
    /// @throws Error InvalidArgument unless in (0, 180).
    void setFovY(float degrees);
    /// @throws Error InvalidArgument unless finite and > 0.
    void setOrthoHeight(float height);
    /// @throws Error InvalidArgument unless 0 < near < far, both finite.
    void setClipPlanes(float nearPlane, float farPlane);
    /// Chooses perspective or orthographic projection.
    void setProjectionType(Projection projection) { m_projection = projection; }
    /// Shifts the image by `offset` in normalized device coordinates (one pixel of a W x H
    /// target is 2/W by 2/H) without moving the camera: the sub-pixel jitter of progressive
    /// anti-aliasing (FrameAccumulator). Default (0, 0).
    /// @throws Error InvalidArgument if offset is not finite.
    void setSubpixelOffset(glm::vec2 offset);
    glm::vec2 subpixelOffset() const { return m_subpixelOffset; }

    /// Eye position in world space.
    glm::vec3 position() const;
    /// Unit vector from the eye towards the target.
    glm::vec3 forward() const;
    /// Unit vector pointing right on screen.
    glm::vec3 right() const;
    /// Unit vector pointing up on screen.
    glm::vec3 up() const;
    /// World-to-view matrix (the eye at the origin looking along -z).
    glm::mat4 view() const;
    /// View-to-clip matrix for a viewport of the given width/height ratio. Orthographic uses a
    /// view of orthoHeight() x orthoHeight()*aspect centred on the axis.
    /// @throws Error InvalidArgument unless aspect is finite and > 0.
    glm::mat4 projection(float aspect) const;

    /// Adds to yaw and pitch (pitch clamped to [-89, 89]); the distance does not change.
    /// @throws Error InvalidArgument if an argument is not finite.
    void orbit(float dYawDeg, float dPitchDeg);
    /// Multiplies distance by factor (< 1 moves closer) and, so that zoom also works in
    /// orthographic mode, orthoHeight too. The distance never drops below 1e-6.
    /// @throws Error InvalidArgument unless factor is finite and > 0.
    void zoom(float factor);
    /// Moves the target (and with it the eye) by delta.x * distance along right() and
    /// delta.y * distance along up(). @throws Error InvalidArgument if delta is not finite.
    void pan(glm::vec2 delta);
    /// Points the camera at the centre of bounds and sets the distance so the bounding sphere
    /// exactly fits the vertical field of view (distance = radius / sin(fovY/2)); orthoHeight
    /// becomes the sphere's diameter, near = max((distance - radius) / 2, distance * 1e-4) and
    /// far = 2 * (distance + radius). Yaw and pitch are kept. A point-like box is treated as a
    /// sphere of radius 1e-3. @throws Error InvalidArgument if bounds is empty or not finite.
    void frame(const Bounds& bounds);
    /// Frames bounds tightly for the current yaw, pitch, fovY and projection type and a
    /// viewport of the given width/height ratio: the projection of the box's eight corners
    /// fills the view up to margin (a fraction of the view's half-width and half-height, in
    /// [0, 0.5]) on the axis where it is larger and is centred on the other. frame() fits the
    /// bounding sphere in the vertical field of view, which leaves most of a wide viewport
    /// empty; this fills it. The view direction is kept; the target becomes the point on the
    /// view axis at the depth of the box's centre, so orbiting turns around the subject.
    /// Perspective: the eye is where the frustum's side planes touch the box (the tighter
    /// pair decides the distance). Orthographic: orthoHeight fits the projected box and the
    /// distance is frame()'s. Near and far enclose the box with frame()'s margins. A
    /// point-like or flat box is given a half-side of at least 1e-3.
    /// @throws Error InvalidArgument if bounds is empty or not finite, aspect is not finite
    ///         and > 0, or margin is outside [0, 0.5].
    void frameTight(const Bounds& bounds, float aspect, float margin = 0.05f);
    /// frameTight() for a set of points, e.g. a mesh's vertices: their projection, not their
    /// box's, fills the view, which frames round or rotated subjects closer. The eye stays in
    /// front of every point. @throws Error InvalidArgument as above, or if points is empty.
    void frameTight(std::span<const glm::vec3> points, float aspect, float margin = 0.05f);

private:
    glm::vec3 m_target{0.0f};
    float m_distance = 3.0f;
    float m_yaw = 0.0f;
    float m_pitch = 0.0f;
    float m_fovY = 45.0f;
    float m_orthoHeight = 2.0f;
    float m_near = 0.01f;
    float m_far = 100.0f;
    Projection m_projection = Projection::Perspective;
    glm::vec2 m_subpixelOffset{0.0f};
};

}  // namespace sss

SSS_END_API
