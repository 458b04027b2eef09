"""Placement and pictures, against the command line: `apart place`'s JSON, and the files
`apart partition --svg/--png` and `apart sequence --glb/--html` write, byte for byte."""

from __future__ import annotations

import subprocess
from fractions import Fraction

import numpy as np
import pytest

import apart
from conftest import EXAMPLES, REPO, apart_bin


def cli_files(*args: str) -> None:
    exe = apart_bin()
    if not exe.is_file():
        pytest.fail(f"the apart binary is not at {exe}: run `cargo build --release` or set APART_BIN")
    r = subprocess.run([str(exe), *args, "--quiet"], capture_output=True, text=True, cwd=REPO,
                       timeout=600)
    assert r.returncode in (0, 2), r.stderr


def same_candidates(result, j):
    assert result.moving == j["moving"] and list(result.fixed) == j["fixed"]
    assert result.cost_kind == j["cost_kind"] and len(result) == len(j["candidates"])
    for c, t in zip(result, j["candidates"]):
        assert c.exact_translation == tuple(Fraction(s) for s in t["exact_translation"])
        assert np.allclose(c.translation, t["translation"])
        assert list(c.exact_rotation) == t["exact_rotation"]
        assert c.cost == pytest.approx(t["cost"])
        d = c.to_dict()
        for key in ["translation", "exact_translation", "rotation_deg", "exact_rotation", "cost"]:
            assert d[key] == t[key], key


@pytest.mark.parametrize("example,part,kwargs,flags", [
    ("peg-in-the-hole", "red", {}, []),
    ("peg-in-the-hole", "blue", dict(target=(0, 0, 30), candidates=3),
     ["--target", "0,0,30", "--candidates", "3"]),
    ("hinge", "bolt", dict(weight=0.3, dtheta=90), ["--weight", "0.3", "--dtheta", "90"]),
])
def test_place_matches_the_command_line(example, part, kwargs, flags, cli):
    path = EXAMPLES / example
    result = apart.place(path, part, **kwargs)
    code, j = cli("place", str(path), part, *flags)
    assert code == (0 if j["candidates"] else 2)
    assert result.found == bool(j["candidates"])
    same_candidates(result, j)
    # The same through a loaded assembly.
    again = apart.load(path).place(part, **kwargs)
    same_candidates(again, j)
    assert "PlaceResult" in repr(result)


def test_place_with_a_box_of_translations_and_clearance(cli):
    path = EXAMPLES / "peg-in-the-hole"
    result = apart.place(path, "red", translations=(-50, -50, -50, 50, 50, 50), clearance=0.5)
    code, j = cli("place", str(path), "red", "--translations", "-50,-50,-50,50,50,50",
                  "--clearance", "0.5")
    same_candidates(result, j)


def test_place_arguments_are_checked():
    asm = apart.load(EXAMPLES / "peg-in-the-hole")
    for bad in [dict(candidates=0), dict(dtheta=0), dict(weight=1.5), dict(target=(1, 2)),
                dict(region=(1, 0, 0, 0, 1, 1)), dict(region=(0,) * 6, translations=(0,) * 6),
                dict(clearance=-1), dict(bases=[(45, 0)])]:
        with pytest.raises(apart.InputError):
            asm.place("red", **bad)
    with pytest.raises(apart.InputError):
        asm.place("no such part")


@pytest.mark.parametrize("fmt,projection", [("svg", "equal-area"), ("png", "orthographic")])
def test_render_is_the_command_lines_picture(tmp_path, fmt, projection):
    path = EXAMPLES / "split-star"
    ours, theirs = tmp_path / f"ours.{fmt}", tmp_path / f"cli.{fmt}"
    apart.load(path).render(ours, projection=projection)
    cli_files("partition", str(path), f"--{fmt}", str(theirs), "--projection", projection)
    assert ours.read_bytes() == theirs.read_bytes()
    assert ours.stat().st_size > 1000


def test_render_checks_its_arguments(tmp_path):
    asm = apart.load(EXAMPLES / "split-star")
    with pytest.raises(apart.InputError):
        asm.render(tmp_path / "x.jpg")
    with pytest.raises(apart.InputError):
        asm.render(tmp_path / "x.svg", projection="mercator")
    with pytest.raises(apart.InputError):
        apart.load(EXAMPLES / "sheet-metal" / "cube.off").render(tmp_path / "x.svg")


@pytest.mark.parametrize("example", ["peg-in-the-hole", "hinge"])
def test_sequence_glb_and_html_are_the_command_lines(tmp_path, example):
    path = EXAMPLES / example
    plan = apart.load(path).sequence()
    plan.to_glb(tmp_path / "ours.glb")
    plan.to_html(tmp_path / "ours.html")
    cli_files("sequence", str(path), "--glb", str(tmp_path / "cli.glb"),
              "--html", str(tmp_path / "cli.html"))
    assert (tmp_path / "ours.glb").read_bytes() == (tmp_path / "cli.glb").read_bytes()
    assert (tmp_path / "ours.html").read_bytes() == (tmp_path / "cli.html").read_bytes()
    assert (tmp_path / "ours.glb").read_bytes()[:4] == b"glTF"


def test_a_stopped_plan_has_no_pictures(tmp_path):
    def stop(phase, done, total):
        raise apart.Stop

    plan = apart.load(EXAMPLES / "split-star").sequence(progress=stop)
    assert not plan.complete
    with pytest.raises(apart.ApartError):
        plan.to_glb(tmp_path / "x.glb")
