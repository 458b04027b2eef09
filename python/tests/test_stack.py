"""Stacking, against the command line's JSON."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

import apart
from conftest import EXAMPLES


@pytest.mark.parametrize("part,count,extra", [
    ("cube", 4, []),
    ("channel", 3, ["--weight", "0.2"]),
])
def test_stack_matches_the_command_line(part, count, extra, cli):
    path = EXAMPLES / "sheet-metal" / f"{part}.off"
    kwargs = {"weight": float(extra[1])} if extra else {}
    plan = apart.stack(path, count, **kwargs)
    code, j = cli("stack", str(path), "--count", str(count), *extra)
    assert code == (0 if j["complete"] else 2)
    assert plan.complete == j["complete"] and len(plan) == len(j["placements"])
    assert plan.stack_height == pytest.approx(j["stack_height"])
    for p, t in zip(plan, j["placements"]):
        assert p.exact_translation == tuple(Fraction(s) for s in t["exact_translation"])
        assert np.allclose(p.translation, t["translation"])
        for key in ["index", "exact_rotation", "stage", "contacts", "examined"]:
            assert p.to_dict()[key] == t[key], key


def test_stacked_cubes_do_not_overlap_and_rest_on_something():
    plan = apart.stack(EXAMPLES / "sheet-metal" / "cube.off", 5, floor_z=1.0)
    asm = apart.load(EXAMPLES / "sheet-metal" / "cube.off")
    lo, hi = asm.check().parts[0].bbox
    boxes = [(lo + p.translation, hi + p.translation) for p in plan]
    assert plan.complete and len(boxes) == 5
    for a_lo, a_hi in boxes:
        assert a_lo[2] >= 1.0 - 1e-9  # above the floor
    for (a_lo, a_hi), (b_lo, b_hi) in [(x, y) for i, x in enumerate(boxes) for y in boxes[i + 1:]]:
        overlap = np.minimum(a_hi, b_hi) - np.maximum(a_lo, b_lo)
        assert (overlap <= 1e-9).any()  # interiors disjoint
    for p in plan:
        assert any(c["supports"] for c in p.contacts)


def test_stack_arguments_are_checked():
    cube = EXAMPLES / "sheet-metal" / "cube.off"
    for bad in [dict(count=0), dict(count=1001), dict(weight=2), dict(dtheta=0),
                dict(floor=(1, 0, 0, 1)), dict(bases=[(45, 0)]), dict(clearance=-1)]:
        with pytest.raises(apart.InputError):
            apart.stack(cube, **bad)
    with pytest.raises(apart.InputError):
        apart.load(EXAMPLES / "hinge").stack()  # three parts: which one?
