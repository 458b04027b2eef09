"""apart.disassemble: plans of several moves, against the command line and the
examples' known answers (each folder's expected.json, from its construction)."""

from __future__ import annotations

import json
import math
from fractions import Fraction

import pytest

import apart

from conftest import EXAMPLES


@pytest.mark.parametrize("example", ["keyhole", "l-slot", "drawer", "diagonal-two-move"])
def test_off_grid_examples_match_the_command_line_and_their_known_level(example, cli):
    want = json.loads((EXAMPLES / example / "expected.json").read_text())
    plan = apart.disassemble(EXAMPLES / example)
    code, j = cli("disassemble", str(EXAMPLES / example))
    assert code == 0 and plan.complete and plan.level == want["level"] == j["level"]
    assert len(plan) == len(j["moves"])
    for m, t in zip(plan, j["moves"]):
        assert m.moving == tuple(t["moving"])
        assert m.exact_direction == tuple(int(c) for c in t["exact_direction"])
        assert (m.distance == math.inf) == (t["distance"] == "infinity")
        if not m.to_infinity:
            assert m.distance == Fraction(t["distance"]) > 0
    # The first move is finite, the last of the first separation goes to infinity.
    assert not plan.moves[0].to_infinity and plan.moves[want["level"] - 1].to_infinity


def test_the_keyhole_moves_exactly():
    plan = apart.load(EXAMPLES / "keyhole").disassemble()
    first = plan.moves[0]
    assert first.moving == ("key",) and first.exact_direction == (-1, 0, 0)
    assert first.distance == Fraction(9)
    assert first.exact_positions["key"] == (Fraction(-9), Fraction(0), Fraction(0))
    assert list(first.positions["key"]) == [-9.0, 0.0, 0.0]
    assert plan.to_dict()["model"] == "free cone"


def test_a_voxel_puzzle_has_its_level_with_axes():
    want = json.loads((EXAMPLES / "voxel-level-6" / "expected.json").read_text())
    plan = apart.disassemble(EXAMPLES / "voxel-level-6", axes=True)
    assert plan.level == want["level"] and plan.complete and plan.model == "axes"
    assert all(m.exact_direction.count(0) == 2 for m in plan)


def test_bounds_are_stated_and_checked():
    plan = apart.disassemble(EXAMPLES / "l-slot", max_moves=1)
    assert not plan.complete and plan.level is None
    assert "no plan with at most 1 moves exists" in plan.verdict
    with pytest.raises(apart.InputError):
        apart.disassemble(EXAMPLES / "l-slot", max_states=0)
