"""Hostile input: a partition of many loose parts is listed as the command line lists
it (bounded, every solution counted), the memory budget stops a call with apart's own
MemoryError and the interpreter carries on, and the compiled module refuses bad
arguments and arrays itself."""

from __future__ import annotations

import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import pytest

import apart
from apart import _apart
from conftest import EXAMPLES, box, solution_set


def loose_cubes(n: int):
    """An n x n x n lattice of unit cubes with unit gaps: no cube touches another."""
    parts = []
    for i in range(n):
        for j in range(n):
            for k in range(n):
                lo = np.array([2 * i, 2 * j, 2 * k], float)
                parts.append((f"c{i}{j}{k}", *box(lo, lo + 1)))
    return parts


def write_off_folder(folder: Path, parts) -> None:
    folder.mkdir(parents=True, exist_ok=True)
    for name, v, f in parts:
        lines = ["OFF", f"{len(v)} {len(f)} 0"]
        lines += [" ".join(repr(float(x)) for x in p) for p in v]
        lines += ["3 " + " ".join(str(int(i)) for i in t) for t in f]
        (folder / f"{name}.off").write_text("\n".join(lines) + "\n")


@pytest.fixture(scope="module")
def lattice(tmp_path_factory):
    """27 loose cubes, as arrays and as a folder the command line reads."""
    parts = loose_cubes(3)
    folder = tmp_path_factory.mktemp("loose") / "cubes"
    write_off_folder(folder, parts)
    return apart.Assembly.from_meshes(parts, name="cubes"), folder


def test_loose_cubes_are_listed_as_the_command_line_lists_them(lattice, cli):
    asm, folder = lattice
    p = asm.partition()
    everything = asm.partition(all=True)
    # Every solution counted, a bounded listing: 20 moving sets, 5 of each kind per set.
    assert p.complete and not p.interlocked
    assert p.solution_count == everything.solution_count == len(everything.solutions)
    assert p.moving_set_count == everything.moving_set_count == len(everything.groups) > 20
    assert p.truncated and not everything.truncated and p.limit == 20
    assert len(p.groups) == 20 and len(p.solutions) < p.solution_count
    for g in p.groups:
        assert g.listed <= 15 and g.solutions > g.listed
        kinds = [s.cell for s in p.solutions if s.moving == g.moving]
        assert len(kinds) == g.listed and all(kinds.count(k) <= 5 for k in set(kinds))
    assert solution_set(p) <= solution_set(everything)
    # Field for field the command line's default listing (and --all its whole one).
    code, j = cli("partition", str(folder))
    assert code == 0
    assert p.solution_count == j["solution_count"]
    assert p.moving_set_count == j["moving_set_count"] and j["limit"] == 20
    assert [g.to_dict() for g in p.groups] == j["groups"]
    assert solution_set(p) == solution_set(j["solutions"])
    assert p.to_dict()["truncated"] is j["truncated"] is True
    # Narrower and wider listings.
    small = asm.partition(limit=2, max_per_set=1)
    assert len(small.groups) == 2 and len(small) <= 6
    assert small.solution_count == p.solution_count


def test_all_takes_no_limit(lattice):
    asm, _ = lattice
    for bad in (dict(all=True, limit=3), dict(all=True, max_per_set=2), dict(limit=0),
                dict(max_per_set=-1)):
        with pytest.raises(apart.InputError):
            asm.partition(**bad)
    with pytest.raises(apart.InputError, match="limit"):
        asm._inner.partition_json(limit=-5)
    with pytest.raises(apart.InputError, match="all=True"):
        asm._inner.partition_json(all=True, max_per_set=1)


def test_many_loose_cubes_are_counted_not_listed(tmp_path, cli):
    """The hostile run, smaller: 512 loose cubes have 3.3 million solutions (35 s, and
    listing them all took the interpreter down); 216 have about half a million, counted
    in full and listed as the command line lists them."""
    parts = loose_cubes(6)
    asm = apart.Assembly.from_meshes(parts, name="many")
    p = asm.partition()
    assert p.complete and p.truncated
    assert len(p.groups) == 20 and len(p.solutions) <= 20 * 15
    assert p.solution_count > 400_000
    assert p.solution_count > sum(g.solutions for g in p.groups) > len(p.solutions)
    write_off_folder(tmp_path / "many", parts)
    code, j = cli("partition", str(tmp_path / "many"))
    assert code == 0
    assert p.solution_count == j["solution_count"]
    assert p.moving_set_count == j["moving_set_count"]
    assert [g.to_dict() for g in p.groups] == j["groups"]
    assert solution_set(p) == solution_set(j["solutions"])


@pytest.fixture
def budget():
    """Restores the default memory budget after a test that changes it."""
    yield
    apart.set_memory_budget("default")


def test_the_default_budget_is_the_command_lines(budget):
    d = _apart.DEFAULT_MEMORY_BUDGET
    assert d is None or apart.memory_budget() == d
    apart.set_memory_budget("2G")
    assert apart.memory_budget() == 2 << 30
    apart.set_memory_budget(None)
    assert apart.memory_budget() is None
    apart.set_memory_budget(64 << 20)
    assert apart.memory_budget() == 64 << 20
    assert apart.memory_in_use() > 0
    for bad in ("4X", "100K", -1, 1000, True, "nan", [1]):
        with pytest.raises(apart.InputError, match="memory budget"):
            apart.set_memory_budget(bad)


def test_a_planner_over_a_tiny_budget_stops_and_the_next_call_works(lattice, budget):
    asm, _ = lattice
    full = asm.partition(all=True)
    # Far below what the 27 cubes' motion space needs: the partition either stops
    # with what it found (the soft limit) or raises apart's MemoryError.
    apart.set_memory_budget(apart.memory_in_use() + (2 << 20))
    try:
        p = asm.partition(all=True)
    except apart.OutOfMemoryBudget as e:
        assert isinstance(e, MemoryError) and isinstance(e, apart.ApartError)
        assert str(e).startswith("out of memory budget (") and " during " in str(e)
        assert e.phase and e.detail
    else:
        assert p.status == "out of memory" and not p.complete
        assert p.stopped["by"] == "memory budget" and p.stopped["detail"]
        assert solution_set(p) <= solution_set(full)
    # A call that cannot stop (loading 512 cubes from arrays needs a few MiB) raises.
    apart.set_memory_budget(apart.memory_in_use() + (1 << 20))
    with pytest.raises(apart.OutOfMemoryBudget, match="during loading"):
        apart.Assembly.from_meshes(loose_cubes(8), name="more")
    # The interpreter carries on: with the default budget the same call answers in full.
    apart.set_memory_budget("default")
    again = asm.partition(all=True)
    assert again.complete and solution_set(again) == solution_set(full)


def test_a_motion_space_over_the_budget_is_refused_before_it_is_built(budget):
    asm = apart.Assembly.from_meshes(loose_cubes(6), name="cubes216")
    # Enough for the pair regions (about 40 MiB), not for the motion space of 216 cubes
    # (estimated at more than 100 MiB): refused, as the command line refuses it.
    apart.set_memory_budget(apart.memory_in_use() + (64 << 20))
    with pytest.raises(apart.OutOfMemoryBudget, match="the motion space needs at least") as e:
        asm.partition()
    assert e.value.phase == "motion space"
    with pytest.raises(apart.OutOfMemoryBudget, match="motion space"):
        asm.render(Path(tempfile.mkdtemp()) / "sphere.svg")


def test_the_budget_survives_in_a_fresh_interpreter():
    """A budget far too small for loading: the load raises, the process lives on and
    exits normally."""
    code = (
        "import apart, sys\n"
        f"sys.path.insert(0, {str(Path(__file__).parent)!r})\n"
        "from test_hostile import loose_cubes\n"
        "apart.set_memory_budget(apart.memory_in_use() + (1 << 20))\n"
        "try:\n"
        "    apart.Assembly.from_meshes(loose_cubes(5), name='x').partition(all=True)\n"
        "except MemoryError as e:\n"
        "    print('raised', type(e).__name__)\n"
        "else:\n"
        "    print('answered')\n"
        "apart.set_memory_budget('default')\n"
        f"print(len(apart.load({str(EXAMPLES / 'split-star')!r}).partition()))\n"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       timeout=600)
    assert r.returncode == 0, r.stderr
    lines = r.stdout.split()
    assert lines[-1] == "8", r.stdout
    assert "raised OutOfMemoryBudget" in r.stdout or "answered" in r.stdout


# ---------------------------------------------------------------------------
# The compiled module's own checks

LOAD = dict(grid_bits=_apart.DEFAULT_GRID_BITS, tolerance=None, tolerance_auto=False,
            strict=False, one_part_per_file=False, allow_outside=False, verify=False,
            units=None, progress=None, timeout=None)


@pytest.mark.parametrize("change,word", [
    (dict(timeout=float("nan")), "timeout"),
    (dict(timeout=-1.0), "timeout"),
    (dict(timeout=0.0), "timeout"),
    (dict(timeout=float("inf")), "timeout"),
    (dict(timeout=1e9), "timeout"),
    (dict(units="furlong"), "units"),
    (dict(grid_bits=-3), "grid_bits"),
    (dict(grid_bits=1000), "grid_bits"),
    (dict(tolerance=float("nan")), "tolerance"),
    (dict(tolerance=-1e-3), "tolerance"),
])
def test_direct_calls_check_their_arguments(change, word):
    path = str(EXAMPLES / "split-star")
    with pytest.raises(apart.InputError, match=word):
        _apart.load(path, **{**LOAD, **change})
    v, f = box((0, 0, 0), (1, 1, 1))
    parts = [("a", np.ascontiguousarray(v, "<f8").tobytes(), np.ascontiguousarray(f, "<i8").tobytes())]
    opts = {k: val for k, val in {**LOAD, **change}.items() if k != "allow_outside"}
    with pytest.raises(apart.InputError, match=word):
        _apart.from_meshes("x", parts, **opts)


def test_direct_planner_calls_check_their_arguments():
    star = apart.load(EXAMPLES / "split-star")._inner
    nan = float("nan")
    cases = [
        (lambda: star.partition_json(timeout=nan), "timeout"),
        (lambda: star.partition_json(timeout=-2.0), "timeout"),
        (lambda: star.partition_json(max_solutions=0), "max_solutions"),
        (lambda: star.partition_json(max_per_set=-1), "max_per_set"),
        (lambda: star.partition_json(direction=[nan, 0, 1]), "direction"),
        (lambda: star.partition_json(direction=[0, 0, 0]), "direction"),
        (lambda: star.sequence_json(base=None, first=False, prefer_single=False,
                                    prefer_connected=False, prefer_axes=False,
                                    max_depth=-1, growth=False, progress=None,
                                    timeout=None), "max_depth"),
        (lambda: star.sequence_json(base=None, first=False, prefer_single=False,
                                    prefer_connected=False, prefer_axes=False,
                                    max_depth=None, growth=False, progress=None,
                                    timeout=nan), "timeout"),
        (lambda: star.separate_json("red", "blue", progress=None, timeout=-1.0), "timeout"),
        (lambda: star.motion_space_picture(svg=True, orthographic=False, progress=None,
                                           timeout=nan), "timeout"),
    ]
    place = dict(target=[0.0, 0, 0], weight=None, floor_point=[0.0, 0, 0], region=None,
                 translations=None, dtheta=360.0, bases=None, clearance=None,
                 candidates=5, timeout=None)
    for change, word in [(dict(target=[nan, 0, 0]), "target"), (dict(weight=2.0), "weight"),
                         (dict(dtheta=0.0), "dtheta"), (dict(candidates=0), "candidates"),
                         (dict(candidates=-4), "candidates"), (dict(clearance=-1.0), "clearance"),
                         (dict(region=[1.0, 0, 0, 0, 1, 1]), "region"),
                         (dict(bases=[(7, 0)]), "bases"), (dict(timeout=nan), "timeout")]:
        cases.append((lambda c=change: star.place_json("red", **{**place, **c}), word))
    stack = dict(count=2, weight=0.5, floor=None, floor_z=0.0, max_height=None, dtheta=90.0,
                 bases=None, clearance=None, max_candidates=10, extrapolate=True,
                 progress=None, timeout=None)
    for change, word in [(dict(count=0), "count"), (dict(count=-1), "count"),
                         (dict(count=5000), "count"), (dict(weight=nan), "weight"),
                         (dict(floor=[0.0, 0, nan, 1]), "floor"), (dict(floor_z=nan), "floor_z"),
                         (dict(max_height=-1.0), "max_height"),
                         (dict(max_candidates=0), "max_candidates"),
                         (dict(timeout=0.0), "timeout")]:
        cases.append((lambda c=change: star.stack_json("red", **{**stack, **c}), word))
    for call, word in cases:
        with pytest.raises(apart.InputError, match=word):
            call()


# ---------------------------------------------------------------------------
# Arrays

def cube_arrays():
    return box((0, 0, 0), (1, 1, 1))


@pytest.mark.parametrize("make,word", [
    (lambda v, f: (v.astype(complex), f), "real numbers"),
    (lambda v, f: (v + 0j, f), "real numbers"),
    (lambda v, f: (v.astype(object) * (1 + 0j), f), "real numbers"),
    (lambda v, f: (v > 0, f), "real numbers"),
    (lambda v, f: (v.astype(str), f), "real numbers"),
    (lambda v, f: (np.where(np.arange(24).reshape(8, 3) == 4, np.nan, v), f), "vertex 1"),
    (lambda v, f: (np.where(np.arange(24).reshape(8, 3) == 23, np.inf, v), f), "vertex 7"),
    (lambda v, f: (v[:, :2], f), "n x 3"),
    (lambda v, f: (v.ravel(), f), "n x 3"),
    (lambda v, f: (v, f[:, :2]), "m x 3"),
    (lambda v, f: (v, np.where(f == 7, 8, f)), "not one of the 8 vertices"),
    (lambda v, f: (v, np.where(f == 7, -1, f)), "not one of the 8 vertices"),
    (lambda v, f: (v, f.astype(float) + 0.5), "integers"),
    (lambda v, f: (v, f.astype(complex)), "integers"),
    (lambda v, f: (v, f > 3), "integers"),
    (lambda v, f: (v, f.astype(np.uint64) + np.uint64(2**63)), "not one of"),
    (lambda v, f: (v, np.where(f == 7, 1e30, f)), "not one of"),
])
def test_arrays_that_are_not_real_meshes_are_refused(make, word):
    a, b = cube_arrays()
    other = box((2, 0, 0), (3, 1, 1))
    v, f = make(a, b)
    with pytest.raises(apart.InputError, match=word) as e:
        apart.Assembly.from_meshes([("bad", v, f), ("ok", *other)])
    assert e.value.part == "bad"


def test_a_complex_direction_is_refused():
    star = apart.load(EXAMPLES / "split-star")
    with pytest.raises(apart.InputError, match="direction"):
        star.partition(direction=np.array([1, 1, 1j]))
    with pytest.raises(apart.InputError, match="direction"):
        star.partition(direction=[float("nan"), 1, 1])
    with pytest.raises(apart.InputError, match="timeout"):
        star.partition(timeout=np.complex128(1 + 0j))


def test_no_complex_warning_reaches_the_user():
    a, b = cube_arrays()
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(apart.InputError):
            apart.Assembly.from_meshes([("c", a.astype(np.complex64), b)])
