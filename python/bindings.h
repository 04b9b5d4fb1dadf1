#pragma once
// Shared pieces of the Python module (python/*.cpp): conversions between glm and Python
// sequences, option structs with keyword constructors, enums that also accept their names,
// and the GL context every GL object of the module is made with.
#include <sss/context.h>
#include <sss/error.h>
#include <sss/option_names.h>
#include <sss/option_table.h>
#include <sss/image.h>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <cctype>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace py = pybind11;

// ---- glm vectors <-> any sequence of N numbers (tuple, list, 1-D NumPy array) ----------------
namespace pybind11::detail {

template <glm::length_t N, typename T, glm::qualifier Q>
struct type_caster<glm::vec<N, T, Q>> {
    using Vec = glm::vec<N, T, Q>;
    PYBIND11_TYPE_CASTER(Vec, const_name("tuple[") + make_caster<T>::name + const_name(", ...]"));

    bool load(handle src, bool convert) {
        if (!src || PyUnicode_Check(src.ptr()) || PyBytes_Check(src.ptr()) || !PySequence_Check(src.ptr()))
            return false;
        sequence seq = reinterpret_borrow<sequence>(src);
        if (seq.size() != static_cast<std::size_t>(N)) return false;
        for (glm::length_t i = 0; i < N; ++i) {
            make_caster<T> element;
            if (!element.load(seq[static_cast<std::size_t>(i)], convert)) return false;
            value[i] = cast_op<T>(element);
        }
        return true;
    }

    static handle cast(const Vec& v, return_value_policy, handle) {
        tuple result(N);
        for (glm::length_t i = 0; i < N; ++i)
            PyTuple_SET_ITEM(result.ptr(), i, pybind11::cast(v[i]).release().ptr());
        return result.release();
    }
};

// glm::mat4 <-> 4x4 NumPy array (row-major in NumPy, m[row][col]; glm stores columns).
template <>
struct type_caster<glm::mat4> {
    PYBIND11_TYPE_CASTER(glm::mat4, const_name("numpy.ndarray[float32[4, 4]]"));

    bool load(handle src, bool) {
        if (!src || src.is_none()) return false;
        auto a = array_t<float, array::c_style | array::forcecast>::ensure(src);
        if (!a || a.ndim() != 2 || a.shape(0) != 4 || a.shape(1) != 4) return false;
        for (int row = 0; row < 4; ++row)
            for (int col = 0; col < 4; ++col) value[col][row] = a.at(row, col);
        return true;
    }

    static handle cast(const glm::mat4& m, return_value_policy, handle) {
        array_t<float> a({4, 4});
        auto w = a.mutable_unchecked<2>();
        for (int row = 0; row < 4; ++row)
            for (int col = 0; col < 4; ++col) w(row, col) = m[col][row];
        return a.release();
    }
};

}  // namespace pybind11::detail

namespace ssspy {

/// Throws the module's InvalidArgumentError (an sss.Error and a ValueError) with `message`.
[[noreturn]] inline void invalidArgument(const std::string& message) {
    throw sss::Error(sss::ErrorKind::InvalidArgument, message);
}

/// "MeshRenderOptions(cameras=8, ...)": a struct bound with keyword construction. Every field is
/// a read-write attribute; the constructor takes any of them as keyword arguments (an unknown
/// name is a TypeError listing the known ones) and then runs the struct's validator, so an
/// invalid value fails where it is written. replace(**kw) returns a changed copy.
template <typename T>
class Struct {
public:
    using Validator = std::function<void(const T&)>;

    Struct(py::module_& m, const char* name, const char* doc)
        : m_cls(m, name, doc), m_name(name), m_names(std::make_shared<std::vector<std::string>>()) {}

    template <typename M>
    Struct& field(const char* name, M T::*member, const char* doc) {
        m_cls.def_readwrite(name, member, doc);
        m_names->push_back(name);
        return *this;
    }

    /// Every field of T's option table (sss/option_table.h): its snake_case name, its help, its
    /// range and the default of a default-constructed T.
    Struct& tableFields() {
        sss::forEachOptionField<T>([this](const auto& f) {
            using M = std::remove_cvref_t<decltype(T{}.*f.member)>;
            std::string doc(f.help);
            constexpr bool integer = std::is_same_v<M, int>;
            if constexpr (integer || std::is_floating_point_v<M>) doc += ", " + sss::describeRange(f.range, integer);
            if constexpr (!std::is_enum_v<M>) doc += " (default " + std::string(py::repr(py::cast(T{}.*f.member))) + ")";
            else doc += " (default " + std::string(sss::enumName(T{}.*f.member)) + ")";
            field(sss::snakeCase(f.name).c_str(), f.member, doc.c_str());
        });
        return *this;
    }

    /// Finishes the class: __init__(**kw), __repr__, __eq__, replace, validate.
    py::class_<T>& done(Validator validator = {}) {
        auto names = m_names;
        std::string typeName = m_name;
        auto apply = [names, typeName, validator](T base, const py::kwargs& kw) {
            py::object obj = py::cast(std::move(base));
            for (auto item : kw) {
                const std::string key = py::str(item.first);
                if (std::find(names->begin(), names->end(), key) == names->end()) {
                    std::string known;
                    for (const std::string& n : *names) known += (known.empty() ? "" : ", ") + n;
                    throw py::type_error(typeName + ": unknown option '" + key + "' (options: " + known + ")");
                }
                py::object value = py::reinterpret_borrow<py::object>(item.second);
                py::object current = obj.attr(key.c_str());
                py::object fieldType = py::type::of(current);
                // An enum field given by name: convert here so an unknown name is an
                // InvalidArgumentError listing the valid ones, not a bare TypeError.
                if (py::isinstance<py::str>(value) && py::hasattr(fieldType, "__members__")) value = fieldType(value);
                try {
                    obj.attr(key.c_str()) = value;
                } catch (py::error_already_set& e) {
                    if (!e.matches(PyExc_TypeError)) throw;
                    throw py::type_error(typeName + "." + key + ": expected " +
                                         std::string(py::str(fieldType.attr("__name__"))) + ", got " +
                                         std::string(py::repr(value)));
                }
            }
            T value = obj.cast<T>();
            if (validator) validator(value);
            return value;
        };
        m_cls.def(py::init([apply](const py::kwargs& kw) { return apply(T{}, kw); }),
                  ("Every field is a keyword argument; unset fields keep their defaults. Raises TypeError "
                   "for an unknown name and sss.InvalidArgumentError for a value outside its range."));
        m_cls.def(
            "replace", [apply](const T& self, const py::kwargs& kw) { return apply(self, kw); },
            "A copy with the given fields changed (validated as the constructor does).");
        m_cls.def("__repr__", [names, typeName](const py::object& self) {
            std::string text = typeName + "(";
            for (std::size_t i = 0; i < names->size(); ++i) {
                if (i) text += ", ";
                text += (*names)[i] + "=" + std::string(py::repr(self.attr((*names)[i].c_str())));
            }
            return text + ")";
        });
        m_cls.def("__copy__", [](const T& self) { return T(self); });
        m_cls.def("__deepcopy__", [](const T& self, const py::dict&) { return T(self); });
        m_cls.def_property_readonly_static("fields", [names](const py::object&) {
            py::tuple t(names->size());
            for (std::size_t i = 0; i < names->size(); ++i) t[i] = py::str((*names)[i]);
            return t;
        }, "The names of the fields, in declaration order.");
        // Field by field, so structs without operator== compare by value too.
        m_cls.def(
            "__eq__",
            [names](const py::object& a, const py::object& b) {
                for (const std::string& n : *names)
                    if (!a.attr(n.c_str()).equal(b.attr(n.c_str()))) return false;
                return true;
            },
            py::is_operator());
        if (validator)
            m_cls.def("validate", [validator](const T& self) { validator(self); },
                      "Raises sss.InvalidArgumentError naming the first field outside its range.");
        return m_cls;
    }

private:
    py::class_<T> m_cls;
    std::string m_name;
    std::shared_ptr<std::vector<std::string>> m_names;
};

/// Binds an enum with Python-style UPPER_CASE members that also converts from its member name
/// as a string, case-insensitively, with '-' or ' ' for '_' ("scattering", "blinn-phong").
template <typename E>
py::enum_<E> bindEnum(py::module_& m, const char* name, std::initializer_list<std::pair<const char*, E>> values,
                      const char* doc) {
    py::enum_<E> e(m, name, doc);
    auto table = std::make_shared<std::vector<std::pair<std::string, E>>>();
    for (const auto& [n, v] : values) {
        e.value(n, v);
        table->emplace_back(n, v);
    }
    std::string typeName = name;
    e.def(py::init([table, typeName](const std::string& text) {
              std::string key;
              for (char c : text) key += (c == '-' || c == ' ') ? '_' : static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
              std::string known;
              for (const auto& [n, v] : *table) {
                  if (n == key) return v;
                  std::string lower;
                  for (char c : n) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
                  known += (known.empty() ? "" : ", ") + lower;
              }
              invalidArgument(typeName + ": unknown value \"" + text + "\" (" + known + ")");
          }),
          py::arg("name"));
    py::implicitly_convertible<py::str, E>();
    return e;
}

/// The EGL context a GL object of the module was made with. GL objects hold it by shared_ptr,
/// so it outlives them whatever order Python destroys things in, and make it current before
/// touching GL (several contexts may exist).
struct ContextHolder {
    std::unique_ptr<sss::EglContext> context;
    void makeCurrent() { context->makeCurrent(); }
};
using ContextPtr = std::shared_ptr<ContextHolder>;

/// The module's default context, created on first use (released at interpreter exit).
ContextPtr defaultContext();
/// Drops the module's reference to the default context (at interpreter exit).
void releaseDefaultContext();
/// `context` (an sss.Context or None) as a holder; None gives the default context.
ContextPtr contextFrom(const py::object& context);

/// A float32 NumPy array of shape (height, width, 4), top row first, from an image.
py::array_t<float> toNumpy(const sss::Image& image);
/// An sss::Image from an (H, W, 4) or (H, W, 3) array of numbers (alpha 1 for 3 channels).
sss::Image imageFromNumpy(const py::handle& array, const char* what);

void bindData(py::module_& m);     // bind_data.cpp: meshes, volumes, transfer functions, ...
void bindRender(py::module_& m);   // bind_render.cpp: context, options, renderers, scene

}  // namespace ssspy
