"""Rendering through the Python module: the same scene gives the same image as the C++ API, NumPy
volumes of every voxel type and meshes from arrays render, lights and progressive frames work."""
import os
import subprocess

import numpy as np
import pytest

import scenes
import sss

BACKGROUND = np.array(sss.HybridOptions().background, dtype=np.float32)


def covered(image, threshold=0.01):
    """Share of pixels that differ from the background by more than threshold in a channel."""
    return float((np.abs(image - BACKGROUND).max(axis=2) > threshold).mean())


@pytest.mark.parametrize("scene", sorted(scenes.RENDER))
def test_render_matches_cpp(gl, out_dir, scene):
    """The Python render of a scene equals the C++ render of it (reference_render.cpp), pixel for
    pixel: both run the same library on the same device, so any difference is a binding bug
    (option or array conversion, row order, frame sequence)."""
    reference = os.environ.get("SSS_PYTHON_REFERENCE")
    if not reference:
        pytest.skip("SSS_PYTHON_REFERENCE (the sss_python_reference program) is not set")
    exr = os.path.join(out_dir, f"cpp_{scene}.exr")
    subprocess.run([reference, scene, exr], check=True)
    expected = sss.load_exr(exr)
    image = scenes.RENDER[scene]()
    assert image.dtype == np.float32 and image.shape == (scenes.HEIGHT, scenes.WIDTH, 4)
    sss.save_png(os.path.join(out_dir, f"python_{scene}.png"), image)
    diff = np.abs(image - expected)
    print(f"{scene}: max |python - C++| = {diff.max():.3g}, mean = {diff.mean():.3g}, "
          f"covered {covered(image):.1%}")
    assert covered(image) > 0.05, "the scene is not in view"
    assert diff.max() <= 1e-6


def blob(shape=(24, 28, 32)):
    """A Gaussian blob in [0, 1], 1 at the centre voxel, indexed [z, y, x]."""
    z, y, x = np.indices(shape, dtype=np.float64)
    c = [(n - 1) / 2 for n in shape]
    r2 = ((x - c[2]) / shape[2]) ** 2 + ((y - c[1]) / shape[1]) ** 2 + ((z - c[0]) / shape[0]) ** 2
    return np.exp(-r2 * 14.0)


def as_dtype(f, dtype):
    """f in [0, 1] spread over dtype's range (float32 as is), so the transfer function sees the
    same coordinate for every type: uint8 over 0..255, the others over their value range."""
    if dtype == np.float32:
        return f.astype(np.float32)
    info = np.iinfo(dtype)
    return np.round(info.min + f * (float(info.max) - info.min)).astype(dtype)


@pytest.fixture(scope="module")
def volume_images(gl):
    renderer = sss.VolumeRenderer(shading="gradient", jitter=False)
    renderer.transfer_function = sss.TransferFunction([(0.0, (0.2, 0.4, 1.0), 0.0), (1.0, (1.0, 0.8, 0.3), 0.6)])
    renderer.lights = [sss.DirectionalLight(direction=(-1, -1, -1))]
    camera = sss.Camera(yaw=20, pitch=15, distance=2.2)
    data = blob()
    images = {}
    for dtype in (np.uint8, np.uint16, np.int16, np.float32):
        volume = sss.Volume(as_dtype(data, dtype), spacing=(1.0, 1.0, 1.25))
        assert volume.dims == (32, 28, 24)
        assert volume.dtype == np.dtype(dtype)
        assert np.array_equal(volume.data, as_dtype(data, dtype))
        renderer.set_volume(volume)
        images[np.dtype(dtype).name] = renderer.render(camera, width=64, height=48)
    return images


@pytest.mark.parametrize("dtype", ["uint8", "uint16", "int16", "float32"])
def test_numpy_volume_of_each_dtype_renders(volume_images, out_dir, dtype):
    """A NumPy volume of each voxel type renders the blob, and the four types agree: the data are
    the same function scaled to each type's range, so only the 8-bit quantisation differs."""
    image = volume_images[dtype]
    sss.save_png(os.path.join(out_dir, f"numpy_volume_{dtype}.png"), image)
    diff = np.abs(image - volume_images["float32"]).max()
    print(f"{dtype}: covered {covered(image):.1%}, max difference to float32 {diff:.3g}")
    assert covered(image) > 0.1
    # 8-bit voxels differ from the others by up to half a step (1/510) in value, which gradient
    # shading amplifies; the 16-bit types agree to 0.005.
    assert diff < (0.04 if dtype == "uint8" else 0.01)


def test_mesh_from_arrays_renders_as_the_library_mesh(gl, out_dir):
    """A mesh built from NumPy arrays (with normals, and without: computed) renders; with the
    library sphere's own arrays it gives the library sphere's image."""
    sphere = sss.make_uv_sphere(32, 16, 0.5)
    from_arrays = sss.Mesh(sphere.vertices, sphere.indices.astype(np.int64), normals=sphere.normals)
    no_normals = sss.Mesh(sphere.vertices.astype(np.float64), sphere.indices)
    renderer = sss.MeshRenderer()  # Blinn-Phong
    renderer.lights = [sss.PointLight(position=(1.0, 2.0, 2.0), intensity=6.0)]
    camera = sss.Camera(distance=2.0, pitch=10)
    images = []
    for mesh in (sphere, from_arrays, no_normals):
        renderer.set_mesh(mesh)
        images.append(renderer.render(camera, width=64, height=64))
    sss.save_png(os.path.join(out_dir, "mesh_from_arrays.png"), images[1])
    same = np.abs(images[1] - images[0]).max()
    computed = np.abs(images[2] - images[0]).mean()
    print(f"covered {covered(images[0]):.1%}; from arrays: max difference {same:.3g}; computed normals: "
          f"mean difference {computed:.3g}")
    assert covered(images[0]) > 0.2
    # The normals are normalized again on the way in, which may move their last bit.
    assert same < 1e-4
    # Computed normals are area-weighted, not analytic: close, not equal.
    assert computed < 0.01


def test_spot_light_lights_only_inside_its_cone(gl):
    """A spot light aimed at the mesh lights it; the same light turned away leaves only ambient."""
    renderer = sss.MeshRenderer(sss.MeshRenderOptions())
    renderer.set_mesh(sss.make_uv_sphere(radius=0.5))
    camera = sss.Camera(distance=2.0)
    spot = sss.SpotLight(position=(0, 0, 2), direction=(0, 0, -1), cone_angle=20, intensity=4.0)
    renderer.lights = [spot]
    lit = renderer.render(camera, width=48, height=48)
    renderer.lights = [spot.replace(direction=(0, 0, 1))]
    dark = renderer.render(camera, width=48, height=48)
    print(f"centre: lit {lit[24, 24, 0]:.3f}, turned away {dark[24, 24, 0]:.3f}")
    assert lit[24, 24, 0] > 5 * dark[24, 24, 0]
    assert isinstance(renderer.lights[0], sss.SpotLight)


def test_multiple_scattering_accumulates_frames(gl):
    """Progressive path tracing: `frames` renders add samples_per_frame paths each to the mean."""
    renderer = sss.VolumeRenderer(shading="scattering", model="physical", multiple_scattering=True,
                                  samples_per_frame=2)
    renderer.set_volume(sss.make_blobs_volume(16))
    renderer.lights = [sss.DirectionalLight(direction=(-1, -1, -1), intensity=8.0)]
    image = renderer.render(width=32, height=24, frames=3, antialias=4)  # antialias is ignored here
    assert renderer.accumulated_samples == 6
    assert np.isfinite(image).all()


def test_multiple_scattering_cache_refines_and_brightens(gl):
    """The multiple-scattering cache: each frame adds cache_photons_per_frame photons until
    cache_photons; the light scattered more than once adds to single scattering."""
    options = dict(shading="scattering", model="physical", cache_resolution=16)
    single = sss.VolumeRenderer(**options)
    cached = sss.VolumeRenderer(multiple_scattering_cache=True, cache_photons_per_frame=4096, cache_photons=8192,
                                **options)
    for renderer in (single, cached):
        renderer.set_volume(sss.make_blobs_volume(16))
        renderer.lights = [sss.DirectionalLight(direction=(-1, -1, -1), intensity=8.0)]
    base = single.render(width=32, height=24, antialias=1)
    image = cached.render(width=32, height=24, frames=3, antialias=1)
    assert cached.cached_photons == 8192 and single.cached_photons == 0
    assert np.isfinite(image).all()
    assert image[..., :3].sum() > 1.05 * base[..., :3].sum()  # measured 1.10


def test_multiple_scattering_cache_view_evaluation(gl):
    """cache_view_evaluation: the cache's light towards the viewer once per cell and camera move
    (the "scattering-cache-view" pass) or per sample (no such pass), the same picture within 2 %."""
    images, view_runs = {}, {}
    for evaluation in (sss.CacheViewEvaluation.PER_CELL, sss.CacheViewEvaluation.PER_SAMPLE):
        renderer = sss.VolumeRenderer(shading="scattering", model="physical", multiple_scattering_cache=True,
                                      cache_resolution=16, cache_photons_per_frame=8192, cache_photons=8192,
                                      cache_view_evaluation=evaluation)
        renderer.set_volume(sss.make_blobs_volume(16))
        renderer.lights = [sss.DirectionalLight(direction=(-1, -1, -1), intensity=8.0)]
        images[evaluation] = renderer.render(width=32, height=24, antialias=1)
        view_runs[evaluation] = renderer.stats.get("scattering-cache-view", {}).get("runs", 0)
    assert view_runs[sss.CacheViewEvaluation.PER_CELL] == 1 and view_runs[sss.CacheViewEvaluation.PER_SAMPLE] == 0
    a, b = images[sss.CacheViewEvaluation.PER_SAMPLE][..., :3], images[sss.CacheViewEvaluation.PER_CELL][..., :3]
    assert np.sqrt(np.mean((a - b) ** 2)) < 0.02 * np.sqrt(np.mean(b ** 2))


def test_light_volume_preview(gl):
    """light_volume_preview_scale: one frame after a light change draws a coarser light volume,
    the next the full one, the same picture as without the preview."""
    full = sss.VolumeRenderer(shading="scattering")
    preview = sss.VolumeRenderer(shading="scattering", light_volume_preview_scale=0.25)
    for renderer in (full, preview):
        renderer.set_volume(sss.make_blobs_volume(32))
        renderer.lights = [sss.DirectionalLight(direction=(-1, -0.6, -0.3))]
    reference = full.render(width=32, height=24)
    first = preview.render(width=32, height=24)
    assert preview.light_volume_previewed
    assert not np.array_equal(first, reference)
    second = preview.render(width=32, height=24)
    assert not preview.light_volume_previewed
    assert np.array_equal(second, reference)


def test_scene_handles_and_display(gl, out_dir):
    """A Scene's meshes and volumes are handles whose options can change, stale after clear();
    to_display applies the library's display transform."""
    scene = sss.Scene(background=(0, 0, 0, 1))
    mesh = scene.add_mesh(sss.make_torus(), material=sss.BlinnPhongMaterial(diffuse=(0.9, 0.2, 0.2)))
    scene.lights = [sss.DirectionalLight(direction=(0, -1, -1))]
    assert mesh.options.shading == sss.MeshShading.BLINN_PHONG
    mesh.configure(shading="scattering", cameras=2, samples=4, map_resolution=64, light_map_resolution=64,
                   accumulation_frames=1)
    assert mesh.options.cameras == 2 and mesh.material.diffuse[1] == pytest.approx(0.2)
    image = scene.render(width=64, height=48)
    assert mesh.converged
    display = sss.to_display(image, exposure=1.0, tone_map="filmic")
    assert display.dtype == np.uint8 and display.shape == (48, 64, 4)
    sss.save_png(os.path.join(out_dir, "scene_torus.png"), display)
    scene.clear()
    with pytest.raises(sss.InvalidArgumentError, match="removed by Scene.clear"):
        mesh.options


def test_cornell_box_scene_is_seen_straight_in(gl, out_dir):
    """A Scene with cornell_box=True and no camera looks straight into the box: the red wall on
    the left of the picture, the green one on the right."""
    scene = sss.Scene(cornell_box=True)
    scene.add_mesh(sss.make_uv_sphere(radius=0.3))
    scene.lights = [sss.PointLight(position=(0.0, 0.5, 0.0), intensity=0.5)]
    image = scene.render(width=80, height=60)
    sss.save_png(os.path.join(out_dir, "cornell_box.png"), image)
    left, right = image[20:40, 8:16, :3].mean(axis=(0, 1)), image[20:40, -16:-8, :3].mean(axis=(0, 1))
    print(f"left wall {left}, right wall {right}")
    assert left[0] > 2 * left[1] and right[1] > 2 * right[0]


def test_hybrid_scene_matches_sss_render(gl, out_dir):
    """The hybrid scene sss-render builds from its command line (procedural sphere made 0.4 units
    large and moved, procedural blobs, its default light, background and framing) rendered
    through Python equals sss-render's linear EXR, pixel for pixel."""
    sss_render = os.environ.get("SSS_RENDER")
    if not sss_render:
        pytest.skip("SSS_RENDER (the sss-render program) is not set")
    exr = os.path.join(out_dir, "sss_render_hybrid.exr")
    subprocess.run([sss_render, "--mode", "hybrid", "--mesh", "procedural:sphere", "--mesh-size", "0.4",
                    "--mesh-offset", "0.3,0,0.6", "--volume", "procedural:blobs", "--cameras", "4", "--samples",
                    "8", "--map-resolution", "128", "--frames", "2", "--size", "96x72", "--aa", "2", "--out", exr],
                   check=True, stdout=subprocess.DEVNULL)
    sphere = sss.make_uv_sphere()
    scale = np.float32(0.4) / np.float32(max(sphere.bounds.size))
    fit = np.diag([scale, scale, scale, 1.0]).astype(np.float32) @ translation(-np.array(sphere.bounds.center))
    offset = translation((0.3, 0.0, 0.6))

    scene = sss.Scene()
    scene.add_mesh(sphere.transformed(fit), offset, shading="scattering", cameras=4, samples=8, map_resolution=128,
                   light_map_resolution=128, accumulation_frames=2)
    scene.add_volume(sss.make_blobs_volume(), shading="scattering", samples_per_frame=8)
    scene.lights = [sss.DirectionalLight(direction=(-1, -1, -1))]
    image = scene.render(width=96, height=72, antialias=2)
    diff = np.abs(image - sss.load_exr(exr))
    print(f"max |python - sss-render| = {diff.max():.3g}, mean = {diff.mean():.3g}, covered {covered(image):.1%}")
    assert covered(image) > 0.1
    assert diff.max() <= 1e-6


def translation(t):
    m = np.eye(4, dtype=np.float32)
    m[:3, 3] = t
    return m


def test_clip_cuts_the_volume_and_refuses_bad_planes(gl):
    """set_clip: a crop box keeping the volume's left half leaves the image's right part empty and
    its left part as it was; a zero normal is refused with the field named."""
    renderer = sss.VolumeRenderer(shading="emission-absorption", jitter=False)
    renderer.set_volume(sss.make_blobs_volume(32))
    # Seen along -z from x = 0: every ray left of the image's centre stays at x < 0.
    camera = sss.Camera(yaw=0, pitch=0, distance=1.4)
    whole = renderer.render(camera, width=64, height=48)
    renderer.set_clip(crop_max=(0.5, 1.0, 1.0))
    assert renderer.clip["crop_max"] == pytest.approx((0.5, 1.0, 1.0))
    cropped = renderer.render(camera, width=64, height=48)
    assert covered(whole[:, 34:]) > 0.05
    assert covered(cropped[:, 34:]) == 0.0
    assert np.array_equal(cropped[:, :30], whole[:, :30])
    renderer.set_clip(planes=[((0.0, 0.0, 0.0), (-1.0, 0.0, 0.0))])
    planes = renderer.render(camera, width=64, height=48)
    assert np.abs(planes - cropped).max() <= 2.0 / 255.0
    # The same plane in normalised data coordinates: x <= 0.5 of the volume.
    renderer.set_clip(planes=[((0.5, 0.0, 0.0), (-1.0, 0.0, 0.0))], plane_space="data")
    assert renderer.clip["plane_space"] == sss.CropSpace.DATA
    data_planes = renderer.render(camera, width=64, height=48)
    assert np.abs(data_planes - cropped).max() <= 2.0 / 255.0
    with pytest.raises(ValueError, match=r"planes\[0\]\.normal must be non-zero"):
        renderer.set_clip(planes=[((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))])
    renderer.set_clip(crop_min=(-5.0, -5.0, -5.0), crop_max=(0.0, 5.0, 5.0), crop_space="world")
    assert renderer.clip["crop_space"] == sss.CropSpace.WORLD
    world = renderer.render(camera, width=64, height=48)
    assert np.abs(world - planes).max() <= 2.0 / 255.0
    renderer.set_clip()
    assert renderer.clip["planes"] == []


def test_scene_isosurface_lies_in_its_volume_at_its_physical_size(gl):
    """Scene.add_isosurface: the surface of the blobs volume (32 voxels of 1.5 mm on its largest
    side) lies inside the volume's world box, renders, and gets millimetres_per_unit = 48 (and
    480 when a volume unit is 10 mm); a value no voxel crosses is refused."""
    volume = sss.Volume(sss.make_blobs_volume(32).data, spacing=(1.5, 1.5, 1.5))
    scene = sss.Scene(background=(0, 0, 0, 1))
    scene.add_volume(volume, shading="scattering")
    surface = scene.add_isosurface(volume, 128.0, shading="scattering", cameras=2, samples=4, map_resolution=64,
                                   light_map_resolution=64, accumulation_frames=1)
    assert surface.options.millimetres_per_unit == pytest.approx(48.0)
    lo, hi = np.array(scene.bounds.min), np.array(scene.bounds.max)
    assert np.all(lo >= -0.5 - 1e-6) and np.all(hi <= 0.5 + 1e-6)  # the volume's box holds both
    image = scene.render(width=48, height=36)
    assert covered(image) > 0.05
    scaled = scene.add_isosurface(volume, 128.0, millimetres_per_volume_unit=10.0)
    assert scaled.options.millimetres_per_unit == pytest.approx(480.0)
    with pytest.raises(sss.InvalidArgumentError, match="value"):
        scene.add_isosurface(volume, 1000.0)


def test_textured_material_from_numpy(gl, out_dir):
    """A mesh with texture coordinates and a NumPy base colour renders as a textured translucent
    material; a uniform texture gives the uniform material of its colour (the library's own
    inversion, material_from_reflectance)."""
    colour = np.array([200, 140, 90], dtype=np.uint8)
    slab = sss.make_slab((1.6, 1.0, 0.4))
    assert slab.texcoords.shape == (slab.vertex_count, 2)
    textured_mesh = slab.with_base_colour(np.tile(colour, (4, 4, 1)))
    assert textured_mesh.base_colour.shape == (4, 4, 4)
    textured = sss.textured_scattering(sss.material_preset("skin1"))
    linear = np.where(colour / 255.0 <= 0.04045, colour / 255.0 / 12.92, ((colour / 255.0 + 0.055) / 1.055) ** 2.4)
    uniform = sss.material_from_reflectance(tuple(linear), textured.mean_free_path, textured.eta)
    options = sss.MeshRenderOptions(shading=sss.MeshShading.SCATTERING, millimetres_per_unit=20.0, specular=0.0,
                                    map_resolution=256)
    renderer = sss.MeshRenderer(options)
    renderer.set_mesh(textured_mesh)
    camera = sss.Camera(distance=2.5, yaw=25, pitch=35)
    renderer.set_textured_material(textured)
    a = renderer.render(camera, width=48, height=32)
    renderer.scattering_material = uniform
    b = renderer.render(camera, width=48, height=32)
    sss.save_png(os.path.join(out_dir, "textured_uniform.png"), a)
    difference = np.abs(a - b)[..., :3].mean() / max(np.abs(b[..., :3]).mean(), 1e-9)
    print(f"covered {covered(a):.1%}; textured against uniform: mean relative difference {difference:.4f}")
    assert covered(a) > 0.2
    assert difference < 0.01  # measured 0.00; the C++ test measures relRmse 0.0010
    with pytest.raises(sss.Error, match="texture coordinates"):
        sss.make_uv_sphere(8, 4).with_base_colour(np.zeros((2, 2, 4), dtype=np.uint8))
