"""The scenes of the "matches C++" tests, built through the Python module. They must stay the
same as python/tests/reference_render.cpp, which renders them with the C++ API."""
import numpy as np

import sss

WIDTH, HEIGHT, ANTIALIAS = 96, 72, 2
LIGHT = sss.DirectionalLight(direction=(-1, -1, -1), color=(1.0, 0.95, 0.9), intensity=2.0)


def mesh_options():
    return sss.MeshRenderOptions(shading="scattering", cameras=4, samples=8, map_resolution=128,
                                 light_map_resolution=128, accumulation_frames=2, millimetres_per_unit=20.0)


def volume_options():
    return sss.VolumeRenderOptions(shading=sss.VolumeShading.SCATTERING, light_volume_scale=0.5)


def sphere():
    return sss.make_uv_sphere(24, 16, 0.5)


def render_mesh():
    r = sss.MeshRenderer(mesh_options())
    r.set_mesh(sphere())
    r.scattering_material = sss.material_preset("marble")
    r.lights = [LIGHT]
    return r.render(width=WIDTH, height=HEIGHT, antialias=ANTIALIAS)


def render_volume():
    r = sss.VolumeRenderer(volume_options())
    r.set_volume(sss.make_blobs_volume(32))
    r.transfer_function = sss.TransferFunction.preset("bucky")
    r.lights = [LIGHT]
    return r.render(width=WIDTH, height=HEIGHT, antialias=ANTIALIAS)


def mesh_model():
    """Translate (0.2, 0, 0.6) after a uniform scale of 0.4, as a 4x4 matrix."""
    model = np.diag([0.4, 0.4, 0.4, 1.0]).astype(np.float32)
    model[:3, 3] = (0.2, 0.0, 0.6)
    return model


def render_hybrid():
    scene = sss.Scene()
    scene.add_mesh(sphere(), mesh_model(), mesh_options(), scattering_material=sss.material_preset("skin1"))
    scene.add_volume(sss.make_blobs_volume(32), options=volume_options(),
                     transfer_function=sss.TransferFunction.preset("bucky"))
    scene.lights = [LIGHT]
    return scene.render(width=WIDTH, height=HEIGHT, antialias=ANTIALIAS)


RENDER = {"mesh": render_mesh, "volume": render_volume, "hybrid": render_hybrid}
