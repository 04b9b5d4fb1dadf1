"""examples/python/render_numpy.py runs and writes its pictures, so the example cannot rot."""
import os
import pathlib
import subprocess
import sys

import numpy as np

import sss

EXAMPLE = pathlib.Path(__file__).resolve().parents[2] / "examples" / "python" / "render_numpy.py"


def test_render_numpy_example_writes_its_pictures(gl, out_dir):
    out = os.path.join(out_dir, "example")
    subprocess.run([sys.executable, str(EXAMPLE), "--out", out, "--size", "160x120"], check=True)
    for name in ("volume.png", "mesh.png"):
        image = sss.load_png(os.path.join(out, name))
        assert image.shape == (120, 160, 4)
        # Something was drawn: well over a tenth of the pixels are brighter than the background.
        assert (image[..., :3].max(axis=2) > 60).mean() > 0.1, name
    linear = sss.load_exr(os.path.join(out, "volume.exr"))
    assert linear.dtype == np.float32 and np.isfinite(linear).all()
