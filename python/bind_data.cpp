// CPU-side data of the Python module: bounds, meshes, volumes, transfer functions, materials,
// lights, the camera, images and the display transform. Nothing here needs a GL context.
#include "bindings.h"

#include <sss/bounds.h>
#include <sss/bssrdf.h>
#include <sss/camera.h>
#include <sss/display.h>
#include <sss/light.h>
#include <sss/materials.h>
#include <sss/isosurface.h>
#include <sss/mesh.h>
#include <sss/mesh_scattering_renderer.h>
#include <sss/procedural.h>
#include <sss/transfer_function.h>
#include <sss/volume.h>

#include <cstring>
#include <limits>
#include <optional>

namespace ssspy {

namespace {

std::string dtypeName(const py::array& a) { return py::str(a.dtype()); }

// An (N, 3) array of real numbers as glm::vec3s. `what` names the argument in messages.
// Rows of N floats (positions, normals: 3; texture coordinates: 2) from an array of that many columns.
template <int N>
std::vector<glm::vec<N, float>> floatRows(const py::handle& src, const char* what) {
    const std::string shape = "(N, " + std::to_string(N) + ")";
    py::array raw = py::array::ensure(src);
    if (!raw) invalidArgument(std::string("Mesh: ") + what + " must be an array of shape " + shape);
    const char kind = raw.dtype().kind();
    if (kind != 'f' && kind != 'i' && kind != 'u')
        invalidArgument(std::string("Mesh: ") + what + " must hold real numbers, got dtype " + dtypeName(raw));
    if (raw.ndim() != 2 || raw.shape(1) != N)
        invalidArgument(std::string("Mesh: ") + what + " must have shape " + shape + ", got " +
                        std::string(py::str(py::tuple(raw.attr("shape")))));
    auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(raw);
    std::vector<glm::vec<N, float>> out(static_cast<std::size_t>(a.shape(0)));
    if (!out.empty()) std::memcpy(out.data(), a.data(), out.size() * sizeof(glm::vec<N, float>));
    return out;
}

std::vector<glm::vec3> vec3Rows(const py::handle& src, const char* what) { return floatRows<3>(src, what); }

std::vector<std::uint32_t> indexRows(const py::handle& src) {
    py::array raw = py::array::ensure(src);
    if (!raw) invalidArgument("Mesh: indices must be an integer array of shape (M, 3)");
    const char kind = raw.dtype().kind();
    if (kind != 'i' && kind != 'u')
        invalidArgument("Mesh: indices must be an integer array, got dtype " + dtypeName(raw));
    if (!((raw.ndim() == 2 && raw.shape(1) == 3) || (raw.ndim() == 1 && raw.shape(0) % 3 == 0)))
        invalidArgument("Mesh: indices must have shape (M, 3), got " + std::string(py::str(py::tuple(raw.attr("shape")))));
    auto a = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(raw);
    std::vector<std::uint32_t> out(static_cast<std::size_t>(a.size()));
    const std::int64_t* p = a.data();
    for (std::size_t i = 0; i < out.size(); ++i) {
        if (p[i] < 0 || p[i] > std::numeric_limits<std::uint32_t>::max())
            invalidArgument("Mesh: index " + std::to_string(p[i]) + " at position " + std::to_string(i) +
                            " is outside [0, 2^32)");
        out[i] = static_cast<std::uint32_t>(p[i]);
    }
    return out;
}

template <int N>
py::array_t<float> floatArray(const std::vector<glm::vec<N, float>>& v) {
    py::array_t<float> a({static_cast<py::ssize_t>(v.size()), py::ssize_t{N}});
    if (!v.empty()) std::memcpy(a.mutable_data(), v.data(), v.size() * sizeof(glm::vec<N, float>));
    return a;
}

py::array_t<float> vec3Array(const std::vector<glm::vec3>& v) { return floatArray<3>(v); }

// NumPy dtype <-> VoxelType. Only the native (little-endian) layouts map directly.
std::optional<sss::VoxelType> voxelType(const py::dtype& d) {
    if (d.is(py::dtype::of<std::uint8_t>())) return sss::VoxelType::UInt8;
    if (d.is(py::dtype::of<std::uint16_t>())) return sss::VoxelType::UInt16;
    if (d.is(py::dtype::of<std::int16_t>())) return sss::VoxelType::Int16;
    if (d.is(py::dtype::of<float>())) return sss::VoxelType::Float32;
    return std::nullopt;
}

py::dtype dtypeOf(sss::VoxelType t) {
    switch (t) {
        case sss::VoxelType::UInt8: return py::dtype::of<std::uint8_t>();
        case sss::VoxelType::UInt16: return py::dtype::of<std::uint16_t>();
        case sss::VoxelType::Int16: return py::dtype::of<std::int16_t>();
        case sss::VoxelType::Float32: return py::dtype::of<float>();
    }
    return py::dtype::of<std::uint8_t>();
}

sss::Volume volumeFromNumpy(const py::handle& src, glm::vec3 spacing) {
    py::array raw = py::array::ensure(src);
    if (!raw) invalidArgument("Volume: data must be a 3-D NumPy array indexed [z, y, x]");
    const std::optional<sss::VoxelType> type = voxelType(raw.dtype());
    if (!type)
        invalidArgument("Volume: dtype " + dtypeName(raw) + " is not supported (uint8, uint16, int16, float32)");
    if (raw.ndim() != 3)
        invalidArgument("Volume: data must be 3-D, indexed [z, y, x], got shape " +
                        std::string(py::str(py::tuple(raw.attr("shape")))));
    // C order with x fastest is the Volume layout; a strided view is copied into it.
    py::array a = py::array::ensure(raw, py::array::c_style);
    const glm::ivec3 dims(static_cast<int>(a.shape(2)), static_cast<int>(a.shape(1)), static_cast<int>(a.shape(0)));
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(a.nbytes()));
    if (!bytes.empty()) std::memcpy(bytes.data(), a.data(), bytes.size());
    return sss::Volume::fromData(dims, *type, std::move(bytes), spacing);
}

py::array volumeToNumpy(const sss::Volume& v) {
    const glm::ivec3 d = v.dims();
    py::array a(dtypeOf(v.type()), {static_cast<py::ssize_t>(d.z), static_cast<py::ssize_t>(d.y), static_cast<py::ssize_t>(d.x)});
    std::memcpy(a.mutable_data(), v.bytes().data(), v.bytes().size());
    return a;
}

py::array_t<std::uint8_t> toNumpy8(const sss::Image8& image) {
    py::array_t<std::uint8_t> a({static_cast<py::ssize_t>(image.height()), static_cast<py::ssize_t>(image.width()), py::ssize_t{4}});
    std::memcpy(a.mutable_data(), image.data().data(), image.data().size());
    return a;
}

sss::Image8 image8FromNumpy(const py::array& raw) {
    if (raw.ndim() != 3 || (raw.shape(2) != 3 && raw.shape(2) != 4))
        invalidArgument("save_png: image must have shape (H, W, 4) or (H, W, 3), got " +
                        std::string(py::str(py::tuple(raw.attr("shape")))));
    auto a = py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>::ensure(raw);
    const int h = static_cast<int>(a.shape(0)), w = static_cast<int>(a.shape(1)), c = static_cast<int>(a.shape(2));
    sss::Image8 image(w, h, glm::u8vec4(255));
    auto r = a.unchecked<3>();
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int k = 0; k < c; ++k) image.at(x, y)[k] = r(y, x, k);
    return image;
}

sss::DisplayTransform displayTransform(float exposure, sss::ToneMap toneMap, bool srgb) {
    sss::DisplayTransform t{.exposure = exposure, .toneMap = toneMap, .srgb = srgb};
    sss::validate(t);
    return t;
}

void bindGeometry(py::module_& m) {
    py::class_<sss::Bounds>(m, "Bounds", "An axis-aligned box (min and max corners).")
        .def(py::init([](glm::vec3 lo, glm::vec3 hi) { return sss::Bounds{lo, hi}; }), py::arg("min"), py::arg("max"))
        .def_readwrite("min", &sss::Bounds::min, "smallest corner")
        .def_readwrite("max", &sss::Bounds::max, "largest corner")
        .def_property_readonly("center", &sss::Bounds::center)
        .def_property_readonly("size", &sss::Bounds::size)
        .def_property_readonly("radius", &sss::Bounds::radius)
        .def_property_readonly("empty", &sss::Bounds::empty)
        .def("__repr__", [](const sss::Bounds& b) {
            return "Bounds(min=" + std::string(py::repr(py::cast(b.min))) + ", max=" + std::string(py::repr(py::cast(b.max))) + ")";
        });

    py::class_<sss::Mesh>(m, "Mesh", "An indexed triangle mesh with one unit normal per vertex.")
        .def(py::init([](const py::handle& vertices, const py::handle& indices, const py::handle& normals,
                         const std::string& name, const py::handle& texcoords) {
                 std::vector<glm::vec3> n;
                 if (!normals.is_none()) n = vec3Rows(normals, "normals");
                 std::vector<glm::vec2> t;
                 if (!texcoords.is_none()) t = floatRows<2>(texcoords, "texcoords");
                 return sss::Mesh::fromArrays(vec3Rows(vertices, "vertices"), indexRows(indices), std::move(n), name,
                                              std::move(t));
             }),
             py::arg("vertices"), py::arg("indices"), py::arg("normals") = py::none(), py::arg("name") = "mesh",
             py::arg("texcoords") = py::none(),
             "From arrays: vertices (N, 3) real numbers, indices (M, 3) integers (counter-clockwise "
             "triangles), normals (N, 3) or None for smooth area-weighted ones, texcoords (N, 2) or None "
             "((0, 0) is a texture's bottom-left corner).")
        .def_property_readonly("texcoords",
                               [](const sss::Mesh& mesh) -> py::object {
                                   if (mesh.texcoords().empty()) return py::none();
                                   return floatArray<2>(mesh.texcoords());
                               },
                               "(N, 2) float32 copy of the texture coordinates, or None")
        .def_property_readonly("base_colour",
                               [](const sss::Mesh& mesh) -> py::object {
                                   if (!mesh.baseColour()) return py::none();
                                   return toNumpy8(*mesh.baseColour());
                               },
                               "(H, W, 4) uint8 copy of the base-colour texture (sRGB, row 0 at the top), or None")
        .def("with_base_colour",
             [](const sss::Mesh& mesh, const py::handle& image) {
                 if (image.is_none()) return mesh.withBaseColour(nullptr);
                 return mesh.withBaseColour(std::make_shared<const sss::Image8>(image8FromNumpy(py::array::ensure(image))));
             },
             py::arg("image"),
             "A copy with this base-colour texture: (H, W, 3 or 4) uint8, sRGB, row 0 at the top; None removes it. "
             "Textured translucent materials take it as the reflectance (TexturedScattering).")
        .def_static("load", &sss::Mesh::load, py::arg("path"),
                    "Loads OBJ, PLY, STL, glTF 2.0 (.gltf/.glb) or OFF (see sss::Mesh::load).")
        .def_property_readonly("vertices", [](const sss::Mesh& mesh) { return vec3Array(mesh.positions()); },
                               "(N, 3) float32 copy of the vertex positions")
        .def_property_readonly("normals", [](const sss::Mesh& mesh) { return vec3Array(mesh.normals()); },
                               "(N, 3) float32 copy of the unit normals")
        .def_property_readonly("indices", [](const sss::Mesh& mesh) {
            py::array_t<std::uint32_t> a({static_cast<py::ssize_t>(mesh.triangleCount()), py::ssize_t{3}});
            std::memcpy(a.mutable_data(), mesh.indices().data(), mesh.indices().size() * sizeof(std::uint32_t));
            return a;
        }, "(M, 3) uint32 copy of the triangle indices")
        .def_property_readonly("vertex_count", &sss::Mesh::vertexCount)
        .def_property_readonly("triangle_count", &sss::Mesh::triangleCount)
        .def_property_readonly("bounds", &sss::Mesh::bounds)
        .def_property_readonly("name", &sss::Mesh::name)
        .def("transformed", &sss::Mesh::transformed, py::arg("matrix"),
             "A copy transformed by a 4x4 matrix (normals by its inverse transpose).")
        .def("__repr__", [](const sss::Mesh& mesh) {
            return "<sss.Mesh '" + mesh.name() + "': " + std::to_string(mesh.vertexCount()) + " vertices, " +
                   std::to_string(mesh.triangleCount()) + " triangles>";
        });

    m.def("make_uv_sphere", &sss::makeUvSphere, py::arg("segments") = 20, py::arg("rings") = 20,
          py::arg("radius") = 1.0f, "UV sphere at the origin with analytic normals.");
    m.def("make_torus", &sss::makeTorus, py::arg("major_radius") = 0.7f, py::arg("minor_radius") = 0.3f,
          py::arg("major_segments") = 48, py::arg("minor_segments") = 24, "Torus around the y axis.");
    m.def("make_slab", &sss::makeSlab, py::arg("size") = glm::vec3(1.6f, 1.0f, 0.2f), "Box centred at the origin.");
}

void bindVolume(py::module_& m) {
    bindEnum<sss::VoxelType>(m, "VoxelType",
                             {{"UINT8", sss::VoxelType::UInt8}, {"UINT16", sss::VoxelType::UInt16},
                              {"INT16", sss::VoxelType::Int16}, {"FLOAT32", sss::VoxelType::Float32}},
                             "Storage type of one voxel.");

    py::class_<sss::Volume>(m, "Volume",
                            "A dense 3-D grid of scalars. As a NumPy array it is indexed [z, y, x] (x varies fastest).")
        .def(py::init(&volumeFromNumpy), py::arg("data"), py::arg("spacing") = glm::vec3(1.0f),
             "From a 3-D array indexed [z, y, x] of dtype uint8, uint16, int16 or float32; spacing is the "
             "voxel size along (x, y, z).")
        .def_static(
            "load",
            [](const std::filesystem::path& path, std::optional<glm::ivec3> dims, std::optional<sss::VoxelType> type,
               std::optional<glm::vec3> spacing, bool allowOblique) {
                sss::VolumeLoadOptions options;
                options.raw = {.dims = dims, .type = type, .spacing = spacing};
                options.allowOblique = allowOblique;
                return sss::Volume::load(path, options);
            },
            py::arg("path"), py::kw_only(), py::arg("dims") = py::none(), py::arg("type") = py::none(),
            py::arg("spacing") = py::none(), py::arg("allow_oblique") = false,
            "Loads NRRD, MetaImage, NIfTI, .vti, a DICOM directory or .raw (dims, type and spacing are for "
            ".raw files, whose name may also give dims and type).")
        .def_property_readonly("dims", &sss::Volume::dims, "voxels along (x, y, z)")
        .def_property_readonly("spacing", &sss::Volume::spacing, "voxel size along (x, y, z)")
        .def_property_readonly("type", &sss::Volume::type)
        .def_property_readonly("dtype", [](const sss::Volume& v) { return dtypeOf(v.type()); })
        .def_property_readonly("data", &volumeToNumpy, "a copy of the voxels, indexed [z, y, x]")
        .def("__array__",
             [](const sss::Volume& v, const py::object& dtype) -> py::object {
                 py::array a = volumeToNumpy(v);
                 return dtype.is_none() ? py::object(a) : a.attr("astype")(dtype);
             },
             py::arg("dtype") = py::none())
        .def_property_readonly("value_range", &sss::Volume::valueRange, "smallest and largest raw value")
        .def_property_readonly("transfer_function_range", &sss::Volume::transferFunctionRange,
                               "the raw values the transfer function's [0, 1] spans")
        .def_property("value_window", &sss::Volume::valueWindow, &sss::Volume::setValueWindow,
                      "(lo, hi) in raw units that the transfer function spans, or None for the default")
        .def_property_readonly("world_bounds", &sss::Volume::worldBounds)
        .def("value_at", &sss::Volume::valueAt, py::arg("x"), py::arg("y"), py::arg("z"))
        .def("normalized_at", &sss::Volume::normalizedAt, py::arg("x"), py::arg("y"), py::arg("z"))
        .def("histogram",
             [](const sss::Volume& v, int bins, std::optional<std::pair<double, double>> range) {
                 std::vector<std::uint32_t> h = range ? v.histogram(bins, *range) : v.histogram(bins);
                 return py::array_t<std::uint32_t>(static_cast<py::ssize_t>(h.size()), h.data());
             },
             py::arg("bins") = 256, py::arg("range") = py::none())
        .def("__repr__", [](const sss::Volume& v) {
            const glm::ivec3 d = v.dims();
            return "<sss.Volume " + std::to_string(d.x) + "x" + std::to_string(d.y) + "x" + std::to_string(d.z) + " " +
                   sss::voxelTypeName(v.type()) + ">";
        });

    m.def("make_blobs_volume", &sss::makeBlobsVolume, py::arg("n") = 64, "n^3 uint8 volume with four soft blobs.");
    m.def("make_shell_volume", &sss::makeShellVolume, py::arg("n") = 64, py::arg("outer_radius") = 0.42f,
          py::arg("thickness") = 0.08f, "n^3 uint8 hollow spherical shell.");
    m.def("make_bucky_volume", &sss::makeBuckyLikeVolume, py::arg("n") = 32, "n^3 uint8 look-alike of C60 'bucky'.");
    m.def(
        "extract_isosurface",
        [](const sss::Volume& volume, double value, int smoothingIterations, int maxTriangles) {
            return sss::extractIsosurface(volume, {value, smoothingIterations, maxTriangles});
        },
        py::arg("volume"), py::arg("value"), py::arg("smoothing_iterations") = 15, py::arg("max_triangles") = 0,
        "The surface where the volume's data cross `value` (its units: Hounsfield for CT) as a Mesh in the "
        "volume's physical units (its spacing), centred, normals towards lower values (sss::extractIsosurface).");
}

void bindTransferFunction(py::module_& m) {
    Struct<sss::ControlPoint>(m, "ControlPoint", "One control point of a TransferFunction (all in [0, 1]).")
        .field("value", &sss::ControlPoint::value, "scalar position in [0, 1]")
        .field("color", &sss::ControlPoint::color, "linear RGB in [0, 1]")
        .field("opacity", &sss::ControlPoint::opacity, "in [0, 1]")
        .done()
        .def(py::init([](float value, glm::vec3 color, float opacity) { return sss::ControlPoint{value, color, opacity}; }),
             py::arg("value"), py::arg("color"), py::arg("opacity"))
        .def(py::init([](const py::tuple& t) {
                 if (t.size() != 3) invalidArgument("ControlPoint: a tuple must be (value, (r, g, b), opacity)");
                 return sss::ControlPoint{t[0].cast<float>(), t[1].cast<glm::vec3>(), t[2].cast<float>()};
             }),
             py::arg("point"), "From a (value, (r, g, b), opacity) tuple.");
    py::implicitly_convertible<py::tuple, sss::ControlPoint>();

    py::class_<sss::TransferFunction>(m, "TransferFunction",
                                      "Piecewise-linear colour and opacity over [0, 1] (control points sorted by value).")
        .def(py::init<>(), "The ramp: 0 is black and transparent, 1 white and opaque.")
        .def(py::init<std::vector<sss::ControlPoint>>(), py::arg("points"),
             "From ControlPoints or (value, (r, g, b), opacity) tuples, values strictly increasing.")
        .def_static("preset", &sss::TransferFunction::preset, py::arg("name"))
        .def_static("preset_names", &sss::TransferFunction::presetNames)
        .def_static("load_paraview_json", &sss::TransferFunction::loadParaViewJson, py::arg("path"),
                    py::arg("data_range") = py::none())
        .def("save_paraview_json", &sss::TransferFunction::saveParaViewJson, py::arg("path"), py::arg("name") = "libsss")
        .def_property_readonly("points", &sss::TransferFunction::points)
        .def("add_point",
             [](sss::TransferFunction& tf, float value, glm::vec3 color, float opacity) {
                 return tf.addPoint({value, color, opacity});
             },
             py::arg("value"), py::arg("color"), py::arg("opacity"))
        .def("move_point", &sss::TransferFunction::movePoint, py::arg("index"), py::arg("value"))
        .def("set_point", &sss::TransferFunction::setPoint, py::arg("index"), py::arg("color"), py::arg("opacity"))
        .def("remove_point", &sss::TransferFunction::removePoint, py::arg("index"))
        .def("evaluate", &sss::TransferFunction::evaluate, py::arg("value"), "(r, g, b, opacity) at value")
        .def("table",
             [](const sss::TransferFunction& tf, int entries) {
                 std::vector<glm::vec4> t = tf.table(entries);
                 py::array_t<float> a({static_cast<py::ssize_t>(t.size()), py::ssize_t{4}});
                 std::memcpy(a.mutable_data(), t.data(), t.size() * sizeof(glm::vec4));
                 return a;
             },
             py::arg("entries") = 256, "(entries, 4) float32 samples from 0 to 1")
        .def("__repr__", [](const sss::TransferFunction& tf) {
            return "<sss.TransferFunction with " + std::to_string(tf.points().size()) + " points>";
        });
}

void bindMaterials(py::module_& m) {
    Struct<sss::ScatteringMaterial>(m, "ScatteringMaterial",
                                    "A translucent material: coefficients in mm^-1 (see MeshRenderOptions.millimetres_per_unit).")
        .field("sigma_a", &sss::ScatteringMaterial::sigmaA, "absorption coefficient, mm^-1, each >= 0")
        .field("sigma_s", &sss::ScatteringMaterial::sigmaS, "scattering coefficient, mm^-1, each >= 0")
        .field("g", &sss::ScatteringMaterial::g, "Henyey-Greenstein mean cosine, in (-1, 1)")
        .field("eta", &sss::ScatteringMaterial::eta, "relative index of refraction, in [0.4, 2.5]")
        .field("name", &sss::ScatteringMaterial::name, "label")
        .done([](const sss::ScatteringMaterial& s) { s.validate(); });
    m.def("material_preset", &sss::materialPreset, py::arg("name"),
          "A measured material by name ('marble', 'skin1', 'wholemilk', ...; see material_preset_names()).");
    m.def("material_preset_names", &sss::materialPresetNames);

    py::class_<sss::TexturedScattering>(m, "TexturedScattering",
                                        "A translucent material whose reflectance comes from a texture (the mesh's "
                                        "base colour unless `reflectance` is set) and whose blur from a mean free "
                                        "path per channel (docs/textured-materials.md).")
        .def(py::init<>())
        .def_readwrite("mean_free_path", &sss::TexturedScattering::meanFreePath,
                       "reduced mean free path 1 / sigma_t' per channel, mm, each > 0")
        .def_readwrite("eta", &sss::TexturedScattering::eta, "relative index of refraction, in [0.4, 2.5]")
        .def_readwrite("name", &sss::TexturedScattering::name, "label")
        .def_property(
            "reflectance",
            [](const sss::TexturedScattering& t) -> py::object {
                return t.reflectance ? py::object(toNumpy8(*t.reflectance)) : py::none();
            },
            [](sss::TexturedScattering& t, const py::handle& image) {
                t.reflectance = image.is_none()
                                    ? nullptr
                                    : std::make_shared<const sss::Image8>(image8FromNumpy(py::array::ensure(image)));
            },
            "(H, W, 3 or 4) uint8 sRGB base colour, or None for the mesh's")
        .def_property(
            "mean_free_path_scale",
            [](const sss::TexturedScattering& t) -> py::object {
                return t.meanFreePathScale ? py::object(toNumpy8(*t.meanFreePathScale)) : py::none();
            },
            [](sss::TexturedScattering& t, const py::handle& image) {
                t.meanFreePathScale = image.is_none() ? nullptr
                                                      : std::make_shared<const sss::Image8>(
                                                            image8FromNumpy(py::array::ensure(image)));
            },
            "(H, W, 3 or 4) uint8 whose red channel / 255 scales the mean free path per texel, or None")
        .def("validate", &sss::TexturedScattering::validate);
    m.def("textured_scattering", &sss::texturedScattering, py::arg("material"),
          "A material's mean free path and eta, its colour left to a texture.");

    Struct<sss::BlinnPhongMaterial>(m, "BlinnPhongMaterial", "Surface of the Blinn-Phong mesh shading (linear RGB).")
        .field("diffuse", &sss::BlinnPhongMaterial::diffuse, "Lambert albedo")
        .field("specular", &sss::BlinnPhongMaterial::specular, "specular colour")
        .field("shininess", &sss::BlinnPhongMaterial::shininess, "Blinn-Phong exponent, > 0")
        .field("ambient", &sss::BlinnPhongMaterial::ambient, "ambient light times albedo")
        .done([](const sss::BlinnPhongMaterial& b) { sss::validate(b); });
}

void bindLights(py::module_& m) {
    Struct<sss::DirectionalLight>(m, "DirectionalLight", "A light at infinity.")
        .field("direction", &sss::DirectionalLight::direction, "direction the light travels, non-zero")
        .field("color", &sss::DirectionalLight::color, "linear RGB, each >= 0")
        .field("intensity", &sss::DirectionalLight::intensity, "scales color, >= 0")
        .done([](const sss::DirectionalLight& l) { sss::validateLight(l, "light"); });
    Struct<sss::PointLight>(m, "PointLight", "An isotropic point light.")
        .field("position", &sss::PointLight::position, "world-space position")
        .field("color", &sss::PointLight::color, "linear RGB, each >= 0")
        .field("intensity", &sss::PointLight::intensity, "scales color, >= 0")
        .done([](const sss::PointLight& l) { sss::validateLight(l, "light"); });
    Struct<sss::SpotLight>(m, "SpotLight", "A point light emitting into a cone around direction.")
        .field("position", &sss::SpotLight::position, "world-space position")
        .field("direction", &sss::SpotLight::direction, "axis of the cone, non-zero")
        .field("cone_angle", &sss::SpotLight::coneAngle, "half-angle of the outer cone, degrees, in (0, 90]")
        .field("falloff", &sss::SpotLight::falloff, "share of cone_angle over which the edge fades, [0, 1]")
        .field("color", &sss::SpotLight::color, "linear RGB, each >= 0")
        .field("intensity", &sss::SpotLight::intensity, "scales color, >= 0")
        .done([](const sss::SpotLight& l) { sss::validateLight(l, "light"); })
        .def("cone_factor", &sss::spotConeFactor, py::arg("cos_angle"),
             "Fraction of the intensity sent at this cosine from the axis.");
}

void bindCamera(py::module_& m) {
    bindEnum<sss::Projection>(m, "Projection",
                              {{"PERSPECTIVE", sss::Projection::Perspective}, {"ORTHOGRAPHIC", sss::Projection::Orthographic}},
                              "Projection kind of a Camera.");
    py::class_<sss::Camera>(m, "Camera",
                            "Orbit camera: the eye is at target + distance * (sin(yaw) cos(pitch), sin(pitch), "
                            "cos(yaw) cos(pitch)); angles in degrees, up is +y.")
        .def(py::init([](glm::vec3 target, float distance, float yaw, float pitch, float fovY, float orthoHeight,
                         float nearPlane, float farPlane, sss::Projection projection) {
                 sss::Camera c;
                 c.setTarget(target);
                 c.setDistance(distance);
                 c.setYaw(yaw);
                 c.setPitch(pitch);
                 c.setFovY(fovY);
                 c.setOrthoHeight(orthoHeight);
                 c.setClipPlanes(nearPlane, farPlane);
                 c.setProjectionType(projection);
                 return c;
             }),
             py::kw_only(), py::arg("target") = glm::vec3(0.0f), py::arg("distance") = 3.0f, py::arg("yaw") = 0.0f,
             py::arg("pitch") = 0.0f, py::arg("fov_y") = 45.0f, py::arg("ortho_height") = 2.0f,
             py::arg("near") = 0.01f, py::arg("far") = 100.0f, py::arg("projection") = sss::Projection::Perspective)
        .def_property("target", &sss::Camera::target, &sss::Camera::setTarget)
        .def_property("distance", &sss::Camera::distance, &sss::Camera::setDistance)
        .def_property("yaw", &sss::Camera::yaw, &sss::Camera::setYaw)
        .def_property("pitch", &sss::Camera::pitch, &sss::Camera::setPitch)
        .def_property("fov_y", &sss::Camera::fovY, &sss::Camera::setFovY)
        .def_property("ortho_height", &sss::Camera::orthoHeight, &sss::Camera::setOrthoHeight)
        .def_property("near", &sss::Camera::nearPlane, [](sss::Camera& c, float n) { c.setClipPlanes(n, c.farPlane()); })
        .def_property("far", &sss::Camera::farPlane, [](sss::Camera& c, float f) { c.setClipPlanes(c.nearPlane(), f); })
        .def("set_clip_planes", &sss::Camera::setClipPlanes, py::arg("near"), py::arg("far"))
        .def_property("projection", &sss::Camera::projectionType, &sss::Camera::setProjectionType)
        .def_property("subpixel_offset", &sss::Camera::subpixelOffset, &sss::Camera::setSubpixelOffset)
        .def_property_readonly("position", &sss::Camera::position)
        .def_property_readonly("forward", &sss::Camera::forward)
        .def_property_readonly("right", &sss::Camera::right)
        .def_property_readonly("up", &sss::Camera::up)
        .def("view_matrix", &sss::Camera::view, "world-to-view 4x4 matrix")
        .def("projection_matrix", &sss::Camera::projection, py::arg("aspect"), "view-to-clip 4x4 matrix")
        .def("orbit", &sss::Camera::orbit, py::arg("d_yaw"), py::arg("d_pitch"))
        .def("zoom", &sss::Camera::zoom, py::arg("factor"))
        .def("pan", &sss::Camera::pan, py::arg("delta"))
        .def("frame", &sss::Camera::frame, py::arg("bounds"), "Fits the bounds' sphere into the vertical field of view.")
        .def("frame_tight",
             [](sss::Camera& c, const py::object& what, float aspect, float margin) {
                 if (py::isinstance<sss::Bounds>(what)) return c.frameTight(what.cast<sss::Bounds>(), aspect, margin);
                 if (py::isinstance<sss::Mesh>(what)) return c.frameTight(what.cast<const sss::Mesh&>().positions(), aspect, margin);
                 const std::vector<glm::vec3> points = vec3Rows(what, "points");
                 c.frameTight(points, aspect, margin);
             },
             py::arg("what"), py::arg("aspect"), py::arg("margin") = 0.05f,
             "Frames a Bounds, a Mesh's vertices or (N, 3) points tightly for the view direction and aspect.")
        .def("__copy__", [](const sss::Camera& c) { return sss::Camera(c); })
        .def("__deepcopy__", [](const sss::Camera& c, const py::dict&) { return sss::Camera(c); })
        .def("__repr__", [](const sss::Camera& c) {
            return "Camera(target=" + std::string(py::repr(py::cast(c.target()))) + ", distance=" + std::to_string(c.distance()) +
                   ", yaw=" + std::to_string(c.yaw()) + ", pitch=" + std::to_string(c.pitch()) + ")";
        });
}

void bindImages(py::module_& m) {
    bindEnum<sss::ToneMap>(m, "ToneMap", {{"NONE", sss::ToneMap::None}, {"FILMIC", sss::ToneMap::Filmic}},
                           "Tone mapping of the display transform.");
    Struct<sss::DisplayTransform>(m, "DisplayTransform",
                                  "display = encode(tone_map(linear * 2^exposure)); encode is sRGB if srgb.")
        .field("exposure", &sss::DisplayTransform::exposure, "stops, in [-64, 64]")
        .field("tone_map", &sss::DisplayTransform::toneMap, "ToneMap.NONE clips at 1; FILMIC rolls off")
        .field("srgb", &sss::DisplayTransform::srgb, "encode with the sRGB transfer function")
        .done([](const sss::DisplayTransform& t) { sss::validate(t); });

    m.def("to_display",
          [](const py::handle& image, float exposure, sss::ToneMap toneMap, bool srgb) {
              return toNumpy8(sss::toDisplay(imageFromNumpy(image, "to_display"), displayTransform(exposure, toneMap, srgb)));
          },
          py::arg("image"), py::kw_only(), py::arg("exposure") = 0.0f, py::arg("tone_map") = sss::ToneMap::None,
          py::arg("srgb") = true,
          "The 8-bit display image (H, W, 4) uint8 of a linear (H, W, 4) float image: the library's display "
          "transform (exposure, tone map, sRGB), as sss-render writes PNGs.");
    m.def("save_png",
          [](const std::filesystem::path& path, const py::handle& image, float exposure, sss::ToneMap toneMap, bool srgb) {
              py::array a = py::array::ensure(image);
              if (!a) invalidArgument("save_png: image must be a NumPy array");
              if (a.dtype().is(py::dtype::of<std::uint8_t>())) image8FromNumpy(a).savePng(path);
              else sss::toDisplay(imageFromNumpy(a, "save_png"), displayTransform(exposure, toneMap, srgb)).savePng(path);
          },
          py::arg("path"), py::arg("image"), py::kw_only(), py::arg("exposure") = 0.0f,
          py::arg("tone_map") = sss::ToneMap::None, py::arg("srgb") = true,
          "Writes an RGBA PNG: a uint8 image as is, a float image through to_display().");
    m.def("save_exr", [](const std::filesystem::path& path, const py::handle& image) {
              imageFromNumpy(image, "save_exr").saveExr(path);
          },
          py::arg("path"), py::arg("image"), "Writes a linear float image as 32-bit float RGBA OpenEXR.");
    m.def("load_exr", [](const std::filesystem::path& path) { return toNumpy(sss::Image::loadExr(path)); },
          py::arg("path"), "(H, W, 4) float32 from an OpenEXR file.");
    m.def("load_png", [](const std::filesystem::path& path) { return toNumpy8(sss::Image8::loadPng(path)); },
          py::arg("path"), "(H, W, 4) uint8 from a PNG file.");
}

}  // namespace

py::array_t<float> toNumpy(const sss::Image& image) {
    py::array_t<float> a({static_cast<py::ssize_t>(image.height()), static_cast<py::ssize_t>(image.width()), py::ssize_t{4}});
    std::memcpy(a.mutable_data(), image.data().data(), image.data().size() * sizeof(float));
    return a;
}

sss::Image imageFromNumpy(const py::handle& src, const char* what) {
    py::array raw = py::array::ensure(src);
    if (!raw) invalidArgument(std::string(what) + ": image must be a NumPy array of shape (H, W, 4)");
    const char kind = raw.dtype().kind();
    if (kind != 'f' && kind != 'i' && kind != 'u')
        invalidArgument(std::string(what) + ": image must hold real numbers, got dtype " + dtypeName(raw));
    if (raw.ndim() != 3 || (raw.shape(2) != 3 && raw.shape(2) != 4))
        invalidArgument(std::string(what) + ": image must have shape (H, W, 4) or (H, W, 3), got " +
                        std::string(py::str(py::tuple(raw.attr("shape")))));
    auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(raw);
    const int h = static_cast<int>(a.shape(0)), w = static_cast<int>(a.shape(1)), c = static_cast<int>(a.shape(2));
    sss::Image image(w, h, glm::vec4(1.0f));
    if (c == 4) {
        std::memcpy(image.data().data(), a.data(), image.data().size() * sizeof(float));
    } else {
        auto r = a.unchecked<3>();
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) image.at(x, y) = glm::vec4(r(y, x, 0), r(y, x, 1), r(y, x, 2), 1.0f);
    }
    return image;
}

void bindData(py::module_& m) {
    bindGeometry(m);
    bindVolume(m);
    bindTransferFunction(m);
    bindMaterials(m);
    bindLights(m);
    bindCamera(m);
    bindImages(m);
}

}  // namespace ssspy
