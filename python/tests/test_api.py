"""The Python API without rendering (except where noted): arrays in and out, option structs,
enums, and errors raised as sss.Error subclasses carrying the library's message."""
import math

import numpy as np
import pytest

import sss


# ---- errors ---------------------------------------------------------------------------------------

def test_error_classes_derive_from_sss_error_and_builtins():
    assert issubclass(sss.InvalidArgumentError, sss.Error) and issubclass(sss.InvalidArgumentError, ValueError)
    assert issubclass(sss.IoError, sss.Error) and issubclass(sss.IoError, OSError)
    assert issubclass(sss.ParseError, sss.Error) and issubclass(sss.ParseError, ValueError)
    assert issubclass(sss.GlError, sss.Error) and issubclass(sss.GpuLimitError, sss.Error)
    assert issubclass(sss.Error, RuntimeError)


def test_invalid_option_raises_with_the_library_message():
    with pytest.raises(sss.InvalidArgumentError) as e:
        sss.MeshRenderOptions(cameras=0)
    assert str(e.value) == "MeshRenderOptions::cameras must be in 1..32, got 0"
    assert e.value.kind == sss.ErrorKind.INVALID_ARGUMENT
    with pytest.raises(sss.InvalidArgumentError, match=r"^VolumeRenderOptions::stepSize must be finite and > 0"):
        sss.VolumeRenderOptions(step_size=-1.0)
    with pytest.raises(sss.InvalidArgumentError, match=r"^Camera::setFovY: fovY must be in \(0, 180\)"):
        sss.Camera(fov_y=200)
    with pytest.raises(sss.InvalidArgumentError, match=r"PointLight::intensity must be finite and >= 0, got -1"):
        sss.PointLight(intensity=-1)
    with pytest.raises(ValueError, match=r"ScatteringMaterial::eta must be in \[0.4, 2.5\]"):
        sss.material_preset("marble").replace(eta=0.0)


def test_unknown_option_and_wrong_type_are_type_errors():
    with pytest.raises(TypeError, match=r"MeshRenderOptions: unknown option 'foo' \(options: shading, "):
        sss.MeshRenderOptions(foo=1)
    with pytest.raises(TypeError, match=r"MeshRenderOptions.cameras: expected int, got 'x'"):
        sss.MeshRenderOptions(cameras="x")
    with pytest.raises(sss.InvalidArgumentError, match=r'MeshShading: unknown value "nope" \(blinn_phong, scattering\)'):
        sss.MeshRenderOptions(shading="nope")


def test_missing_files_raise_io_errors_naming_the_file():
    with pytest.raises(sss.IoError, match=r"^/nonexistent/bunny.obj: file does not exist$") as e:
        sss.Mesh.load("/nonexistent/bunny.obj")
    assert isinstance(e.value, OSError) and e.value.kind == sss.ErrorKind.IO
    with pytest.raises(sss.IoError, match=r"^Volume::load: /nonexistent/head.nrrd: "):
        sss.Volume.load("/nonexistent/head.nrrd")
    with pytest.raises(sss.IoError, match="/nonexistent/tf.json"):
        sss.TransferFunction.load_paraview_json("/nonexistent/tf.json")
    with pytest.raises(sss.IoError):
        sss.load_exr("/nonexistent/image.exr")


def test_malformed_file_raises_parse_error(tmp_path):
    path = tmp_path / "bad.obj"
    path.write_text("v 1 2 x\nf 1 2 3\n")
    with pytest.raises(sss.ParseError, match=r'bad.obj: vertex 1 has a non-finite or non-numeric coordinate "x"'):
        sss.Mesh.load(path)


def test_unknown_presets_list_the_known_names():
    with pytest.raises(sss.InvalidArgumentError, match=r'unknown preset "nope"; valid names: ramp, bucky'):
        sss.TransferFunction.preset("nope")
    with pytest.raises(sss.InvalidArgumentError, match=r'unknown material "nope"; known: apple'):
        sss.material_preset("nope")


# ---- meshes ---------------------------------------------------------------------------------------

TRIANGLE = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], dtype=np.float32)


def test_mesh_from_arrays_round_trips():
    mesh = sss.Mesh(TRIANGLE, [[0, 1, 2]], name="tri")
    assert (mesh.vertex_count, mesh.triangle_count, mesh.name) == (3, 1, "tri")
    assert np.array_equal(mesh.vertices, TRIANGLE) and mesh.vertices.dtype == np.float32
    assert mesh.indices.dtype == np.uint32 and mesh.indices.tolist() == [[0, 1, 2]]
    assert np.allclose(mesh.normals, [[0, 0, 1]] * 3)  # computed: counter-clockwise seen from +z
    assert mesh.bounds.max == (1.0, 1.0, 0.0)
    moved = mesh.transformed(np.diag([2.0, 2.0, 2.0, 1.0]))
    assert moved.bounds.max == (2.0, 2.0, 0.0)


def test_mesh_rejects_bad_arrays():
    with pytest.raises(sss.InvalidArgumentError, match=r"^Mesh: vertices must have shape \(N, 3\), got \(3, 2\)$"):
        sss.Mesh(np.zeros((3, 2)), [[0, 1, 2]])
    with pytest.raises(sss.InvalidArgumentError, match=r"^Mesh: indices must be an integer array, got dtype float64$"):
        sss.Mesh(TRIANGLE, np.array([[0.0, 1.0, 2.0]]))
    with pytest.raises(sss.InvalidArgumentError, match="vertices must hold real numbers, got dtype <U1"):
        sss.Mesh(np.array([["a", "b", "c"]] * 3), [[0, 1, 2]])
    with pytest.raises(sss.InvalidArgumentError, match=r"index -1 at position 2 is outside"):
        sss.Mesh(TRIANGLE, [[0, 1, -1]])
    # The library's own checks come through with its message.
    with pytest.raises(sss.InvalidArgumentError,
                       match=r"^mesh: triangle 0 \(indices\[2\]\) references vertex 5, but the mesh has 3 vertices$"):
        sss.Mesh(TRIANGLE, [[0, 1, 5]])
    with pytest.raises(sss.InvalidArgumentError):
        sss.Mesh(TRIANGLE * np.nan, [[0, 1, 2]])


# ---- volumes --------------------------------------------------------------------------------------

@pytest.mark.parametrize("dtype,kind", [(np.uint8, sss.VoxelType.UINT8), (np.uint16, sss.VoxelType.UINT16),
                                        (np.int16, sss.VoxelType.INT16), (np.float32, sss.VoxelType.FLOAT32)])
def test_volume_from_numpy_keeps_values_and_layout(dtype, kind):
    data = (np.arange(2 * 3 * 4) * 3).reshape(2, 3, 4).astype(dtype)  # [z, y, x]
    volume = sss.Volume(data, spacing=(1.0, 2.0, 0.5))
    assert volume.type == kind and volume.dtype == np.dtype(dtype)
    assert volume.dims == (4, 3, 2) and volume.spacing == (1.0, 2.0, 0.5)
    assert volume.value_at(3, 1, 0) == data[0, 1, 3]
    assert np.array_equal(volume.data, data) and np.array_equal(np.asarray(volume), data)
    assert np.asarray(volume, dtype=np.float64).dtype == np.float64
    assert volume.value_range == (0.0, float(data.max()))


def test_volume_copies_strided_views_in_x_fastest_order():
    data = np.arange(4 * 5 * 6, dtype=np.uint16).reshape(4, 5, 6)
    view = data[:, ::2, ::-1]
    volume = sss.Volume(view)
    assert volume.dims == (6, 3, 4) and np.array_equal(volume.data, view)


def test_volume_rejects_bad_arrays():
    with pytest.raises(sss.InvalidArgumentError,
                       match=r"^Volume: dtype float64 is not supported \(uint8, uint16, int16, float32\)$"):
        sss.Volume(np.zeros((2, 2, 2)))
    with pytest.raises(sss.InvalidArgumentError, match="dtype int32 is not supported"):
        sss.Volume(np.zeros((2, 2, 2), dtype=np.int32))
    with pytest.raises(sss.InvalidArgumentError, match=r"must be 3-D, indexed \[z, y, x\], got shape \(4, 4\)"):
        sss.Volume(np.zeros((4, 4), dtype=np.uint8))
    with pytest.raises(sss.InvalidArgumentError, match=r"^Volume::fromData: voxel 0 is nan; float32 voxels must be finite$"):
        sss.Volume(np.full((2, 2, 2), np.nan, dtype=np.float32))
    with pytest.raises(sss.InvalidArgumentError, match="spacing"):
        sss.Volume(np.zeros((2, 2, 2), dtype=np.uint8), spacing=(1, 0, 1))


def test_volume_window_and_histogram():
    volume = sss.Volume(np.array([[[0, 100], [200, 255]]], dtype=np.uint8))
    assert volume.transfer_function_range == (0.0, 255.0)
    volume.value_window = (0.0, 200.0)
    assert volume.transfer_function_range == (0.0, 200.0)
    volume.value_window = None
    hist = volume.histogram(4)
    assert hist.tolist() == [1, 1, 0, 2]


def test_raw_volume_load_options(tmp_path):
    path = tmp_path / "cube_2x2x2_uint16.raw"
    np.arange(8, dtype="<u2").tofile(path)
    volume = sss.Volume.load(path, spacing=(1, 1, 2))
    assert volume.type == sss.VoxelType.UINT16 and volume.dims == (2, 2, 2) and volume.spacing == (1, 1, 2)
    assert volume.data.ravel().tolist() == list(range(8))
    with pytest.raises(sss.ParseError):
        sss.Volume.load(path, dims=(3, 3, 3))


# ---- transfer functions, materials, lights, camera ------------------------------------------------

def test_transfer_function_points_and_table(tmp_path):
    tf = sss.TransferFunction([(0.0, (0, 0, 0), 0.0), sss.ControlPoint(value=1.0, color=(1, 0.5, 0), opacity=1.0)])
    assert tf.evaluate(0.5) == pytest.approx((0.5, 0.25, 0.0, 0.5))
    table = tf.table(5)
    assert table.shape == (5, 4) and table.dtype == np.float32 and table[4].tolist() == [1.0, 0.5, 0.0, 1.0]
    index = tf.add_point(0.25, (1, 1, 1), 0.1)
    assert index == 1 and len(tf.points) == 3
    with pytest.raises(sss.InvalidArgumentError, match="strictly increasing"):
        sss.TransferFunction([(0.5, (1, 1, 1), 1.0), (0.2, (0, 0, 0), 0.0)])
    path = tmp_path / "tf.json"
    tf.save_paraview_json(path)
    again = sss.TransferFunction.load_paraview_json(path)
    assert [p.value for p in again.points] == pytest.approx([p.value for p in tf.points])
    assert "bucky" in sss.TransferFunction.preset_names()


def test_material_presets_and_option_structs():
    marble = sss.material_preset("Marble")
    assert marble.eta == 1.5 and marble.name == "marble"
    assert "skin1" in sss.material_preset_names()
    options = sss.MeshRenderOptions(shading="scattering", combine=sss.MeshCombine.PER_VERTEX, cameras=16)
    assert options.shading == sss.MeshShading.SCATTERING and options.cameras == 16
    assert options.samples == 24  # untouched fields keep the library's defaults
    changed = options.replace(samples=4, environment=(0.1, 0.1, 0.1))
    assert (changed.samples, options.samples) == (4, 24) and changed.environment == pytest.approx((0.1,) * 3)
    assert changed != options and changed.replace(samples=24, environment=(0, 0, 0)) == options
    assert "cameras=16" in repr(options) and "cameras" in sss.MeshRenderOptions.fields
    volume = sss.VolumeRenderOptions(shading="scattering-gradient", model="physical")
    assert volume.shading == sss.VolumeShading.SCATTERING_GRADIENT and volume.model == sss.VolumeModel.PHYSICAL
    assert sss.HybridOptions(cornell_box=True).shadow_map_resolution == 1024


def test_lights_and_spot_cone():
    spot = sss.SpotLight(cone_angle=40.0, falloff=0.0)
    assert spot.cone_factor(math.cos(math.radians(39.0))) == 1.0
    assert spot.cone_factor(math.cos(math.radians(41.0))) == 0.0
    with pytest.raises(sss.InvalidArgumentError, match="coneAngle"):
        sss.SpotLight(cone_angle=120.0)
    light = sss.DirectionalLight(direction=(0, -1, 0), intensity=2.0)
    assert light.direction == (0.0, -1.0, 0.0) and light == sss.DirectionalLight(direction=(0, -1, 0), intensity=2.0)


def test_camera_matrices_and_framing():
    camera = sss.Camera(distance=4.0, yaw=90.0)
    assert camera.position == pytest.approx((4.0, 0.0, 0.0), abs=1e-5)
    view = camera.view_matrix()
    assert view.shape == (4, 4) and view.dtype == np.float32
    eye = view @ np.array([4.0, 0.0, 0.0, 1.0])
    assert eye == pytest.approx([0, 0, 0, 1], abs=1e-5)  # the eye maps to the origin
    camera.frame_tight(sss.make_uv_sphere(), aspect=1.5)
    assert camera.distance > 1.0
    camera.near = 0.5
    with pytest.raises(sss.InvalidArgumentError):
        camera.far = 0.1


def test_display_transform_matches_srgb_formula():
    linear = np.array([[[0.0, 0.0031308, 0.5, 1.0], [2.0, 0.214, 1.0, 0.5]]], dtype=np.float32)
    display = sss.to_display(linear)
    def srgb(v):
        v = min(max(v, 0.0), 1.0)
        return 12.92 * v if v <= 0.0031308 else 1.055 * v ** (1 / 2.4) - 0.055
    expected = [[round(255 * srgb(v)) for v in px[:3]] for px in linear[0]]
    assert display[0, :, :3].tolist() == expected
    assert display[0, :, 3].tolist() == [255, 128]  # alpha passes through, linear
    assert sss.to_display(linear, srgb=False)[0, 0, 2] == 128
    assert sss.to_display(linear, exposure=-1.0, srgb=False)[0, 1, :2].tolist() == [255, round(255 * 0.107)]
    with pytest.raises(sss.InvalidArgumentError, match=r"got \(4, 4\)"):
        sss.to_display(np.zeros((4, 4)))
    with pytest.raises(sss.InvalidArgumentError, match="exposure"):
        sss.to_display(linear, exposure=100.0)


def test_png_and_exr_round_trip(tmp_path):
    image = np.random.default_rng(1).random((5, 7, 4), dtype=np.float32) * 3.0
    sss.save_exr(tmp_path / "a.exr", image)
    assert np.array_equal(sss.load_exr(tmp_path / "a.exr"), image)
    sss.save_png(tmp_path / "a.png", image)
    assert np.array_equal(sss.load_png(tmp_path / "a.png"), sss.to_display(image))


# ---- GL objects: bad input at the renderers -------------------------------------------------------

def test_renderers_raise_library_errors(gl):
    with pytest.raises(sss.InvalidArgumentError, match="MeshRenderOptions::cameras must be in 1..32, got 0"):
        sss.MeshRenderer(cameras=0)
    renderer = sss.MeshRenderer()
    with pytest.raises(sss.InvalidArgumentError, match=r"^MeshScatteringRenderer::render: no mesh set"):
        renderer.render(sss.Camera())
    with pytest.raises(sss.InvalidArgumentError, match="nothing to frame"):
        renderer.render()
    renderer.set_mesh(sss.make_uv_sphere())
    with pytest.raises(sss.InvalidArgumentError, match=r"^RenderTarget: size must be in 1..16384 on each side, got 0x480$"):
        renderer.render(sss.Camera(), width=0)
    with pytest.raises(TypeError, match="unknown option 'camera'"):
        sss.VolumeRenderer(camera=3)
    with pytest.raises(sss.InvalidArgumentError, match="at most 8"):
        renderer.lights = [sss.PointLight()] * 9
    assert "llvmpipe" in gl.renderer or not gl.software


def test_log_handler_receives_library_warnings(tmp_path):
    path = tmp_path / "line.obj"
    path.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\nf 1 2 3\n")  # a two-vertex face is skipped
    messages = []
    sss.set_log_handler(lambda level, message: messages.append((level, message)))
    try:
        mesh = sss.Mesh.load(path)
    finally:
        sss.set_log_handler(None)
    assert mesh.triangle_count == 1
    assert any(level == sss.LogLevel.WARNING and "line.obj" in text for level, text in messages), messages


def test_isosurface_of_a_volume_is_a_mesh_at_its_physical_size():
    volume = sss.make_blobs_volume(32)
    mesh = sss.extract_isosurface(volume, 100, max_triangles=2000)
    positions = mesh.vertices
    assert 100 < mesh.triangle_count <= 2200
    # Centred voxel coordinates (spacing 1): within half the grid of the centre, and not tiny.
    assert np.all(np.abs(positions) <= 16.0)
    assert np.ptp(positions, axis=0).max() > 5.0
    with pytest.raises(sss.InvalidArgumentError, match="IsosurfaceOptions::value"):
        sss.extract_isosurface(volume, 1000)

