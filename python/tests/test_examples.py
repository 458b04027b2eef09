"""The API on the shipped examples, against the command line's JSON and published
answers."""

from __future__ import annotations

import itertools
import subprocess
import sys

import numpy as np
import pytest

import apart
from conftest import EXAMPLES, solution_set


@pytest.fixture(scope="module")
def star():
    return apart.load(EXAMPLES / "split-star")


def test_split_star_has_the_eight_published_motions(star, cli):
    p = star.partition()
    assert isinstance(p, apart.Partition) and p.complete and not p.interlocked
    # The published answer: eight isolated directions (±1, ±1, ±1), three parts each.
    assert len(p) == 8 and p.solution_count == 8
    assert {s.exact_direction for s in p} == set(itertools.product((1, -1), repeat=3))
    for s in p:
        assert s.cell == "vertex" and len(s.moving) == 3 and s.clearance_deg == 0.0
        assert np.allclose(s.direction, np.array(s.exact_direction) / np.sqrt(3))
    # d versus -d: the parts that stay along d are the parts that move along -d.
    by_dir = {s.exact_direction: set(s.moving) for s in p}
    for d, moving in by_dir.items():
        opposite = by_dir[tuple(-c for c in d)]
        assert moving | opposite == set(star.parts) and not moving & opposite
    code, j = cli("partition", str(EXAMPLES / "split-star"), "--all")
    assert code == 0
    assert solution_set(p) == solution_set(j["solutions"])
    assert [g.moving for g in p.groups] == [tuple(g["moving"]) for g in j["groups"]]
    assert p.to_dict()["solutions"] == j["solutions"]


@pytest.mark.parametrize("example", ["peg-in-the-hole", "split-star-3", "dovetail-and-cap", "hinge"])
def test_partition_matches_the_command_line(example, cli):
    p = apart.load(EXAMPLES / example).partition(all=True)
    code, j = cli("partition", str(EXAMPLES / example), "--all")
    assert code == (2 if j["interlocked"] else 0)
    assert p.interlocked == j["interlocked"]
    assert p.solution_count == j["solution_count"]
    assert solution_set(p) == solution_set(j["solutions"])
    for s, t in zip(p, j["solutions"]):
        assert s.clearance_deg == pytest.approx(t["clearance_deg"])
        assert np.allclose(s.direction, t["direction"])


def test_first_solution_is_one_of_all(cli):
    asm = apart.load(EXAMPLES / "peg-in-the-hole")
    first = asm.partition(first=True)
    code, j = cli("partition", str(EXAMPLES / "peg-in-the-hole"), "--first")
    assert code == 0 and len(first) >= 1
    assert solution_set(first) == solution_set(j["solutions"])
    # Each first solution is a solution of the full answer's moving sets.
    all_sets = {frozenset(g.moving) for g in asm.partition().groups}
    assert {frozenset(s.moving) for s in first} <= all_sets


def test_one_direction_matches_the_command_line(star, cli):
    d = star.partition(direction=(1, 1, 1))
    assert isinstance(d, apart.DirectionAnswer)
    code, j = cli("partition", str(EXAMPLES / "split-star"), "--direction", "1,1,1")
    assert code == 0
    assert d.exact_direction == (1, 1, 1) and d.cell == j["cell"] == "vertex"
    assert sorted(d.blocks) == sorted(tuple(b) for b in j["blocks"])
    assert [set(m) for m in d.moving] == [set(m) for m in j["moving"]]
    # A direction that is not one of the eight moves nothing.
    assert star.partition(direction=[1, 0, 0]).moving == []


def test_linked_rings_are_interlocked(cli):
    p = apart.load(EXAMPLES / "linked-rings").partition()
    code, j = cli("partition", str(EXAMPLES / "linked-rings"))
    assert code == 2 and j["interlocked"] is True
    assert p.interlocked and len(p) == 0 and p.complete


@pytest.mark.parametrize("example,base", [("tray-of-cubes", "tray"), ("hinge", None)])
def test_sequence_matches_the_command_line(example, base, cli):
    plan = apart.load(EXAMPLES / example).sequence(base=base)
    args = ["sequence", str(EXAMPLES / example)] + (["--base", base] if base else [])
    code, j = cli(*args)
    assert code == 0 and plan.complete and not plan.interlocked
    assert len(plan) == len(j["steps"]) == len(plan.parts) - 1
    for step, t in zip(plan, j["steps"]):
        assert step.moving == tuple(t["moving"])
        assert step.subassembly == tuple(t["subassembly"])
        assert step.exact_direction == tuple(int(c) for c in t["exact_direction"])
        assert step.cell == t["cell"] and step.depth == t["depth"]
    if base:
        assert all(base not in s.moving for s in plan)
    # Walked step by step, every part ends up alone: each step splits its subassembly.
    for step in plan:
        assert set(step.moving) < set(step.subassembly)
        assert set(step.staying) == set(step.subassembly) - set(step.moving)


@pytest.mark.parametrize("example,base", [("tray-of-cubes", "tray"), ("split-star", None)])
def test_first_sequence_matches_the_command_line(example, base, cli):
    plan = apart.load(EXAMPLES / example).sequence(base=base, first=True)
    args = ["sequence", "--first", str(EXAMPLES / example)] + (["--base", base] if base else [])
    code, j = cli(*args)
    assert code == 0 and plan.complete and j["full_searches"] == plan.to_dict()["full_searches"]
    assert [(s.moving, s.subassembly, s.exact_direction, s.cell) for s in plan] == [
        (tuple(t["moving"]), tuple(t["subassembly"]), tuple(int(c) for c in t["exact_direction"]),
         t["cell"]) for t in j["steps"]]
    assert len(plan) == len(plan.parts) - 1
    if base:
        assert all(base not in s.moving for s in plan)
    with pytest.raises(apart.InputError):
        apart.load(EXAMPLES / example).sequence(first=True, growth=True)


@pytest.mark.parametrize("ranking", ["auto", "full", "local"])
def test_sequence_rankings_match_the_command_line(ranking, cli):
    asm = apart.load(EXAMPLES / "tray-of-cubes")
    plan = asm.sequence(base="tray", ranking=ranking)
    code, j = cli("sequence", str(EXAMPLES / "tray-of-cubes"), "--base", "tray",
                  "--ranking", ranking)
    assert code == 0 and plan.complete and len(plan) == len(plan.parts) - 1
    assert [(s.moving, s.subassembly, s.exact_direction, s.cell, s.rule) for s in plan] == [
        (tuple(t["moving"]), tuple(t["subassembly"]), tuple(int(c) for c in t["exact_direction"]),
         t["cell"], t["rule"]) for t in j["steps"]]
    mine = plan.to_dict()
    for key in ("ranking", "pair_regions", "work", "full_searches"):
        assert mine[key] == j[key], key
    assert mine["ranking"] == ranking
    if ranking == "full":
        assert {s.rule for s in plan} == {"ranked"}
    if ranking == "local":
        assert all(s.rule != "ranked" for s in plan if len(s.subassembly) > 2)


def test_sequence_preferences_match_the_command_line(cli):
    asm = apart.load(EXAMPLES / "tray-of-cubes")
    plan = asm.sequence(base="tray", prefer_single=True, prefer_axes=True, growth=True)
    code, j = cli("sequence", str(EXAMPLES / "tray-of-cubes"), "--base", "tray",
                  "--prefer-single", "--prefer-axes", "--growth")
    assert code == 0
    assert [(s.moving, s.exact_direction) for s in plan] == [
        (tuple(t["moving"]), tuple(int(c) for c in t["exact_direction"])) for t in j["steps"]]
    assert [s.growth for s in plan] == pytest.approx([t["growth"] for t in j["steps"]])
    assert all(len(s.moving) == 1 for s in plan)


def test_separate_matches_the_command_line(cli):
    asm = apart.load(EXAMPLES / "dovetail-and-cap")
    s = apart.separate(asm, "tenon", "slot")
    code, j = cli("separate", str(EXAMPLES / "dovetail-and-cap"), "tenon", "slot")
    assert code == 0 and s.separable == j["separable"]
    assert s.area_fraction == pytest.approx(j["area_fraction"])
    assert s.best_exact_direction == tuple(int(c) for c in j["best"]["exact_direction"])
    assert s.isolated == [tuple(int(c) for c in d) for d in j["isolated"]]
    assert s.to_dict()["regions"] == j["regions"] and s.sliding == j["sliding"]
    # Leaving the other way round: the free directions are the opposite ones.
    back = asm.separate("slot", "tenon")
    assert back.area_fraction == pytest.approx(s.area_fraction)
    assert back.best_exact_direction == tuple(-c for c in s.best_exact_direction)


def test_check_matches_the_command_line(cli):
    for example in ["split-star", "ring-and-cone", "cad-seams"]:
        report = apart.load(EXAMPLES / example).check()
        code, j = cli("check", str(EXAMPLES / example))
        assert report.valid == j["valid"] and code == (0 if j["valid"] else 1)
        d = report.to_dict()
        for key in ["assembly", "valid", "grid", "parts", "problems", "repairs", "skipped_files"]:
            assert d[key] == j[key], key
        assert [p.name for p in report.parts] == [p["name"] for p in j["parts"]]


def test_tolerance_auto_matches_the_command_line(cli):
    folder = EXAMPLES / "cad-pin-in-hole"
    # Without a tolerance the pin and its hole overlap: planning refuses.
    with pytest.raises(apart.InvalidAssemblyError) as e:
        apart.load(folder).partition()
    assert e.value.part in ("pin", "block")
    asm = apart.load(folder, tolerance="auto")
    p = asm.partition(all=True)
    code, j = cli("partition", str(folder), "--tolerance", "auto", "--all")
    assert code == 0
    assert p.tolerance == j["tolerance"] and p.tolerance["auto"] is True
    assert solution_set(p) == solution_set(j["solutions"])
    assert [s.holds_without_tolerance for s in p] == [s["holds_without_tolerance"] for s in j["solutions"]]


def test_tolerance_with_units(cli):
    folder = EXAMPLES / "cad-seams"
    p = apart.load(folder, tolerance="5um", units="mm").partition(all=True)
    code, j = cli("partition", str(folder), "--tolerance", "5um", "--units", "mm", "--all")
    assert p.tolerance["eps"] == j["tolerance"]["eps"] == pytest.approx(0.005)
    assert p.units == j["units"] == "mm"
    assert solution_set(p) == solution_set(j["solutions"])


def test_results_read_well(star):
    p = star.partition()
    text = repr(p) + repr(p[0]) + repr(p.groups[0]) + repr(star)
    assert "8 solutions" in text and "vertex" in text and "split-star" in text
    d = p.to_dict()
    d["solutions"].clear()
    assert len(p.to_dict()["solutions"]) == 8  # to_dict is a copy


def test_the_readme_example_prints_the_eight_motions():
    readme = (EXAMPLES.parent / "README.md").read_text()
    section = readme[readme.index("## Python"):]
    code = section[section.index("```python\n") + 10:]
    code = code[:code.index("```")]
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       cwd=EXAMPLES.parent, timeout=300)
    assert r.returncode == 0, r.stderr
    lines = r.stdout.splitlines()
    assert len(lines) == 8
    seen = set()
    for line in lines:
        parts, direction = line.split(" move along ")
        assert len(parts.split(", ")) == 3
        seen.add(tuple(int(c) for c in direction.strip("()").split(", ")))
    assert seen == set(itertools.product((1, -1), repeat=3))
