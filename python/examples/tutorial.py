"""A short tour of apart's Python package.

Run from the repository's root after `pip install ./python`:

    python python/examples/tutorial.py

It loads the Split Star (three parts translate together along one of the eight
diagonal directions (±1, ±1, ±1), each an isolated direction with zero clearance),
plans a disassembly of the hinge (and writes its HTML viewer), places a part, and builds
assemblies from numpy arrays. A STEP assembly loads the same way, apart.load("x.step"),
with `pip install './python[step]'`.
"""

import sys
import tempfile
from pathlib import Path

import numpy as np

import apart

examples = Path(__file__).resolve().parents[2] / "examples"

# 1. The Split Star: six identical parts, and exactly eight ways to take it apart.
star = apart.load(examples / "split-star")
print(star)
motions = star.partition()
print(motions)
for s in motions:
    print(f"  {', '.join(s.moving)} move along {s.exact_direction} ({s.cell})")

# 2. A disassembly plan, walked step by step; its reverse assembles.
hinge = apart.load(examples / "hinge")
plan = hinge.sequence(prefer_single=True)
for step in plan:
    verb = "leaves" if len(step.moving) == 1 else "leave"
    print(f"  step {step.index + 1}: {', '.join(step.moving)} {verb} "
          f"{', '.join(step.staying)} along {step.exact_direction}")
out = Path(tempfile.mkdtemp())
plan.to_html(out / "hinge.html")      # the viewer `apart sequence --html` writes
star.render(out / "split-star.svg")   # the motion-space sphere of `apart partition --svg`
print(f"  pictures in {out}")

# Where could the bolt go instead? Positions free of the other parts, nearest first.
spot = apart.place(examples / "hinge", "bolt", target=(0, 0, 50), candidates=2)
print(spot)


# 3. Assemblies from arrays: two unit boxes side by side, then a box in a cup.
def box(lo, hi):
    """The 8 corners and 12 outward triangles of an axis-aligned box."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    v = np.array([[x, y, z] for x in (x0, x1) for y in (y0, y1) for z in (z0, z1)], float)
    f = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                  [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])
    return v, f


boxes = apart.Assembly.from_meshes([("left", *box((0, 0, 0), (1, 1, 1))),
                                    ("right", *box((2, 0, 0), (3, 1, 1)))])
sep = boxes.separate("left", "right")
print(sep)
print("  best direction:", sep.best_exact_direction, "≈", np.round(sep.best_direction, 3))

# Progress reports come as (phase, done, total); progress=True draws a tqdm bar.
phases = set()
star.sequence(progress=lambda phase, done, total: phases.add(phase))
print("  phases reported:", sorted(phases))

# Bad input raises an exception naming the part and the element.
try:
    apart.Assembly.from_meshes([("broken", np.zeros((3, 3)), [[0, 1, 7]])])
except apart.InputError as e:
    print(f"  InputError: part={e.part!r} element={e.element!r}: {e}")
sys.exit(0)
