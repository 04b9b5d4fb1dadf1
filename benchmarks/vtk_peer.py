#!/usr/bin/env python3
"""Times libsss's volume renderer against VTK's vtkGPUVolumeRayCastMapper on the same volume,
transfer function, viewport, camera, light and ray step (issue: "a peer comparison the user can
rerun"). Run it through benchmarks/vtk-peer.sh, which installs what it needs and starts Xvfb
(Debian's VTK renders through GLX only).

Both programs get:
- the volume as a box one unit on its longest side, centred on the origin (libsss's placement);
- the transfer function libsss's preset defines (sss-render --export-tf: a ParaView JSON map),
  over the voxel type's range, with the opacity of one step of one voxel;
- a perspective camera at the same eye, target and vertical field of view, framing the box's
  bounding sphere; one directional light; the same background;
- a ray step of --step voxels, without automatic sample-distance changes in VTK.

Modes: emission-absorption (no shading), gradient (Phong shading with libsss's defaults:
ambient 0.25, diffuse 0.85, specular 0.3, exponent 32) and, when the VTK has volumetric
scattering (9.2+, e.g. ParaView 5.11's pvpython), scattering (libsss: the light volume, built
before the timed frames; VTK: shadow rays every frame).

Timing: per mode, warm-up frames, then --frames timed frames each (VTK: Render() and
WaitForCompletion(); libsss: sss-render's GL timer query or CPU clock around glFinish),
medians; the two programs alternate --repeats times. Coverage (the share of pixels that differ
from the background) is compared, so a program that draws nothing cannot win.
"""
import argparse
import json
import math
import os
import re
import subprocess
import sys
import tempfile
import time

import numpy as np
import vtkmodules.vtkRenderingVolumeOpenGL2  # noqa: F401  (registers the OpenGL volume mapper)
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkVersion
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPiecewiseFunction
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkColorTransferFunction, vtkLight, vtkRenderer, vtkRenderWindow, vtkVolume,
                                         vtkVolumeProperty, vtkWindowToImageFilter)
from vtkmodules.vtkRenderingVolume import vtkGPUVolumeRayCastMapper
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (registers the OpenGL render window)

BACKGROUND = (0.01, 0.01, 0.0137)  # libsss's default, linear


def parse_raw_name(path):
    match = re.search(r"(\d+)x(\d+)x(\d+)", os.path.basename(path))
    if not match:
        sys.exit(f"vtk_peer: {path}: no dims (like 256x256x256) in the name")
    dims = tuple(int(g) for g in match.groups())
    kind = "uint16" if "uint16" in os.path.basename(path) else "uint8"
    return dims, kind


def load_image(path, dims, kind):
    """The raw volume as vtkImageData placed like libsss's Volume::worldBounds()."""
    count = dims[0] * dims[1] * dims[2]
    voxels = np.fromfile(path, dtype="<u2" if kind == "uint16" else np.uint8)
    if voxels.size < count:
        sys.exit(f"vtk_peer: {path}: {voxels.size} voxels, its dims need {count}")
    array = numpy_to_vtk(voxels[:count], deep=True)
    image = vtkImageData()
    image.SetDimensions(*dims)
    voxel = 1.0 / max(dims)
    image.SetSpacing(voxel, voxel, voxel)
    # Voxel centres inside the box [-dims/2, dims/2] * voxel, as libsss samples its texture.
    image.SetOrigin(*[(-0.5 * d + 0.5) * voxel for d in dims])
    image.GetPointData().SetScalars(array)
    return image, voxel


def camera_setup(dims, yaw, pitch, fov, aspect):
    """Eye, target and distance for libsss's orbit convention, framing the box's bounding
    sphere (Camera::frame), widened when the image is taller than wide."""
    side = [d / max(dims) for d in dims]
    radius = 0.5 * math.sqrt(sum(s * s for s in side))
    distance = radius / math.sin(math.radians(fov) / 2)
    if aspect < 1:
        distance /= aspect
    y, p = math.radians(yaw), math.radians(pitch)
    direction = (math.sin(y) * math.cos(p), math.sin(p), math.cos(y) * math.cos(p))
    eye = tuple(distance * c for c in direction)
    return eye, (0.0, 0.0, 0.0), distance


def coverage_of_png(path):
    """The share of pixels that differ from the corner pixel (the background) by more than 3/255."""
    from vtkmodules.vtkIOImage import vtkPNGReader
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    pixels = vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())[:, :3].astype(int)
    return float(np.mean(np.any(np.abs(pixels - pixels[0]) > 3, axis=1)))


class VtkScene:
    def __init__(self, args, image, voxel, tf_json, eye, target):
        self.window = vtkRenderWindow()
        self.window.SetSize(args.width, args.height)
        self.window.SetOffScreenRendering(1)
        self.window.SetMultiSamples(0)
        self.renderer = vtkRenderer()
        self.renderer.SetBackground(*BACKGROUND)
        self.window.AddRenderer(self.renderer)
        self.mapper = vtkGPUVolumeRayCastMapper()
        self.mapper.SetInputData(image)
        self.mapper.SetAutoAdjustSampleDistances(0)
        self.mapper.SetSampleDistance(args.step * voxel)
        self.property = vtkVolumeProperty()
        self.property.SetInterpolationTypeToLinear()
        self.property.SetScalarOpacityUnitDistance(voxel)  # the TF's opacity is per voxel, as in libsss
        top = 65535.0 if args.kind == "uint16" else 255.0
        colors, opacity = vtkColorTransferFunction(), vtkPiecewiseFunction()
        preset = tf_json[0]
        rgb = preset["RGBPoints"]
        for i in range(0, len(rgb), 4):
            colors.AddRGBPoint(rgb[i] * top, rgb[i + 1], rgb[i + 2], rgb[i + 3])
        points = preset["Points"]
        for i in range(0, len(points), 4):
            opacity.AddPoint(points[i] * top, points[i + 1])
        self.property.SetColor(colors)
        self.property.SetScalarOpacity(opacity)
        self.property.SetAmbient(0.25)
        self.property.SetDiffuse(0.85)
        self.property.SetSpecular(0.3)
        self.property.SetSpecularPower(32.0)
        self.volume = vtkVolume()
        self.volume.SetMapper(self.mapper)
        self.volume.SetProperty(self.property)
        self.renderer.AddVolume(self.volume)
        camera = self.renderer.GetActiveCamera()
        camera.SetPosition(*eye)
        camera.SetFocalPoint(*target)
        camera.SetViewUp(0, 1, 0)
        camera.SetViewAngle(args.fov)
        self.renderer.ResetCameraClippingRange()
        light = vtkLight()
        light.SetLightTypeToSceneLight()
        light.SetPositional(0)
        light.SetPosition(1, 1, 1)  # a directional light travelling along (-1, -1, -1)
        light.SetFocalPoint(0, 0, 0)
        self.renderer.RemoveAllLights()
        self.renderer.AddLight(light)
        self.renderer.SetAutomaticLightCreation(0)

    def set_mode(self, mode):
        self.property.SetShade(0 if mode == "emission-absorption" else 1)
        if hasattr(self.mapper, "SetVolumetricScatteringBlending"):
            self.mapper.SetVolumetricScatteringBlending(1.0 if mode == "scattering" else 0.0)
            self.property.SetScatteringAnisotropy(0.5 if mode == "scattering" else 0.0)

    def time_frames(self, warmup, frames):
        for _ in range(warmup):
            self.window.Render()
            self.window.WaitForCompletion()
        samples = []
        for _ in range(frames):
            start = time.perf_counter()
            self.window.Render()
            self.window.WaitForCompletion()
            samples.append(1000.0 * (time.perf_counter() - start))
        return samples

    def save(self, path):
        grab = vtkWindowToImageFilter()
        grab.SetInput(self.window)
        grab.ReadFrontBufferOff()
        grab.Update()
        writer = vtkPNGWriter()
        writer.SetFileName(path)
        writer.SetInputConnection(grab.GetOutputPort())
        writer.Write()


def time_libsss(args, scene_path, mode, out_png):
    command = [args.sss_render, "--scene", scene_path, "--repeat", str(args.frames + args.warmup), "--aa", "1",
               "--out", out_png]
    result = subprocess.run(command, capture_output=True, text=True, check=False)
    if result.returncode != 0:
        sys.exit(f"vtk_peer: sss-render failed ({mode}):\n{result.stderr}")
    match = re.search(r"frame: ([0-9.]+) ms median", result.stdout)
    renderer = re.search(r"renderer: (.*)", result.stdout)
    return float(match.group(1)), renderer.group(1) if renderer else "?"


def median(values):
    values = sorted(values)
    return values[len(values) // 2]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--sss-render", required=True)
    parser.add_argument("--volume", required=True, help="a headerless raw volume with dims in its name")
    parser.add_argument("--tf", default="bonsai", help="a libsss transfer-function preset")
    parser.add_argument("--size", default="1200x680")
    parser.add_argument("--yaw", type=float, default=30.0)
    parser.add_argument("--pitch", type=float, default=20.0)
    parser.add_argument("--fov", type=float, default=45.0)
    parser.add_argument("--step", type=float, default=0.5, help="ray step in voxels")
    parser.add_argument("--frames", type=int, default=5)
    parser.add_argument("--warmup", type=int, default=2)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--modes", default="emission-absorption,gradient,scattering")
    parser.add_argument("--json", required=True)
    parser.add_argument("--markdown", required=True)
    parser.add_argument("--images", help="folder for both programs' images")
    args = parser.parse_args()
    args.width, args.height = (int(v) for v in args.size.lower().split("x"))
    dims, args.kind = parse_raw_name(args.volume)

    work = tempfile.mkdtemp(prefix="vtk-peer-")
    images = args.images or work
    os.makedirs(images, exist_ok=True)
    tf_path = os.path.join(work, "tf.json")
    subprocess.run([args.sss_render, "--tf", args.tf, "--export-tf", tf_path], check=True, capture_output=True)
    with open(tf_path) as f:
        tf_json = json.load(f)
    image, voxel = load_image(args.volume, dims, args.kind)
    eye, target, distance = camera_setup(dims, args.yaw, args.pitch, args.fov, args.width / args.height)
    vtk_scene = VtkScene(args, image, voxel, tf_json, eye, target)
    vtk_version = vtkVersion.GetVTKVersion()
    has_scattering = hasattr(vtk_scene.mapper, "SetVolumetricScatteringBlending")

    records = []
    for mode in [m for m in args.modes.split(",") if m]:
        if mode == "scattering" and not has_scattering:
            print(f"vtk_peer: VTK {vtk_version} has no volumetric scattering; scattering skipped "
                  "(benchmarks/vtk-peer.sh --paraview uses ParaView 5.11's VTK 9.2)", file=sys.stderr)
            continue
        # VTK's mapper classifies each sample alone: libsss does the same here (its default,
        # pre-integration, costs 1.3x in emission-absorption at equal step and is more accurate).
        scene = {
            "version": 1,
            "volumes": [{"source": os.path.abspath(args.volume), "transferFunction": args.tf,
                         "options": {"shading": mode, "stepSize": args.step, "preintegration": False}}],
            "lights": [{"type": "directional", "direction": [-1, -1, -1]}],
            "camera": {"yaw": args.yaw, "pitch": args.pitch, "fovY": args.fov, "target": list(target),
                       "distance": distance},
            "output": {"width": args.width, "height": args.height, "antiAliasing": 1},
        }
        scene_path = os.path.join(work, f"{mode}.json")
        with open(scene_path, "w") as f:
            json.dump(scene, f)
        vtk_scene.set_mode(mode)
        vtk_medians, sss_medians = [], []
        renderer = "?"
        for repeat in range(args.repeats):
            vtk_medians.append(median(vtk_scene.time_frames(args.warmup, args.frames)))
            sss_png = os.path.join(images, f"libsss-{mode}.png")
            ms, renderer = time_libsss(args, scene_path, mode, sss_png)
            sss_medians.append(ms)
            print(f"{mode} repeat {repeat + 1}: VTK {vtk_medians[-1]:.1f} ms, libsss {ms:.1f} ms", file=sys.stderr)
        vtk_png = os.path.join(images, f"vtk-{mode}.png")
        vtk_scene.save(vtk_png)
        cov_vtk, cov_sss = coverage_of_png(vtk_png), coverage_of_png(sss_png)
        records.append({
            "mode": mode, "volume": os.path.basename(args.volume), "width": args.width, "height": args.height,
            "step_voxels": args.step, "vtk_ms": vtk_medians, "libsss_ms": sss_medians,
            "vtk_ms_median": median(vtk_medians), "libsss_ms_median": median(sss_medians),
            "ratio": median(sss_medians) / median(vtk_medians),
            "coverage_vtk": round(cov_vtk, 4), "coverage_libsss": round(cov_sss, 4),
        })
    report = {"renderer": renderer, "vtk": vtk_version, "records": records,
              "date": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())}
    with open(args.json, "w") as f:
        json.dump(report, f, indent=2)
    lines = [f"# libsss against VTK {vtk_version} (vtkGPUVolumeRayCastMapper)", "",
             f"{os.path.basename(args.volume)}, {args.width} x {args.height}, step {args.step} voxel, "
             f"tf {args.tf}, yaw {args.yaw} pitch {args.pitch}; {renderer}; medians of {args.frames} frames "
             f"after {args.warmup} warm-up, {args.repeats} interleaved repeats ({report['date']}).", "",
             "| mode | libsss ms | VTK ms | ratio | coverage libsss / VTK |", "|---|---|---|---|---|"]
    for r in records:
        lines.append(f"| {r['mode']} | {'-'.join(f'{v:.0f}' for v in sorted(r['libsss_ms']))} | "
                     f"{'-'.join(f'{v:.0f}' for v in sorted(r['vtk_ms']))} | {r['ratio']:.2f}x | "
                     f"{r['coverage_libsss']:.3f} / {r['coverage_vtk']:.3f} |")
    lines += ["", "ratio: libsss median / VTK median (< 1: libsss is faster). A scattering frame in libsss "
              "reuses its light volume (built before the timed frames); VTK traces shadow rays every frame."]
    with open(args.markdown, "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
