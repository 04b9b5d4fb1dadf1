#!/usr/bin/env python3
"""Renders a volume made with NumPy and a mesh made from NumPy arrays with libsss, headless, and
writes them as PNG files (plus the volume as linear OpenEXR).

    PYTHONPATH=build/python python3 examples/python/render_numpy.py --out out/python

The volume is a noisy torus-shaped density in float32, lit through the light volume
(scattering shading); the mesh is a twisted, bumpy ring built vertex by vertex and rendered with
subsurface scattering in marble. Both scenes share one directional light.
"""
import argparse
import os

import numpy as np

import sss


def torus_density(n=64):
    """A float32 volume indexed [z, y, x]: a soft torus around the z axis with some noise."""
    z, y, x = np.mgrid[-1:1:n * 1j, -1:1:n * 1j, -1:1:n * 1j]
    ring = np.sqrt(x ** 2 + y ** 2) - 0.5
    density = np.exp(-(ring ** 2 + z ** 2) / (2 * 0.14 ** 2))
    noise = np.random.default_rng(7).normal(0.0, 0.05, density.shape)
    return np.clip(density + noise * density, 0.0, None).astype(np.float32)


def bumpy_ring(segments=96, sides=32):
    """A torus with a twisted bump, as vertex and index arrays (counter-clockwise triangles)."""
    u = np.linspace(0, 2 * np.pi, segments, endpoint=False)[:, None]
    v = np.linspace(0, 2 * np.pi, sides, endpoint=False)[None, :]
    r = 0.22 + 0.05 * np.sin(3 * u + 2 * v)
    x = (0.6 + r * np.cos(v)) * np.cos(u)
    y = r * np.sin(v)
    z = (0.6 + r * np.cos(v)) * np.sin(u)
    vertices = np.stack([x, y, z], axis=-1).reshape(-1, 3)
    i, j = np.meshgrid(np.arange(segments), np.arange(sides), indexing="ij")
    a = i * sides + j
    b = ((i + 1) % segments) * sides + j
    c = ((i + 1) % segments) * sides + (j + 1) % sides
    d = i * sides + (j + 1) % sides
    indices = np.concatenate([np.stack([a, d, c], -1), np.stack([a, c, b], -1)]).reshape(-1, 3)
    return vertices, indices


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="out/python", help="output folder (default: out/python)")
    parser.add_argument("--size", default="640x480", help="image size WxH (default: 640x480)")
    args = parser.parse_args()
    width, height = (int(s) for s in args.size.split("x"))
    os.makedirs(args.out, exist_ok=True)
    light = sss.DirectionalLight(direction=(-1.0, -1.0, -0.5), intensity=1.5)

    # A NumPy volume: float32, voxels twice as long along z as along x and y.
    volume = sss.Volume(torus_density(), spacing=(1.0, 1.0, 0.5))
    renderer = sss.VolumeRenderer(shading="scattering", anisotropy=0.3)
    renderer.set_volume(volume)
    renderer.transfer_function = sss.TransferFunction([
        (0.0, (0.1, 0.2, 0.6), 0.0),
        (0.3, (0.2, 0.5, 0.9), 0.05),
        (1.0, (1.0, 0.9, 0.7), 0.5),
    ])
    renderer.lights = [light]
    camera = sss.Camera(yaw=25.0, pitch=35.0)
    camera.frame_tight(volume.world_bounds, aspect=width / height)
    image = renderer.render(camera, width=width, height=height, antialias=4)
    sss.save_exr(os.path.join(args.out, "volume.exr"), image)  # linear radiance
    sss.save_png(os.path.join(args.out, "volume.png"), image, tone_map="filmic")

    # A mesh from NumPy arrays (normals computed), translucent marble.
    vertices, indices = bumpy_ring()
    mesh = sss.Mesh(vertices, indices, name="bumpy ring")
    renderer = sss.MeshRenderer(shading="scattering", millimetres_per_unit=40.0, samples=16, map_resolution=256,
                                light_map_resolution=256, environment=(0.05, 0.05, 0.05))
    renderer.set_mesh(mesh)
    renderer.scattering_material = sss.material_preset("marble")
    renderer.lights = [light]
    camera = sss.Camera(yaw=20.0, pitch=50.0)
    camera.frame_tight(mesh, aspect=width / height)
    image = renderer.render(camera, width=width, height=height, antialias=4)
    sss.save_png(os.path.join(args.out, "mesh.png"), sss.to_display(image, exposure=0.5))

    print(f"{sss.default_context().renderer}: wrote volume.png, volume.exr and mesh.png to {args.out}")


if __name__ == "__main__":
    main()
