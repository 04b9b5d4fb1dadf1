#!/usr/bin/env python3
# Topology and area of a volume's isosurfaces against the same trilinear field sampled 4x finer
# (docs/isosurfaces.md): for each iso value, with the raw marching-cubes surface (smoothing 0)
# and with the default smoothing, the area, the Euler characteristic V - E + F and the number of
# connected pieces, counted on the vertex indices.
# Usage: docs/isosurface-topology.py VOLUME.raw V1,V2,... (with the sss Python module importable,
# e.g. PYTHONPATH=build/python). Pick values that neither grid holds exactly (x.3 for 8-bit data):
# where a voxel equals the value, VTK puts several vertices at it.
import sys
import numpy as np, sss

FACTOR = 4


def shape(mesh):
    points = np.asarray(mesh.vertices, dtype=np.float64)
    triangles = np.asarray(mesh.indices).reshape(-1, 3)
    a, b, c = points[triangles[:, 0]], points[triangles[:, 1]], points[triangles[:, 2]]
    area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1).sum()
    edges = np.unique(np.sort(np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]]), axis=1), axis=0)
    used = np.unique(triangles)
    parent = np.arange(len(points))

    def root(x):
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x

    for u, v in edges:
        ru, rv = root(u), root(v)
        if ru != rv:
            parent[ru] = rv
    pieces = len({root(x) for x in used})
    return area, len(used) - len(edges) + len(triangles), pieces


def refined(data):
    for axis in range(3):
        m = data.shape[axis]
        x = np.arange((m - 1) * FACTOR + 1) / FACTOR
        low = np.minimum(np.floor(x).astype(int), m - 2)
        t = (x - low).reshape([-1 if k == axis else 1 for k in range(3)])
        data = np.take(data, low, axis=axis) * (1 - t) + np.take(data, low + 1, axis=axis) * t
    return np.ascontiguousarray(data.astype(np.float32))


volume = sss.Volume.load(sys.argv[1])
spacing = tuple(s / FACTOR for s in volume.spacing)
fine = sss.Volume(refined(np.asarray(volume.data, dtype=np.float64)), spacing=spacing)
print("| value | smoothing | area | 4x finer | ratio | Euler (4x finer) | pieces (4x finer) |")
print("|---:|---:|---:|---:|---:|---|---|")
for value in (float(v) for v in sys.argv[2].split(",")):
    for smoothing in (0, 15):
        c = shape(sss.extract_isosurface(volume, value, smoothing_iterations=smoothing))
        r = shape(sss.extract_isosurface(fine, value, smoothing_iterations=smoothing))
        print("| %g | %d | %.0f | %.0f | %.3f | %d (%d) | %d (%d) |" % (value, smoothing, c[0], r[0], c[0] / r[0], c[1], r[1], c[2], r[2]))
