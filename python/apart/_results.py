"""Typed answers. Each keeps the JSON the compiled module returned, field for field
the command line's ``--json`` output, and gives it back with ``to_dict()``."""

from __future__ import annotations

import copy
import math
import os
from fractions import Fraction
from typing import Any, Dict, Iterator, List, Optional, Tuple, Union

import numpy as np

from ._errors import ApartError

ExactDirection = Tuple[int, int, int]


def _exact(strings: List[str]) -> ExactDirection:
    x, y, z = (int(s) for s in strings)
    return (x, y, z)


def _vec(v: List[float]) -> np.ndarray:
    return np.array(v, dtype=np.float64)


def _fmt_dir(e: ExactDirection) -> str:
    return "(" + ", ".join(str(c) for c in e) + ")"


class _Answer:
    """An answer backed by the command line's JSON."""

    _raw: Dict[str, Any]

    def to_dict(self) -> Dict[str, Any]:
        """The answer as the command line's ``--json`` prints it (a copy)."""
        return copy.deepcopy(self._raw)


class _Facts(_Answer):
    """What every answer states about its input."""

    @property
    def units(self) -> Optional[str]:
        """The unit of the input files, when given."""
        return self._raw.get("units")

    @property
    def tolerance(self) -> Optional[Dict[str, Any]]:
        """The tolerance the answer holds under (parts made ``eps`` smaller); None
        for the parts as given."""
        return self._raw.get("tolerance")

    @property
    def repairs(self) -> List[Dict[str, Any]]:
        """Every repair made on load, per mesh file."""
        return self._raw.get("repairs", [])

    @property
    def skipped_files(self) -> List[Dict[str, Any]]:
        """Files of the assembly folder that were not read, with the reason."""
        return self._raw.get("skipped_files", [])


class Problem(_Answer):
    """A problem found while loading: severity, file, part, element and message."""

    severity: str
    file: Optional[str]
    part: Optional[str]
    element: Optional[str]
    message: str

    @classmethod
    def _from(cls, d: Dict[str, Any]) -> "Problem":
        p = cls()
        p._raw = d
        p.severity = d.get("severity", "error")
        p.file = d.get("file")
        p.part = d.get("part")
        p.element = d.get("element")
        p.message = d.get("message", "")
        return p

    def __str__(self) -> str:
        where = []
        if self.file:
            where.append(self.file + (f' (part "{self.part}")' if self.part else ""))
        elif self.part:
            where.append(f'part "{self.part}"')
        if self.element:
            where.append(self.element)
        ctx = ", ".join(where)
        return f"{self.severity}: {ctx + ': ' if ctx else ''}{self.message}"

    def __repr__(self) -> str:
        return f"<Problem {self}>"


class PartInfo(_Answer):
    """One part as ``check`` reports it."""

    name: str
    volume: Optional[str]
    convex: bool
    pieces: int

    @classmethod
    def _from(cls, d: Dict[str, Any]) -> "PartInfo":
        p = cls()
        p._raw = d
        p.name = d["name"]
        p.volume = d.get("volume")
        p.convex = d["convex"]
        p.pieces = d["pieces"]
        return p

    @property
    def volume_decimal(self) -> Optional[float]:
        """The exact volume as a float (None when unknown)."""
        return self._raw.get("volume_decimal")

    @property
    def bbox(self) -> Optional[Tuple[np.ndarray, np.ndarray]]:
        """The bounding box (min, max) in input units."""
        b = self._raw.get("bbox")
        return None if b is None else (_vec(b["min"]), _vec(b["max"]))

    def __repr__(self) -> str:
        kind = "convex" if self.convex else f"{self.pieces} convex pieces"
        return f"<PartInfo {self.name!r}: volume {self.volume}, {kind}>"


class CheckReport(_Facts):
    """What loading found: the parts, the grid and every problem (``apart check``)."""

    valid: bool
    parts: List[PartInfo]
    problems: List[Problem]

    def __init__(self, raw: Dict[str, Any]) -> None:
        self._raw = raw
        self.valid = raw["valid"]
        self.parts = [PartInfo._from(p) for p in raw["parts"]]
        self.problems = [Problem._from(p) for p in raw["problems"]]

    @property
    def errors(self) -> List[Problem]:
        """The problems that are errors."""
        return [p for p in self.problems if p.severity == "error"]

    def __repr__(self) -> str:
        state = "valid" if self.valid else f"invalid ({len(self.errors)} errors)"
        return (f"<CheckReport {self._raw['assembly']!r}: {len(self.parts)} parts, "
                f"{state}, {len(self.problems)} problems>")


class Solution(_Answer):
    """One way to separate: ``moving`` translates to infinity along ``direction``
    while the other parts stay."""

    cell: str
    moving: Tuple[str, ...]
    direction: np.ndarray
    exact_direction: ExactDirection
    clearance_deg: float
    holds_without_tolerance: Optional[bool]

    @classmethod
    def _from(cls, d: Dict[str, Any]) -> "Solution":
        s = cls()
        s._raw = d
        s.cell = d["cell"]
        s.moving = tuple(d["moving"])
        s.direction = _vec(d["direction"])
        s.exact_direction = _exact(d["exact_direction"])
        s.clearance_deg = d.get("clearance_deg", 0.0)
        s.holds_without_tolerance = d.get("holds_without_tolerance")
        return s

    def __repr__(self) -> str:
        extra = {"face": f"clearance {self.clearance_deg:.2f}°", "edge": "sliding",
                 "vertex": "isolated direction"}.get(self.cell, "")
        return (f"<Solution {self.cell} {', '.join(self.moving)} along "
                f"{_fmt_dir(self.exact_direction)} ({extra})>")


class MovingSet(_Answer):
    """A minimal moving set and how many solutions move it."""

    moving: Tuple[str, ...]
    solutions: int
    faces: int
    edges: int
    vertices: int
    best_clearance_deg: Optional[float]
    #: How many of its solutions the partition lists.
    listed: int

    @classmethod
    def _from(cls, d: Dict[str, Any]) -> "MovingSet":
        g = cls()
        g._raw = d
        g.moving = tuple(d["moving"])
        g.solutions = d["solutions"]
        g.faces, g.edges, g.vertices = d["faces"], d["edges"], d["vertices"]
        g.best_clearance_deg = d.get("best_clearance_deg")
        g.listed = d.get("listed", g.solutions)
        return g

    def __repr__(self) -> str:
        return (f"<MovingSet {', '.join(self.moving)}: {self.faces} faces, "
                f"{self.edges} edges, {self.vertices} vertices>")


class Partition(_Facts):
    """Every direction and minimal subset of parts that separates the assembly by one
    translation (``apart partition``). Iterating gives the listed solutions: as the
    command line lists them, by default those of at most 20 moving sets with at most 5
    of each kind per set (``partition(all=True)`` lists every one); ``solution_count``
    and each group's counts cover every solution."""

    status: str
    complete: bool
    interlocked: bool
    parts: Tuple[str, ...]
    solutions: List[Solution]
    groups: List[MovingSet]
    solution_count: int

    def __init__(self, raw: Dict[str, Any], plan: Any = None) -> None:
        self._raw = raw
        self._plan = plan
        self.status = raw["status"]
        self.complete = raw["complete"]
        self.interlocked = raw["interlocked"]
        self.parts = tuple(raw["parts"])
        self.solutions = [Solution._from(s) for s in raw["solutions"]]
        self.groups = [MovingSet._from(g) for g in raw["groups"]]
        self.solution_count = raw["solution_count"]

    @property
    def moving_set_count(self) -> int:
        """Distinct moving sets among every solution (listed in ``groups`` or not)."""
        return int(self._raw.get("moving_set_count", len(self.groups)))

    @property
    def truncated(self) -> bool:
        """Some solutions are counted but not listed (see ``limit`` and ``max_per_set``
        of :meth:`Assembly.partition`; ``all=True`` lists every one)."""
        return bool(self._raw.get("truncated"))

    @property
    def limit(self) -> Optional[int]:
        """Moving sets listed at most (None with ``all=True``)."""
        return self._raw.get("limit")

    @property
    def nothing_to_separate(self) -> bool:
        """The assembly has one part."""
        return bool(self._raw.get("nothing_to_separate"))

    @property
    def stopped(self) -> Optional[Dict[str, Any]]:
        """Why and when a partial answer stopped (None when complete)."""
        return self._raw.get("stopped")

    @property
    def stats(self) -> Dict[str, Any]:
        """Sizes of the motion space and timings."""
        return self._raw["stats"]

    def __iter__(self) -> Iterator[Solution]:
        return iter(self.solutions)

    def __len__(self) -> int:
        return len(self.solutions)

    def __getitem__(self, k: int) -> Solution:
        return self.solutions[k]

    def __repr__(self) -> str:
        if self.interlocked:
            what = "interlocked"
        else:
            what = (f"{self.solution_count} solutions in {self.moving_set_count} moving sets")
            if self.truncated:
                what += f" ({len(self.solutions)} listed)"
        if not self.complete:
            what += f", partial ({self.status})"
        return f"<Partition of {len(self.parts)} parts: {what}>"


class DirectionAnswer(_Facts):
    """One direction's blocking graph (``apart partition --direction``)."""

    direction: np.ndarray
    exact_direction: ExactDirection
    cell: str
    blocks: List[Tuple[str, str]]
    moving: List[Tuple[str, ...]]

    def __init__(self, raw: Dict[str, Any]) -> None:
        self._raw = raw
        self.direction = _vec(raw["direction"])
        self.exact_direction = _exact(raw["exact_direction"])
        self.cell = raw["cell"]
        self.blocks = [(a, b) for a, b in raw["blocks"]]
        self.moving = [tuple(m) for m in raw["moving"]]

    def __repr__(self) -> str:
        return (f"<DirectionAnswer {_fmt_dir(self.exact_direction)} in a {self.cell}: "
                f"{len(self.blocks)} blocking arcs, {len(self.moving)} moving sets>")


class Step(_Answer):
    """One step of a disassembly plan: ``moving`` leaves ``subassembly`` along
    ``direction``."""

    index: int
    subassembly: Tuple[str, ...]
    moving: Tuple[str, ...]
    direction: np.ndarray
    exact_direction: ExactDirection
    cell: str
    clearance_deg: float
    depth: int

    @classmethod
    def _from(cls, k: int, d: Dict[str, Any]) -> "Step":
        s = cls()
        s._raw = d
        s.index = k
        s.subassembly = tuple(d["subassembly"])
        s.moving = tuple(d["moving"])
        s.direction = _vec(d["direction"])
        s.exact_direction = _exact(d["exact_direction"])
        s.cell = d["cell"]
        s.clearance_deg = d["clearance_deg"]
        s.depth = d["depth"]
        return s

    @property
    def staying(self) -> Tuple[str, ...]:
        """The parts of the subassembly that stay."""
        return tuple(p for p in self.subassembly if p not in self.moving)

    @property
    def growth(self) -> Optional[float]:
        """With ``growth=True``: the largest uniform growth of the parts (input units)
        that keeps the step possible; None when unbounded or not asked."""
        return self._raw.get("growth")

    @property
    def choice(self) -> Dict[str, Any]:
        """Why the step was chosen: its ranking keys, the candidates and the
        runner-up."""
        return self._raw["choice"]

    @property
    def rule(self) -> str:
        """The rule that chose the step: ``"ranked"`` (over the subassembly's full
        motion space), ``"single"`` (a single part from its own free directions),
        ``"pair"`` (two touching parts together), ``"likely"`` (a set along a likely
        direction) or ``"full"`` (the full motion space after nothing simpler split the
        subassembly)."""
        return self._raw["rule"]

    def __repr__(self) -> str:
        verb = "moves" if len(self.moving) == 1 else "move"
        return (f"<Step {self.index + 1}: {', '.join(self.moving)} {verb} along "
                f"{_fmt_dir(self.exact_direction)} ({self.cell})>")


class Sequence(_Facts):
    """A disassembly plan by recursive two-handed partitioning (``apart sequence``);
    its reverse is an assembly plan. Iterating gives the steps in order."""

    status: str
    complete: bool
    interlocked: bool
    parts: Tuple[str, ...]
    steps: List[Step]
    stuck: List[Tuple[str, ...]]
    unsplit: List[Tuple[str, ...]]
    not_yet_split: List[Tuple[str, ...]]

    def __init__(self, raw: Dict[str, Any], plan: Any = None) -> None:
        self._raw = raw
        self._plan = plan
        self.status = raw["status"]
        self.complete = raw["complete"]
        self.interlocked = raw["interlocked"]
        self.parts = tuple(raw["parts"])
        self.steps = [Step._from(k, s) for k, s in enumerate(raw["steps"])]
        self.stuck = [tuple(s) for s in raw["stuck"]]
        self.unsplit = [tuple(s) for s in raw["unsplit"]]
        self.not_yet_split = [tuple(s) for s in raw["not_yet_split"]]

    @property
    def stopped(self) -> Optional[Dict[str, Any]]:
        """Why and when a partial plan stopped (None when it ran to its end)."""
        return self._raw.get("stopped")

    def _drawable(self) -> Any:
        if self._plan is None:
            raise ApartError("a stopped or partial plan has no pictures (nor has it on the command line)")
        return self._plan

    def to_glb(self, path: "os.PathLike[str] | str") -> None:
        """Writes the animated GLB of the disassembly (``apart sequence --glb``): every
        part, each step's moving parts sliding out along its direction. The file is the
        command line's, byte for byte."""
        data = self._drawable().glb()
        with open(os.fspath(path), "wb") as f:
            f.write(data)

    def to_html(self, path: "os.PathLike[str] | str") -> None:
        """Writes the self-contained HTML viewer that plays the disassembly
        (``apart sequence --html``; no network, no WebGL), byte for byte the command
        line's."""
        text = self._drawable().html()
        with open(os.fspath(path), "wb") as f:
            f.write(text.encode("utf-8"))

    def __iter__(self) -> Iterator[Step]:
        return iter(self.steps)

    def __len__(self) -> int:
        return len(self.steps)

    def __getitem__(self, k: int) -> Step:
        return self.steps[k]

    def __repr__(self) -> str:
        state = "complete" if self.complete else (
            "interlocked" if self.interlocked else f"incomplete ({self.status})")
        return f"<Sequence of {len(self.parts)} parts: {len(self.steps)} steps, {state}>"


class Separation(_Facts):
    """Every direction along which ``moving`` leaves ``fixed`` (``apart separate``):
    open regions, sliding arcs and isolated directions."""

    moving: str
    fixed: str
    separable: bool
    area_fraction: float
    best_direction: Optional[np.ndarray]
    best_exact_direction: Optional[ExactDirection]
    best_clearance_deg: Optional[float]
    isolated: List[ExactDirection]

    def __init__(self, raw: Dict[str, Any]) -> None:
        self._raw = raw
        self.moving = raw["moving"]
        self.fixed = raw["fixed"]
        self.separable = raw["separable"]
        self.area_fraction = raw["area_fraction"]
        best = raw.get("best")
        self.best_direction = None if best is None else _vec(best["direction"])
        self.best_exact_direction = None if best is None else _exact(best["exact_direction"])
        self.best_clearance_deg = None if best is None else best["clearance_deg"]
        self.isolated = [_exact(d) for d in raw["isolated"]]

    @property
    def regions(self) -> List[Dict[str, Any]]:
        """Open regions of free directions: area fraction, a deep direction, its
        clearance and the exact boundary arcs."""
        return self._raw["regions"]

    @property
    def sliding(self) -> List[Dict[str, Any]]:
        """Free arcs between blocked regions (exact normal, start and end)."""
        return self._raw["sliding"]

    def __repr__(self) -> str:
        if not self.separable:
            return f"<Separation {self.moving!r} from {self.fixed!r}: inseparable>"
        return (f"<Separation {self.moving!r} from {self.fixed!r}: "
                f"{100 * self.area_fraction:.4f}% of directions, "
                f"{len(self.regions)} regions, {len(self.sliding)} sliding arcs, "
                f"{len(self.isolated)} isolated, best "
                f"{_fmt_dir(self.best_exact_direction) if self.best_exact_direction else '-'}>")


class Placement(_Answer):
    """One part of a stack: where it went (translation, exact as fractions of input
    units), its orientation and what it rests on."""

    index: int
    translation: np.ndarray
    exact_translation: Tuple[Fraction, Fraction, Fraction]
    rotation_deg: np.ndarray
    cost: float
    stage: int
    contacts: List[Dict[str, Any]]

    @classmethod
    def _from(cls, d: Dict[str, Any]) -> "Placement":
        p = cls()
        p._raw = d
        p.index = d["index"]
        p.translation = _vec(d["translation"])
        x, y, z = (Fraction(s) for s in d["exact_translation"])
        p.exact_translation = (x, y, z)
        p.rotation_deg = _vec(d["rotation_deg"])
        p.cost = d["cost"]
        p.stage = d["stage"]
        p.contacts = d["contacts"]
        return p

    def __repr__(self) -> str:
        t = ", ".join(f"{c:g}" for c in self.translation)
        r = ", ".join(f"{c:g}" for c in self.rotation_deg)
        return f"<Placement {self.index}: at ({t}), rotated ({r})°>"


class StackPlan(_Answer):
    """A stack of identical parts on a floor (``apart stack``): each placed by the exact
    placement engine, stable, grippable from above and lowerable along -z. Iterating
    gives the placements in order."""

    status: str
    part: str
    count: int
    complete: bool
    placements: List[Placement]
    stack_height: float

    def __init__(self, raw: Dict[str, Any]) -> None:
        self._raw = raw
        self.status = raw["status"]
        self.part = raw["part"]
        self.count = raw["count"]
        self.complete = raw["complete"]
        self.placements = [Placement._from(p) for p in raw["placements"]]
        self.stack_height = raw["stack_height"]

    @property
    def stopped(self) -> Optional[Dict[str, Any]]:
        """Why and when a partial stack stopped (None when it ran to its end)."""
        return self._raw.get("stopped")

    def __iter__(self) -> Iterator[Placement]:
        return iter(self.placements)

    def __len__(self) -> int:
        return len(self.placements)

    def __getitem__(self, k: int) -> Placement:
        return self.placements[k]

    def __repr__(self) -> str:
        state = "complete" if self.complete else f"incomplete ({self.status})"
        return (f"<StackPlan of {self.part!r}: {len(self.placements)} of {self.count} "
                f"placed, height {self.stack_height:g}, {state}>")


class PlaceCandidate(_Answer):
    """One interference-free position of the placed part: its translation (exact as
    fractions of input units), its rotation and its cost."""

    translation: np.ndarray
    exact_translation: Tuple[Fraction, Fraction, Fraction]
    rotation_deg: np.ndarray
    exact_rotation: Tuple[str, str]
    cost: float

    @classmethod
    def _from(cls, d: Dict[str, Any]) -> "PlaceCandidate":
        c = cls()
        c._raw = d
        c.translation = _vec(d["translation"])
        x, y, z = (Fraction(s) for s in d["exact_translation"])
        c.exact_translation = (x, y, z)
        c.rotation_deg = _vec(d["rotation_deg"])
        c.exact_rotation = (d["exact_rotation"][0], d["exact_rotation"][1])
        c.cost = d["cost"]
        return c

    def __repr__(self) -> str:
        t = ", ".join(f"{c:g}" for c in self.translation)
        r = ", ".join(f"{c:g}" for c in self.rotation_deg)
        return f"<PlaceCandidate at ({t}), rotated ({r})°, cost {self.cost:g}>"


class PlaceResult(_Answer):
    """Interference-free positions of a part among fixed parts, cheapest first
    (``apart place``). Iterating gives the candidates; ``best`` is the first (None when
    the part fits nowhere in the region)."""

    moving: str
    fixed: Tuple[str, ...]
    cost_kind: str
    candidates: List[PlaceCandidate]

    def __init__(self, raw: Dict[str, Any]) -> None:
        self._raw = raw
        self.moving = raw["moving"]
        self.fixed = tuple(raw["fixed"])
        self.cost_kind = raw["cost_kind"]
        self.candidates = [PlaceCandidate._from(c) for c in raw["candidates"]]

    @property
    def found(self) -> bool:
        """True when a position was found (the command line's exit code 0)."""
        return bool(self.candidates)

    @property
    def best(self) -> Optional[PlaceCandidate]:
        """The cheapest position, or None."""
        return self.candidates[0] if self.candidates else None

    def __iter__(self) -> Iterator[PlaceCandidate]:
        return iter(self.candidates)

    def __len__(self) -> int:
        return len(self.candidates)

    def __getitem__(self, k: int) -> PlaceCandidate:
        return self.candidates[k]

    def __repr__(self) -> str:
        if not self.candidates:
            k = len(self.fixed)
            return f"<PlaceResult {self.moving!r}: no position among {k} fixed part{'s' if k != 1 else ''}>"
        n, k = len(self.candidates), len(self.fixed)
        return (f"<PlaceResult {self.moving!r}: {n} position{'s' if n != 1 else ''} among "
                f"{k} fixed part{'s' if k != 1 else ''}, best {self.candidates[0]!r}>")


class Move(_Answer):
    """One move of a plan of moves (``apart disassemble``): ``moving`` translate by
    ``distance`` times ``exact_direction`` (input units), or to infinity."""

    subassembly: Tuple[str, ...]
    moving: Tuple[str, ...]
    direction: np.ndarray
    exact_direction: ExactDirection
    distance: Union[Fraction, float]
    positions: Dict[str, np.ndarray]
    exact_positions: Dict[str, Tuple[Fraction, Fraction, Fraction]]

    def __init__(self, raw: Dict[str, Any]) -> None:
        self._raw = raw
        self.subassembly = tuple(raw["subassembly"])
        self.moving = tuple(raw["moving"])
        self.direction = _vec(raw["direction"])
        self.exact_direction = _exact(raw["exact_direction"])
        d = raw["distance"]
        self.distance = math.inf if d == "infinity" else Fraction(d)
        self.positions = {k: _vec(v) for k, v in raw["positions"].items()}
        self.exact_positions = {
            k: (Fraction(v[0]), Fraction(v[1]), Fraction(v[2]))
            for k, v in raw["exact_positions"].items()
        }

    @property
    def to_infinity(self) -> bool:
        """The move separates its subassembly."""
        return self.distance == math.inf

    def __repr__(self) -> str:
        how = "to infinity" if self.to_infinity else f"by {self.distance} x"
        return f"Move({list(self.moving)} {how} {_fmt_dir(self.exact_direction)})"


class Disassembly(_Facts):
    """A plan of several moves (``apart disassemble``): finite translations, then one to
    infinity, recursively on the separated groups; ``level`` counts the moves up to and
    including the first move to infinity. Iterating gives the moves in order."""

    status: str
    level: Optional[int]
    complete: bool
    verdict: Optional[str]
    model: str
    parts: Tuple[str, ...]
    moves: List[Move]
    states_explored: int

    def __init__(self, raw: Dict[str, Any]) -> None:
        self._raw = raw
        self.status = raw["status"]
        self.level = raw["level"]
        self.complete = raw["complete"]
        self.verdict = raw.get("verdict")
        self.model = raw["model"]
        self.parts = tuple(raw["parts"])
        self.moves = [Move(m) for m in raw["moves"]]
        self.states_explored = raw["states_explored"]

    @property
    def searches(self) -> List[Dict[str, Any]]:
        """Every subassembly's search: its parts, level, states and how it ended."""
        return self._raw["searches"]

    @property
    def stopped(self) -> Optional[Dict[str, Any]]:
        """Why and when a partial plan stopped (None when it ran to its end)."""
        return self._raw.get("stopped")

    def __iter__(self) -> Iterator[Move]:
        return iter(self.moves)

    def __len__(self) -> int:
        return len(self.moves)

    def __repr__(self) -> str:
        return f"Disassembly(level={self.level}, moves={len(self.moves)}, complete={self.complete})"
