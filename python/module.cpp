// The `sss` Python module: libsss through pybind11. The API is described in README.md
// ("Python") and in the docstrings; bind_data.cpp binds the CPU-side data, bind_render.cpp the
// GL side. Errors: every sss::Error becomes an sss.Error (see registerErrors below).
#include "bindings.h"

#include <sss/log.h>

namespace ssspy {
namespace {

// sss::Error -> Python. sss.Error is the base of all; the kind picks a subclass that also
// derives from the matching built-in exception, so callers can catch either:
//   InvalidArgumentError(Error, ValueError)  ErrorKind::InvalidArgument (and bad arrays)
//   IoError(Error, OSError)                  ErrorKind::Io (missing or unreadable files)
//   ParseError(Error, ValueError)            ErrorKind::Parse (malformed files)
//   GlError(Error, RuntimeError)             ErrorKind::Gl (no context, shader failure)
//   GpuLimitError(Error, MemoryError)        ErrorKind::GpuLimit (the scene does not fit the GPU)
//   UnsupportedError(Error, NotImplementedError) ErrorKind::Unsupported (a reader left out of the build)
// The message is the library's what(), unchanged; the exception's `kind` is the ErrorKind.
void registerErrors(py::module_& m) {
    py::enum_<sss::ErrorKind>(m, "ErrorKind", "What kind of failure an sss.Error reports.")
        .value("INVALID_ARGUMENT", sss::ErrorKind::InvalidArgument)
        .value("IO", sss::ErrorKind::Io)
        .value("PARSE", sss::ErrorKind::Parse)
        .value("GL", sss::ErrorKind::Gl)
        .value("GPU_LIMIT", sss::ErrorKind::GpuLimit)
        .value("UNSUPPORTED", sss::ErrorKind::Unsupported);

    auto make = [&m](const char* name, py::handle bases, const char* doc) {
        const std::string qualified = std::string("sss.") + name;
        py::object type = py::reinterpret_steal<py::object>(
            PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases.ptr(), nullptr));
        if (!type) throw py::error_already_set();
        m.attr(name) = type;
        return type;
    };
    py::object error = make("Error", PyExc_RuntimeError,
                            "Base of every libsss error; `kind` is the sss.ErrorKind, the message the library's.");
    py::object invalid = make("InvalidArgumentError", py::make_tuple(error, py::handle(PyExc_ValueError)),
                              "A value breaks a documented precondition (ErrorKind.INVALID_ARGUMENT).");
    py::object io = make("IoError", py::make_tuple(error, py::handle(PyExc_OSError)),
                         "A file is missing or unreadable (ErrorKind.IO).");
    py::object parse = make("ParseError", py::make_tuple(error, py::handle(PyExc_ValueError)),
                            "A file is malformed (ErrorKind.PARSE).");
    py::object gl = make("GlError", py::make_tuple(error, py::handle(PyExc_RuntimeError)),
                         "The environment cannot do what is asked: no OpenGL 4.5 context, ... (ErrorKind.GL).");
    py::object gpuLimit = make("GpuLimitError", py::make_tuple(error, py::handle(PyExc_MemoryError)),
                               "The scene does not fit the GPU (ErrorKind.GPU_LIMIT).");

    py::object unsupported = make("UnsupportedError", py::make_tuple(error, py::handle(PyExc_NotImplementedError)),
                                  "This build of libsss leaves the format or feature out (ErrorKind.UNSUPPORTED).");

    // Kept alive by the module; the translator runs with the GIL held.
    static py::handle types[6];
    types[static_cast<int>(sss::ErrorKind::InvalidArgument)] = invalid.release();
    types[static_cast<int>(sss::ErrorKind::Io)] = io.release();
    types[static_cast<int>(sss::ErrorKind::Parse)] = parse.release();
    types[static_cast<int>(sss::ErrorKind::Gl)] = gl.release();
    types[static_cast<int>(sss::ErrorKind::GpuLimit)] = gpuLimit.release();
    types[static_cast<int>(sss::ErrorKind::Unsupported)] = unsupported.release();
    error.release();

    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const sss::Error& e) {
            py::handle type = types[static_cast<int>(e.kind())];
            // OSError with one argument keeps it as the message (errno stays None).
            py::object instance = type(py::str(e.what()));
            instance.attr("kind") = e.kind();
            PyErr_SetObject(type.ptr(), instance.ptr());
        }
    });
}

void bindLog(py::module_& m) {
    py::enum_<sss::LogLevel>(m, "LogLevel")
        .value("DEBUG", sss::LogLevel::Debug)
        .value("INFO", sss::LogLevel::Info)
        .value("WARNING", sss::LogLevel::Warning)
        .value("ERROR", sss::LogLevel::Error);
    m.def("set_log_handler",
          [](const py::object& handler) {
              if (handler.is_none()) return sss::setLogHandler({});
              // The library logs from the calling thread, which holds the GIL in this module.
              auto shared = std::make_shared<py::object>(handler);
              sss::setLogHandler([shared](sss::LogLevel level, std::string_view message) {
                  py::gil_scoped_acquire gil;
                  try {
                      (*shared)(level, py::str(message.data(), message.size()));
                  } catch (py::error_already_set& e) {
                      e.discard_as_unraisable("sss log handler");
                  }
              });
          },
          py::arg("handler"),
          "Routes the library's log (warnings, GL debug output) to handler(level: LogLevel, message: str); "
          "None restores the default (warnings and errors on stderr).");
}

}  // namespace
}  // namespace ssspy

PYBIND11_MODULE(sss, m) {
    m.doc() = "libsss: light scattering in meshes and volumes, rendered headless with OpenGL 4.5 (EGL).";
    ssspy::registerErrors(m);
    ssspy::bindLog(m);
    ssspy::bindData(m);
    ssspy::bindRender(m);
    // The default context goes before the interpreter finalizes (renderers still alive keep their
    // own reference), and a Python log handler is dropped before Python objects become invalid.
    py::module_::import("atexit").attr("register")(py::cpp_function([] {
        sss::setLogHandler({});
        ssspy::releaseDefaultContext();
    }));
    m.attr("__version__") = SSS_VERSION;
}
