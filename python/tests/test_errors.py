"""Bad input raises exceptions that carry file, part and element, and never crashes the
interpreter."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

import apart
from conftest import EXAMPLES, box


def test_missing_path_names_the_file(tmp_path):
    missing = tmp_path / "nothing-here"
    with pytest.raises(apart.InputError) as e:
        apart.load(missing)
    assert isinstance(e.value, ValueError)
    assert e.value.file == str(missing)
    assert "no such file" in str(e.value)


def open_box_off(path):
    v, f = box((0, 0, 0), (1, 1, 1))
    lines = ["OFF", f"{len(v)} {len(f) - 1} 0"]
    lines += [" ".join(str(c) for c in p) for p in v]
    lines += ["3 " + " ".join(str(i) for i in t) for t in f[:-1]]  # one face missing
    path.write_text("\n".join(lines) + "\n")


def test_open_mesh_file_names_file_part_and_element(tmp_path):
    open_box_off(tmp_path / "lid.off")
    v, f = box((2, 0, 0), (3, 1, 1))
    (tmp_path / "base.off").write_text(
        "OFF\n8 12 0\n" + "\n".join(" ".join(map(str, p)) for p in v) + "\n"
        + "\n".join("3 " + " ".join(map(str, t)) for t in f) + "\n")
    asm = apart.load(tmp_path, strict=True)
    assert not asm.valid
    errors = asm.check().errors
    assert errors and errors[0].file == str(tmp_path / "lid.off")
    assert errors[0].part == "lid" and errors[0].element
    with pytest.raises(apart.InvalidAssemblyError) as e:
        asm.partition()
    assert e.value.file == str(tmp_path / "lid.off") and e.value.part == "lid"
    assert e.value.element == errors[0].element
    assert [p.message for p in e.value.problems if p.severity == "error"] == [p.message for p in errors]


def test_open_mesh_from_arrays_names_part_and_element():
    v, f = box((0, 0, 0), (1, 1, 1))
    asm = apart.Assembly.from_meshes([("open", v, f[:-1]), ("other", *box((2, 0, 0), (3, 1, 1)))],
                                     strict=True)
    assert not asm.valid
    err = asm.check().errors[0]
    assert err.part == "open" and err.element and err.file is None
    with pytest.raises(apart.InvalidAssemblyError) as e:
        asm.sequence()
    assert e.value.part == "open" and e.value.element == err.element and e.value.file is None
    assert "apart-python" not in str(e.value)  # no temporary path leaks


@pytest.mark.parametrize("vertices,faces,element", [
    ([["a", "b", "c"]] * 4, [[0, 1, 2]], "vertices"),
    (np.zeros((4, 2)), [[0, 1, 2]], "vertices"),
    (np.zeros(12), [[0, 1, 2]], "vertices"),
    (np.zeros((4, 3)), [[0, 1, 2, 3]], "faces"),
    (np.zeros((4, 3)), [["x", "y", "z"]], "faces"),
    (np.zeros((4, 3)), [[0, 1, 2.5]], "faces"),
    (np.zeros((4, 3)), [[0, 1, 4]], "face 0"),
    (np.zeros((4, 3)), [[0, 1, 2], [0, -1, 2]], "face 1"),
    (np.array([[0, 0, 0], [1, 0, 0], [0, np.nan, 0], [0, 0, 1]]), [[0, 1, 2]], "vertex 2"),
])
def test_bad_arrays_name_part_and_element(vertices, faces, element):
    with pytest.raises(apart.InputError) as e:
        apart.Assembly.from_meshes([("bad", vertices, faces)])
    assert isinstance(e.value, ValueError)
    assert e.value.part == "bad" and e.value.element == element


def test_bad_arguments():
    asm = apart.load(EXAMPLES / "dovetail-and-cap")
    with pytest.raises(apart.InputError) as e:
        asm.separate("tenon", "slto")
    assert e.value.part == "slto" and '"slot"' in str(e.value)
    with pytest.raises(apart.InputError):
        asm.sequence(base="nope")
    with pytest.raises(apart.InputError):
        asm.separate("tenon", "tenon")
    with pytest.raises(apart.InputError):
        asm.partition(direction=(0, 0, 0))
    with pytest.raises(apart.InputError):
        asm.partition(direction=(1, 2))
    with pytest.raises(apart.InputError):
        asm.sequence(max_depth=0)
    with pytest.raises(apart.InputError):
        asm.sequence(ranking="best")
    with pytest.raises(apart.InputError):
        asm.sequence(first=True, ranking="full")
    for bad in [dict(tolerance=-1), dict(tolerance="5um"), dict(tolerance="3parsecs", units="mm"),
                dict(grid_bits=3), dict(units="furlong")]:
        with pytest.raises(apart.InputError):
            apart.load(EXAMPLES / "hinge", **bad)
    with pytest.raises(apart.InputError):
        apart.Assembly.from_meshes("not meshes")
    with pytest.raises(apart.InputError):
        apart.Assembly.from_meshes([])


def test_overlapping_parts_name_both():
    asm = apart.Assembly.from_meshes([("a", *box((0, 0, 0), (2, 2, 2))), ("b", *box((1, 1, 1), (3, 3, 3)))])
    assert not asm.valid
    with pytest.raises(apart.InvalidAssemblyError) as e:
        asm.partition()
    assert e.value.part in ("a", "b") and "overlap" in str(e.value)


def test_garbage_files_do_not_crash_the_interpreter(tmp_path):
    # Run in a child interpreter: a crash would kill it, not this test run.
    (tmp_path / "junk_a.stl").write_bytes(b"solid \x00\xff" + bytes(range(256)) * 40)
    (tmp_path / "junk_b.off").write_text("OFF\n99999999999 1 0\n1 2 3\n")
    (tmp_path / "junk_c.glb").write_bytes(b"glTF\x02\x00\x00\x00" + b"\xff" * 64)
    code = (
        "import apart, sys\n"
        f"a = apart.load({str(tmp_path)!r})\n"
        "r = a.check()\n"
        "assert not r.valid and r.errors, r\n"
        "assert all(p.file for p in r.errors), r.errors\n"
        "print('ok', len(r.errors))\n"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    assert r.stdout.startswith("ok")
