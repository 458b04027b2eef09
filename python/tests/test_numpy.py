"""Assemblies from numpy arrays."""

from __future__ import annotations

import numpy as np
import pytest

import apart
from conftest import EXAMPLES, box, read_off, solution_set


def test_two_boxes_apart_are_separable():
    asm = apart.Assembly.from_meshes([("left", *box((0, 0, 0), (1, 1, 1))),
                                      ("right", *box((2, 0, 0), (3, 1, 1)))], name="two boxes")
    assert asm.valid and asm.parts == ["left", "right"] and asm.name == "two boxes"
    s = asm.separate("left", "right")
    assert s.separable
    # Every direction with x <= 0 is free, and more: over half the sphere.
    assert 0.5 < s.area_fraction < 1.0
    p = asm.partition()
    assert not p.interlocked and p.complete
    # Moving away from the other box (-x for left) is free; towards it is not.
    along = asm.partition(direction=(-1, 0, 0))
    assert ("left",) in along.moving
    towards = asm.partition(direction=(1, 0, 0))
    assert ("left",) not in towards.moving and ("right",) in towards.moving


def hollow_box():
    """A cube of side 3 with a closed cubic cavity of side 1 in its middle: the outer
    shell outward, the cavity's shell turned inside (faces reversed)."""
    v0, f0 = box((0, 0, 0), (3, 3, 3))
    v1, f1 = box((1, 1, 1), (2, 2, 2))
    return np.vstack([v0, v1]), np.vstack([f0, f1[:, ::-1] + len(v0)])


def test_a_box_sealed_in_a_cavity_is_interlocked():
    asm = apart.Assembly.from_meshes([("shell", *hollow_box()), ("core", *box((1, 1, 1), (2, 2, 2)))])
    assert asm.valid, asm.problems
    assert asm.partition().interlocked
    assert not asm.separate("core", "shell").separable
    plan = asm.sequence()
    assert plan.interlocked and not plan.complete and plan.stuck == [("shell", "core")]


def test_arrays_give_the_same_answer_as_files():
    folder = EXAMPLES / "split-star"
    names = [p.stem for p in sorted(folder.glob("*.off"))]
    meshes = {n: read_off(folder / f"{n}.off") for n in names}
    from_arrays = apart.Assembly.from_meshes(meshes)
    assert sorted(from_arrays.parts) == sorted(names)
    assert solution_set(from_arrays.partition()) == solution_set(apart.load(folder).partition())


def test_int32_faces_and_float32_vertices_are_accepted():
    v, f = box((0, 0, 0), (1, 1, 1))
    w, g = box((1, 0, 0), (2, 1, 1))
    asm = apart.Assembly.from_meshes([("a", v.astype(np.float32), f.astype(np.int32)),
                                      ("b", w.tolist(), g.tolist())])
    assert asm.valid
    # Face contact: sliding along the shared face is free.
    p = asm.partition()
    assert not p.interlocked
    assert {s.cell for s in p} >= {"face"}
