"""Shared fixtures: the shipped examples, the command line to compare against, and
mesh helpers.

The command line is the `apart` binary of this repository: `APART_BIN` if set,
otherwise `$CARGO_TARGET_DIR/release/apart`, otherwise `<repo>/target/release/apart`
(`.ci/run` has built it by then with `cargo test --workspace --release`; locally,
`cargo build --release` first). Tests that compare with it fail, never skip, when it is
missing: a comparison that cannot run is not a pass.
"""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path
from typing import Any, Dict, List, Tuple

import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[2]
EXAMPLES = REPO / "examples"


def apart_bin() -> Path:
    """The command line's binary."""
    if os.environ.get("APART_BIN"):
        return Path(os.environ["APART_BIN"])
    target = Path(os.environ.get("CARGO_TARGET_DIR") or REPO / "target")
    return target / "release" / "apart"


@pytest.fixture(scope="session")
def cli():
    """Runs `apart ARGS --json` and returns (exit code, parsed JSON)."""
    exe = apart_bin()
    if not exe.is_file():
        pytest.fail(f"the apart binary is not at {exe}: run `cargo build --release` or set APART_BIN")

    def run(*args: str) -> Tuple[int, Dict[str, Any]]:
        r = subprocess.run([str(exe), *args, "--json", "--quiet"], capture_output=True,
                           text=True, cwd=REPO, timeout=600)
        return r.returncode, json.loads(r.stdout)

    return run


def box(lo, hi) -> Tuple[np.ndarray, np.ndarray]:
    """The 8 corners and 12 outward triangles of an axis-aligned box."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    v = np.array([[x, y, z] for x in (x0, x1) for y in (y0, y1) for z in (z0, z1)], float)
    f = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                  [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])
    return v, f


def read_off(path: Path) -> Tuple[np.ndarray, np.ndarray]:
    """A plain OFF reader (triangles and convex polygons fanned), independent of apart's."""
    words: List[str] = []
    for line in path.read_text().splitlines():
        words += line.split("#")[0].split()
    assert words[0] == "OFF"
    nv, nf = int(words[1]), int(words[2])
    k = 4
    v = np.array([[float(w) for w in words[k + 3 * i:k + 3 * i + 3]] for i in range(nv)])
    k += 3 * nv
    faces = []
    for _ in range(nf):
        n = int(words[k])
        idx = [int(w) for w in words[k + 1:k + 1 + n]]
        k += 1 + n
        faces += [[idx[0], idx[j], idx[j + 1]] for j in range(1, n - 1)]
    return v, np.array(faces)


def solution_set(solutions) -> set:
    """(cell, moving set, exact direction) of every solution, from JSON or objects."""
    out = set()
    for s in solutions:
        if isinstance(s, dict):
            out.add((s["cell"], frozenset(s["moving"]), tuple(int(c) for c in s["exact_direction"])))
        else:
            out.add((s.cell, frozenset(s.moving), s.exact_direction))
    return out
