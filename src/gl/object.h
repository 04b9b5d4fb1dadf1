#pragma once
// Move-only ownership of one GL object name. Each object kind is a thin class deriving from
// Object<Traits>, where Traits::destroy deletes the name and Traits::labelNamespace is what
// glObjectLabel expects. A default-constructed Object owns nothing (created later, or moved from).

#include "gl/gl.h"

#include <string_view>
#include <utility>

namespace sss::gl {

template <typename Traits>
class Object {
public:
    Object() = default;
    explicit Object(GLuint id) noexcept : m_id(id) {}
    ~Object() { reset(); }
    Object(const Object&) = delete;
    Object& operator=(const Object&) = delete;
    Object(Object&& other) noexcept : m_id(std::exchange(other.m_id, 0)) {}
    Object& operator=(Object&& other) noexcept {
        if (this != &other) {
            reset();
            m_id = std::exchange(other.m_id, 0);
        }
        return *this;
    }

    GLuint id() const noexcept { return m_id; }
    explicit operator bool() const noexcept { return m_id != 0; }

    /// Names the object in KHR_debug messages and GPU debuggers.
    void setLabel(std::string_view label) const {
        if (m_id) glObjectLabel(Traits::labelNamespace, m_id, static_cast<GLsizei>(label.size()), label.data());
    }

    /// Gives up ownership without deleting the name.
    [[nodiscard]] GLuint release() noexcept { return std::exchange(m_id, 0); }

    void reset() noexcept {
        if (m_id) Traits::destroy(m_id);
        m_id = 0;
    }

private:
    GLuint m_id = 0;
};

}  // namespace sss::gl
