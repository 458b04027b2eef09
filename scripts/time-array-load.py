#!/usr/bin/env python3
"""Times loading a large triangle mesh from numpy arrays (apart.Assembly.from_meshes).

A torus of about 200,000 triangles (R = 3, r = 1), given as float64 vertices and int64
faces, is loaded as a one-part assembly; the best of several runs is printed. It uses
the installed package:

    python scripts/time-array-load.py [TRIANGLES] [RUNS]
"""
import sys
import time

import numpy as np

import apart


def torus(triangles: int):
    """A closed torus of about `triangles` triangles (R = 3, r = 1)."""
    v_count = int(round((triangles / 2 / 2.5) ** 0.5))
    u_count = int(round(triangles / 2 / v_count))
    u = np.linspace(0, 2 * np.pi, u_count, endpoint=False)
    v = np.linspace(0, 2 * np.pi, v_count, endpoint=False)
    uu, vv = np.meshgrid(u, v, indexing="ij")
    x = (3 + np.cos(vv)) * np.cos(uu)
    y = (3 + np.cos(vv)) * np.sin(uu)
    z = np.sin(vv)
    verts = np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1)
    i, j = np.meshgrid(np.arange(u_count), np.arange(v_count), indexing="ij")
    a = i * v_count + j
    b = ((i + 1) % u_count) * v_count + j
    c = ((i + 1) % u_count) * v_count + (j + 1) % v_count
    d = i * v_count + (j + 1) % v_count
    faces = np.concatenate([np.stack([a, b, c], -1).reshape(-1, 3),
                            np.stack([a, c, d], -1).reshape(-1, 3)])
    return verts, faces


def main() -> None:
    triangles = int(sys.argv[1]) if len(sys.argv) > 1 else 200_000
    runs = int(sys.argv[2]) if len(sys.argv) > 2 else 5
    verts, faces = torus(triangles)
    times = []
    for _ in range(runs):
        t = time.perf_counter()
        asm = apart.Assembly.from_meshes([("torus", verts, faces)])
        times.append(time.perf_counter() - t)
    assert asm.valid, asm.problems
    print(f"{len(faces)} triangles, {len(verts)} vertices: best of {runs} "
          f"{min(times):.3f} s (all: {', '.join(f'{x:.3f}' for x in times)})")


if __name__ == "__main__":
    main()
