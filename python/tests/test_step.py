"""STEP assemblies: real STEP files made by build123d in the test, written, read back with
apart.load, and checked against the generator's numbers (part count, names, placement,
volume, units) and against the pin/hole guarantee of apart.step's tessellation.

Needs OCP (`pip install './python[step]'`) and build123d; without them these tests say
they are skipped and why (pytest -rs). The test of the message for a missing OCP runs
always."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys

import numpy as np
import pytest

import apart
from conftest import REPO, apart_bin


def test_a_missing_ocp_is_a_clear_import_error(tmp_path, monkeypatch):
    path = tmp_path / "x.step"
    path.write_text("ISO-10303-21;")
    monkeypatch.setitem(sys.modules, "OCP", None)  # import OCP now raises ImportError
    with pytest.raises(ImportError, match=r"pip install './python\[step\]'"):
        apart.load(path)


def test_step_options_apply_to_step_files_only():
    with pytest.raises(apart.InputError, match="STEP"):
        apart.load(REPO / "examples" / "split-star", chordal_tolerance=0.1)


def test_the_command_line_names_the_install_command_without_a_python_for_step(tmp_path):
    exe = apart_bin()
    if not exe.is_file():
        pytest.fail(f"the apart binary is not at {exe}")
    path = tmp_path / "gearbox.step"
    path.write_text("ISO-10303-21;")
    env = dict(os.environ, APART_PYTHON=str(tmp_path / "no-such-python"))
    r = subprocess.run([str(exe), "check", str(path)], capture_output=True, text=True, env=env)
    assert r.returncode == 1, r.stderr
    assert str(path) in r.stderr and "pip install './python[step]'" in r.stderr, r.stderr
    assert "panicked" not in r.stderr and "Traceback" not in r.stderr, r.stderr


def test_the_command_line_names_a_step_file_it_cannot_read(tmp_path):
    """With this Python (the package, with or without OCP): a file that is no STEP file
    is an error naming it, or, without OCP, the install command."""
    exe = apart_bin()
    if not exe.is_file():
        pytest.fail(f"the apart binary is not at {exe}")
    path = tmp_path / "gearbox.step"
    path.write_text("ISO-10303-21;")
    env = dict(os.environ, APART_PYTHON=sys.executable)
    r = subprocess.run([str(exe), "check", str(path)], capture_output=True, text=True, env=env)
    assert r.returncode == 1, r.stderr
    assert str(path) in r.stderr, r.stderr
    try:
        import OCP  # noqa: F401
        assert "not a STEP file OpenCASCADE can read" in r.stderr, r.stderr
    except ImportError:
        assert "pip install './python[step]'" in r.stderr, r.stderr


OCP = pytest.importorskip("OCP", reason="OCP is not installed (pip install './python[step]')")
bd = pytest.importorskip("build123d", reason="build123d is not installed (pip install build123d)")
from apart import step as apart_step  # noqa: E402


def mesh_volume(v, f):
    return float(np.einsum("ij,ij->i", v[f[:, 0]], np.cross(v[f[:, 1]], v[f[:, 2]])).sum() / 6)


def closed(f):
    e = np.sort(np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]]), axis=1)
    _, counts = np.unique(e, axis=0, return_counts=True)
    return bool(np.all(counts == 2))


def min_distance_to_z_axis(v, f):
    """The smallest distance from the z axis to any triangle, in the xy projection (its
    edges' distances to the origin; no triangle of these parts surrounds the axis)."""
    p = v[f][:, :, :2]
    best = np.inf
    for i, j in ((0, 1), (1, 2), (2, 0)):
        a, b = p[:, i], p[:, j]
        d = b - a
        t = np.clip(-np.einsum("mi,mi->m", a, d) / np.maximum(np.einsum("mi,mi->m", d, d), 1e-300), 0, 1)
        q = a + t[:, None] * d
        best = min(best, float(np.sqrt((q ** 2).sum(axis=1)).min()))
    return best


def pin_in_block(path, pin_radius, hole_radius=3.0, turn_deg=17.0):
    """A 20 x 20 x 10 block (centred) with a through hole along z, and a pin of length 16
    in it, turned about its axis so that its tessellation's phase differs."""
    block = bd.Box(20, 20, 10) - bd.Cylinder(hole_radius, 10)
    block.label = "block"
    pin = bd.Cylinder(pin_radius, 16).rotate(bd.Axis.Z, turn_deg)
    pin = pin.moved(bd.Location((0, 0, 3)))
    pin.label = "pin"
    asm = bd.Compound(children=[block, pin], label="pinbox")
    bd.export_step(asm, str(path))
    return block, pin


@pytest.mark.parametrize("pin_radius", [3.0, 2.9])
def test_a_pin_in_its_hole(tmp_path, pin_radius):
    path = tmp_path / "pinbox.step"
    block, pin = pin_in_block(path, pin_radius)
    ct = 0.05
    s = apart_step.read(path, chordal_tolerance=ct)
    assert [p.name for p in s.parts] == ["block", "pin"]
    assert s.units == "mm" and s.chordal_tolerance == ct and s.concave_faces == 1
    b, p = s.parts
    for part, shape in ((b, block), (p, pin)):
        assert closed(part.faces), part.name
        # Volume within the chordal bound: the curved area times twice the tolerance.
        curved = sum(f.area for f in shape.faces() if f.geom_type != bd.GeomType.PLANE)
        assert abs(mesh_volume(part.vertices, part.faces) - shape.volume) <= 2.1 * ct * curved
        assert mesh_volume(part.vertices, part.faces) <= shape.volume + 1e-9  # inside the solid
    # Placement: the pin spans z in [-5, 11], the block [-5, 5].
    assert np.allclose(p.vertices[:, 2].min(), -5) and np.allclose(p.vertices[:, 2].max(), 11)
    assert np.allclose(b.vertices.min(axis=0), [-10, -10, -5])
    # The guarantee: the pin's mesh inside its cylinder, the block's mesh outside the hole.
    assert np.sqrt((p.vertices[:, :2] ** 2).sum(axis=1)).max() <= pin_radius * (1 + 1e-12)
    assert min_distance_to_z_axis(b.vertices, b.faces) >= 3.0 * (1 - 1e-12)
    # ... by at most about the chordal tolerance away from it.
    assert min_distance_to_z_axis(b.vertices, b.faces) <= 3.0 + 1.1 * ct
    # So apart finds no overlap, and the pin leaves along +z and -z.
    asm = apart.load(path, chordal_tolerance=ct)
    assert asm.parts == ["block", "pin"]
    report = asm.check()
    assert report.valid, report.problems
    moves = {(s.moving, s.exact_direction) for s in asm.partition()}
    assert (("pin",), (0, 0, 1)) in moves and (("pin",), (0, 0, -1)) in moves


def test_a_pin_and_its_hole_moved_and_turned_together(tmp_path):
    """The hole's axis is taken in the placed part (here along y, off the origin)."""
    path = tmp_path / "moved.step"
    loc = bd.Location((30, 5, -7), (90, 0, 0))
    block = (bd.Box(20, 20, 10) - bd.Cylinder(3, 10)).moved(loc)
    block.label = "block"
    pin = bd.Cylinder(3, 16).rotate(bd.Axis.Z, 17).moved(bd.Location((0, 0, 3))).moved(loc)
    pin.label = "pin"
    bd.export_step(bd.Compound(children=[block, pin], label="moved"), str(path))
    asm = apart.load(path, chordal_tolerance=0.05)
    report = asm.check()
    assert report.valid, report.problems
    moves = {(x.moving, x.exact_direction) for x in asm.partition()}
    assert (("pin",), (0, 1, 0)) in moves and (("pin",), (0, -1, 0)) in moves


def test_a_drilled_hole_with_a_conical_tip_and_its_pin(tmp_path):
    """A blind hole ending in a cone (to its apex) and a pin of the same shape seated in
    it, turned against it: the cone's concave face is moved off the axis too (its apex
    stays), so the two do not overlap, and the pin leaves along +z only."""
    path = tmp_path / "drilled.step"
    hole = bd.Cylinder(3, 5).moved(bd.Location((0, 0, 2.5))) + bd.Cone(0, 3, 3).moved(bd.Location((0, 0, -1.5)))
    block = bd.Box(20, 20, 10) - hole
    block.label = "block"
    pin = (bd.Cylinder(3, 10).moved(bd.Location((0, 0, 5)))
           + bd.Cone(0, 3, 3).moved(bd.Location((0, 0, -1.5)))).rotate(bd.Axis.Z, 17)
    pin.label = "pin"
    bd.export_step(bd.Compound(children=[block, pin], label="drilled"), str(path))
    s = apart_step.read(path, chordal_tolerance=0.05)
    assert s.concave_faces == 2  # the hole's cylinder and cone
    assert all(closed(p.faces) for p in s.parts)
    asm = apart.load(path, chordal_tolerance=0.05)
    report = asm.check()
    assert report.valid, report.problems
    moves = {(x.moving, x.exact_direction) for x in asm.partition()}
    assert moves == {(("pin",), (0, 0, 1)), (("block",), (0, 0, -1))}


def test_planar_faces_keep_the_b_rep_vertices(tmp_path):
    path = tmp_path / "blocks.step"
    a = bd.Box(10, 20, 30)
    a.label = "plain"
    c = bd.Box(10, 10, 10) - bd.Cylinder(2, 10)
    c = c.moved(bd.Location((30, 0, 0)))
    c.label = "holed"
    bd.export_step(bd.Compound(children=[a, c], label="blocks"), str(path))
    s = apart_step.read(path, chordal_tolerance=0.01)
    plain, holed = s.parts
    corners = {(x, y, z) for x in (-5.0, 5.0) for y in (-10.0, 10.0) for z in (-15.0, 15.0)}
    assert len(plain.vertices) == 8 and len(plain.faces) == 12
    assert {tuple(v) for v in plain.vertices} == corners
    # The holed block's vertices lie on its B-rep edges: the square's edges or the hole's
    # circles (at z = +-5), none inside a face.
    v = holed.vertices - [30, 0, 0]
    assert np.all(np.isclose(np.abs(v[:, 2]), 5))
    r = np.sqrt((v[:, :2] ** 2).sum(axis=1))
    on_square = np.isclose(np.abs(v[:, 0]), 5) | np.isclose(np.abs(v[:, 1]), 5)
    on_circle = (r >= 2 - 1e-9) & (r <= 2 + 0.011)
    assert np.all(on_square | on_circle)


def test_a_nested_assembly_is_placed_and_named(tmp_path):
    path = tmp_path / "cart.step"
    axle = bd.Cylinder(1, 20, rotation=(0, 90, 0))
    axle.label = "axle"
    wheels = []
    for x in (-8.0, 8.0):
        w = bd.Cylinder(5, 2, rotation=(0, 90, 0)).moved(bd.Location((x, 0, 0)))
        w.label = "wheel"
        wheels.append(w)
    axles = []
    for y in (0.0, 30.0):
        sub = bd.Compound(children=[axle.moved(bd.Location()), *(w.moved(bd.Location()) for w in wheels)],
                          label="axle set")
        axles.append(sub.moved(bd.Location((0, y, 7))))
    bd.export_step(bd.Compound(children=axles, label="cart"), str(path))
    s = apart_step.read(path)
    names = [p.name for p in s.parts]
    assert len(names) == 6 and len(set(names)) == 6
    assert sorted(n.split("-")[0] for n in names) == ["axle", "axle", "wheel", "wheel", "wheel", "wheel"]
    assert all(n == apart_step._safe(n) for n in names)
    centres = sorted(tuple(np.round((p.vertices.min(axis=0) + p.vertices.max(axis=0)) / 2, 6))
                     for p in s.parts)
    expected = sorted([(0.0, y, 7.0) for y in (0.0, 30.0)]
                      + [(x, y, 7.0) for x in (-8.0, 8.0) for y in (0.0, 30.0)])
    # (A tessellated cylinder's box is off its axis by at most the chordal tolerance.)
    assert np.allclose(centres, expected, atol=s.chordal_tolerance)
    for p in s.parts:
        assert closed(p.faces)
        assert len(p.path) == 2  # the axle set's instance, then the part's
    wheel = next(p for p in s.parts if p.name.startswith("wheel"))
    # Volume within the chordal bound (a wheel is a convex cylinder: chords inside).
    exact = math.pi * 25 * 2
    area = 2 * math.pi * 5 * 2
    assert exact - 2.1 * s.chordal_tolerance * area <= mesh_volume(wheel.vertices, wheel.faces) <= exact


@pytest.mark.parametrize("unit,symbol,mm", [("INCH", "in", 25.4), ("M", "m", 1000.0)])
def test_units_are_converted(tmp_path, unit, symbol, mm):
    """A 2 x 3 x 4 box written by OpenCASCADE's STEP writer in inches or metres (the file
    holds those numbers) reads back in millimetres, or in the file's unit with units=."""
    from OCP.Interface import Interface_Static
    from OCP.STEPControl import STEPControl_AsIs, STEPControl_Writer

    path = tmp_path / f"box-{symbol}.step"
    box = bd.Box(2 * mm, 3 * mm, 4 * mm)  # build123d works in millimetres
    writer = STEPControl_Writer()
    assert Interface_Static.SetCVal_s("write.step.unit", unit)
    try:
        writer.Transfer(box.wrapped, STEPControl_AsIs)
        writer.Write(str(path))
    finally:
        Interface_Static.SetCVal_s("write.step.unit", "MM")
    text = path.read_text()
    assert ("CONVERSION_BASED_UNIT('INCH'" in text) if symbol == "in" else ("SI_UNIT($,.METRE.)" in text)
    assert "CARTESIAN_POINT('',(-1.,-1.5,-2.))" in text  # the file's own numbers
    native = apart_step.read(path, units=symbol)
    ext = native.parts[0].vertices.max(axis=0) - native.parts[0].vertices.min(axis=0)
    assert native.units == symbol and np.allclose(ext, [2, 3, 4])
    in_mm = apart_step.read(path)
    ext = in_mm.parts[0].vertices.max(axis=0) - in_mm.parts[0].vertices.min(axis=0)
    assert in_mm.units == "mm" and np.allclose(ext, np.array([2, 3, 4]) * mm)
    # The assembly states the unit, as the command line's --units does.
    report = apart.load(path, units=symbol).check()
    assert report.to_dict()["units"] == symbol
    lo, hi = report.parts[0].bbox
    assert np.allclose(hi - lo, [2, 3, 4], rtol=1e-6)


def test_python_m_apart_step_writes_a_folder_the_command_line_reads(tmp_path, cli):
    path = tmp_path / "pinbox.step"
    pin_in_block(path, 2.9)
    out = tmp_path / "pinbox"
    r = subprocess.run([sys.executable, "-m", "apart.step", str(path), str(out),
                        "--chordal-tolerance", "0.05"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert (out / "assembly.json").is_file() and (out / "pin.off").is_file()
    code, j = cli("check", str(out))
    assert code == 0 and j["valid"], j
    assert [p["name"] for p in j["parts"]] == ["block", "pin"]
    # The folder holds the meshes apart.load made from the STEP file.
    direct = apart.load(path, chordal_tolerance=0.05).check().to_dict()
    assert [p["volume"] for p in j["parts"]] == [p["volume"] for p in direct["parts"]]
    code, j = cli("partition", str(out), "--all")
    assert code == 0
    moves = {(frozenset(s["moving"]), tuple(int(c) for c in s["exact_direction"]))
             for s in j["solutions"]}
    assert (frozenset(["pin"]), (0, 0, 1)) in moves and (frozenset(["pin"]), (0, 0, -1)) in moves


def step_cli(*args):
    """Runs `apart ARGS --json --quiet` with this Python as the STEP reader."""
    exe = apart_bin()
    if not exe.is_file():
        pytest.fail(f"the apart binary is not at {exe}")
    r = subprocess.run([str(exe), *args, "--json", "--quiet"], capture_output=True, text=True,
                       cwd=REPO, timeout=600, env=dict(os.environ, APART_PYTHON=sys.executable))
    assert r.stdout, r.stderr
    return r.returncode, json.loads(r.stdout)


SAME = ("assembly", "valid", "units", "grid", "parts", "problems")


def test_the_command_line_reads_a_step_file_as_apart_load_does(tmp_path):
    path = tmp_path / "pinbox.step"
    pin_in_block(path, 2.9)
    code, j = step_cli("check", str(path))
    direct = apart.load(path).check().to_dict()
    assert code == 0 and j["valid"], j
    assert [p["name"] for p in j["parts"]] == ["block", "pin"] and j["units"] == "mm"
    for key in SAME:
        assert j[key] == direct[key], key
    code, j = step_cli("partition", str(path), "--all")
    assert code == 0
    assert j["solutions"] == apart.load(path).partition(all=True).to_dict()["solutions"]
    code, j = step_cli("sequence", str(path))
    assert code == 0 and j["units"] == "mm"
    assert len(j["steps"]) == len(apart.load(path).sequence().to_dict()["steps"]) >= 1
    # The tessellation and the unit, as apart.load's options.
    code, j = step_cli("check", str(path), "--chordal-tolerance", "0.05", "--units", "in")
    direct = apart.load(path, chordal_tolerance=0.05, units="in").check().to_dict()
    assert code == 0 and j["units"] == "in"
    for key in SAME:
        assert j[key] == direct[key], key


def test_the_command_line_reads_a_nested_step_assembly(tmp_path):
    path = tmp_path / "cart.step"
    axle = bd.Cylinder(1, 20, rotation=(0, 90, 0))
    axle.label = "axle"
    wheels = []
    for x in (-8.0, 8.0):
        w = bd.Cylinder(5, 2, rotation=(0, 90, 0)).moved(bd.Location((x, 0, 0)))
        w.label = "wheel"
        wheels.append(w)
    axles = [bd.Compound(children=[axle.moved(bd.Location()), *(w.moved(bd.Location()) for w in wheels)],
                         label="axle set").moved(bd.Location((0, y, 7))) for y in (0.0, 30.0)]
    bd.export_step(bd.Compound(children=axles, label="cart"), str(path))
    code, j = step_cli("check", str(path), "--angular-tolerance", "0.3")
    direct = apart.load(path, angular_tolerance=0.3).check().to_dict()
    assert len(j["parts"]) == 6
    for key in SAME:
        assert j[key] == direct[key], key


def test_emit_prints_the_parts_alone_on_standard_output(tmp_path, monkeypatch, capfd):
    """What the reader prints while reading (OpenCASCADE's messages) goes to standard
    error: standard output holds the JSON the command line parses, and the
    coordinates are the very doubles apart.step.read gives."""
    path = tmp_path / "pinbox.step"
    pin_in_block(path, 2.9)
    real = apart_step.read

    def noisy(*args, **kwargs):
        os.write(1, b"*** a message of the kernel ***\n")
        print("and one of Python")
        return real(*args, **kwargs)

    monkeypatch.setattr(apart_step, "read", noisy)
    assert apart_step.emit([str(path), "--units", "cm"]) == 0
    out, err = capfd.readouterr()
    assert "a message of the kernel" in err and "one of Python" in err
    j = json.loads(out)
    s = real(path, units="cm")
    assert j["units"] == "cm" and j["name"] == s.name
    assert [p["name"] for p in j["parts"]] == [p.name for p in s.parts]
    for got, p in zip(j["parts"], s.parts):
        v = np.array(got["vertices"], dtype=np.uint64).view(np.float64).reshape(-1, 3)
        assert np.array_equal(v, p.vertices)
        assert np.array_equal(np.array(got["triangles"]).reshape(-1, 3), p.faces)
