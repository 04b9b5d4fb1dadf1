#pragma once
/// @file
/// The libsss error policy.
///
/// Every failure the caller can cause or meet is reported by throwing sss::Error:
///  - ErrorKind::InvalidArgument: a value breaks a documented precondition (a zero image size, a
///    negative ray step, a transfer function with unsorted points). The message names the option
///    or parameter ("VolumeRenderOptions::stepSize must be > 0, got -1").
///  - ErrorKind::Io / ErrorKind::Parse: a file is missing, unreadable or malformed. The message
///    names the file and the problem ("bunny.obj: face 12 references vertex 900 of 870").
///  - ErrorKind::Gl: the environment cannot do what is asked (no OpenGL 4.5 context, a shader that
///    does not compile, an incomplete framebuffer). The message says which and why.
///  - ErrorKind::GpuLimit: the scene does not fit the GPU: a texture larger than the
///    implementation allows (GL_MAX_3D_TEXTURE_SIZE, ...), more memory than the driver has free or
///    than the budget set with setGpuMemoryBudget() (include/sss/gpu_memory.h), or
///    GL_OUT_OF_MEMORY, or a buffer that shaders would reach through one storage-buffer binding
///    larger than GL_MAX_SHADER_STORAGE_BLOCK_SIZE (a mesh of millions of vertices on a device
///    that allows 128 MiB). The message names the object, the size asked and the limit.
///  - ErrorKind::Unsupported: this build of libsss leaves out what is asked, such as a file
///    format whose reader was not built (SSS_WITH_VTK=OFF, ...). The message names the format
///    and the build option.
/// Nothing in libsss terminates the process or returns a silently wrong result on bad input.
/// Internal invariants (bugs in libsss itself) are assert()s.

#include "sss/api.h"
#include <stdexcept>
#include <string>

SSS_BEGIN_API

namespace sss {

enum class ErrorKind { InvalidArgument, Io, Parse, Gl, GpuLimit, Unsupported };

/// The one exception type libsss throws; what() is a complete, human-readable message.
class Error : public std::runtime_error {
public:
    Error(ErrorKind kind, const std::string& message) : std::runtime_error(message), m_kind(kind) {}
    /// An error about one field of a struct: what() is "[<context>: ]<owner>::<field> <reason>",
    /// e.g. "MeshRenderOptions::cameras must be in 1..32, got 0".
    Error(ErrorKind kind, const std::string& owner, const std::string& field, const std::string& reason,
          const std::string& context = {})
        : std::runtime_error((context.empty() ? "" : context + ": ") + owner + "::" + field + " " + reason),
          m_kind(kind), m_field(field), m_reason(reason) {}
    ErrorKind kind() const noexcept { return m_kind; }
    /// The offending field's name ("cameras"), or empty when the error is not about one field.
    const std::string& field() const noexcept { return m_field; }
    /// What is wrong with field() ("must be in 1..32, got 0"); empty when field() is.
    const std::string& reason() const noexcept { return m_reason; }

private:
    ErrorKind m_kind;
    std::string m_field, m_reason;
};

}  // namespace sss

SSS_END_API
