"""trimesh Trimesh and Scene objects as input."""

from __future__ import annotations

import numpy as np
import pytest

import apart
from conftest import EXAMPLES, read_off, solution_set

try:
    import trimesh
except ImportError:  # pragma: no cover - CI installs trimesh
    trimesh = None

pytestmark = pytest.mark.skipif(trimesh is None, reason="trimesh is not installed (pip install trimesh)")


def test_two_trimesh_boxes():
    a = trimesh.creation.box(extents=(1, 1, 1))
    b = trimesh.creation.box(extents=(1, 1, 1))
    b.apply_translation((2, 0, 0))
    asm = apart.Assembly.from_trimesh({"a": a, "b": b})
    assert asm.parts == ["a", "b"] and asm.valid
    assert asm.separate("a", "b").separable


def test_scene_nodes_are_parts_with_their_transforms():
    scene = trimesh.Scene()
    box = trimesh.creation.box(extents=(1, 1, 1))
    scene.add_geometry(box, node_name="low", geom_name="box")
    shifted = np.eye(4)
    shifted[:3, 3] = (0, 0, 1)  # stacked on top: face contact
    scene.add_geometry(box, node_name="high", geom_name="box", transform=shifted)
    asm = apart.Assembly.from_meshes(scene)
    assert sorted(asm.parts) == ["high", "low"] and asm.valid
    report = asm.check()
    boxes = {p.name: p.bbox for p in report.parts}
    assert boxes["high"][0][2] == pytest.approx(0.5) and boxes["low"][1][2] == pytest.approx(0.5)
    up = asm.partition(direction=(0, 0, 1))
    assert ("high",) in up.moving


def test_split_star_through_trimesh_matches_files():
    folder = EXAMPLES / "split-star"
    meshes = []
    for path in sorted(folder.glob("*.off")):
        v, f = read_off(path)
        meshes.append((path.stem, trimesh.Trimesh(v, f, process=False)))
    asm = apart.Assembly.from_trimesh(meshes)
    assert solution_set(asm.partition()) == solution_set(apart.load(folder).partition())
