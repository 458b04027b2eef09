"""Loading and planning: the Python face of the compiled module ``apart._apart``."""

from __future__ import annotations

import json
import os
import re
import sys
from typing import Any, Callable, Dict, Iterable, List, Optional, Sequence as Seq, Tuple, Union

import numpy as np

from . import _apart
from ._errors import InputError
from ._results import (CheckReport, DirectionAnswer, Disassembly, Partition, PlaceResult,
                       Problem, Separation, Sequence, StackPlan)

ProgressArg = Union[None, bool, Callable[[str, int, int], Any]]
PathLike = Union[str, "os.PathLike[str]"]

#: Length units of input files, in metres (as the command line's ``--units``).
UNITS: Dict[str, float] = {"m": 1.0, "cm": 0.01, "mm": 1e-3, "um": 1e-6, "in": 0.0254,
                           "ft": 0.3048}


def _tolerance(tolerance: Union[None, float, str], units: Optional[str]) -> Tuple[Optional[float], bool]:
    """(eps in input units, auto) from ``tolerance``: a positive length in input units,
    ``"auto"``, or a length with a unit (``"5um"``), which needs ``units``."""
    if tolerance is None:
        return None, False
    if isinstance(tolerance, bool):
        raise InputError(f"tolerance must be a length or 'auto', not {tolerance!r}")
    if isinstance(tolerance, (int, float)):
        v = float(tolerance)
        if not (np.isfinite(v) and v > 0):
            raise InputError(f"tolerance must be a finite, positive length, not {tolerance!r}")
        return v, False
    if not isinstance(tolerance, str):
        raise InputError(f"tolerance must be a length or 'auto', not {tolerance!r}")
    t = tolerance.strip()
    if t.lower() == "auto":
        return None, True
    m = re.fullmatch(r"([-+0-9.eE]+)\s*([a-zµ]*)", t)
    if not m:
        raise InputError(f"tolerance {tolerance!r} is neither 'auto' nor a length such as 1e-6 or '5um'")
    try:
        v = float(m.group(1))
    except ValueError:
        raise InputError(f"tolerance {tolerance!r} is neither 'auto' nor a length such as 1e-6 or '5um'") from None
    if not (np.isfinite(v) and v > 0):
        raise InputError(f"tolerance must be a finite, positive length, not {tolerance!r}")
    unit = m.group(2).replace("µm", "um")
    if not unit:
        return v, False
    if unit not in UNITS:
        raise InputError(f"tolerance {tolerance!r}: unknown unit {unit!r} (m, cm, mm, um, in, ft)")
    if units is None:
        raise InputError(f"tolerance {tolerance!r} names a unit: say which unit the input files use with units=")
    return v * UNITS[unit] / UNITS[units], False


def _load_options(tolerance: Union[None, float, str], units: Optional[str],
                  grid_bits: Optional[int], strict: bool, one_part_per_file: bool,
                  verify: bool) -> Dict[str, Any]:
    if units is not None and units not in UNITS:
        raise InputError(f"units {units!r} is none of {', '.join(UNITS)}")
    lo, hi = _apart.GRID_BITS_RANGE
    bits = _apart.DEFAULT_GRID_BITS if grid_bits is None else grid_bits
    if isinstance(bits, bool) or not isinstance(bits, int) or not lo <= bits <= hi:
        raise InputError(f"grid_bits must be an integer from {lo} to {hi}, not {grid_bits!r}")
    eps, auto = _tolerance(tolerance, units)
    return dict(grid_bits=bits, tolerance=eps, tolerance_auto=auto, strict=bool(strict),
                one_part_per_file=bool(one_part_per_file), verify=bool(verify), units=units)


#: Largest timeout, in seconds (one week, as the command line's ``--timeout``).
MAX_TIMEOUT = 604800.0


def _timeout(timeout: Optional[float]) -> Optional[float]:
    if timeout is None:
        return None
    t = _number(timeout, "timeout")
    if not 0 < t <= MAX_TIMEOUT:
        raise InputError(f"timeout must be more than 0 and at most {MAX_TIMEOUT} seconds (one week), not {timeout!r}")
    return t


def set_memory_budget(size: Union[None, int, str]) -> None:
    """Sets the memory budget of apart's work in this process, as the command line's
    ``--max-memory``: a number of bytes (at least 1 MiB; 0 for none), a size such as
    ``"4G"``, ``"500M"`` or ``"1.5G"`` (K, M, G, T are powers of 1024), ``"default"``,
    or ``None`` (no budget). The default, set when apart is imported, is the command
    line's: 80 % of the machine's memory (or of its cgroup's limit).

    The budget counts the heap of apart's compiled module (not numpy's or the
    interpreter's). During a call, past 90 % of the budget a planner with partial
    answers stops with what it found (:meth:`Assembly.partition`,
    :meth:`Assembly.sequence`, :meth:`Assembly.stack`: ``status`` is
    ``"out of memory"``, ``complete`` False), and planners refuse to build a structure
    estimated over what the budget leaves; a call without a partial answer, a refusal
    before any answer, or a call whose heap passed the budget itself raises
    :class:`OutOfMemoryBudget` (a ``MemoryError``), and the interpreter carries on.
    Only past the larger of the budget and the default does apart end the process, with
    the command line's message "out of memory budget (SIZE) during PHASE", rather than
    let a failed allocation abort it."""
    if isinstance(size, float) and size.is_integer():
        size = int(size)
    _apart.set_memory_budget(size)


def memory_budget() -> Optional[int]:
    """The memory budget in bytes (None: no budget); see :func:`set_memory_budget`."""
    return _apart.memory_budget()


def memory_in_use() -> int:
    """The heap of apart's compiled module, in bytes, as the memory budget counts it."""
    return _apart.memory_in_use()


class _TqdmBars:
    """A tqdm bar per phase, driven by the (phase, done, total) reports."""

    def __init__(self) -> None:
        from tqdm.auto import tqdm

        self._tqdm = tqdm
        self._bar: Any = None
        self._phase: Optional[str] = None

    def __call__(self, phase: str, done: int, total: int) -> None:
        if phase != self._phase:
            self.close()
            self._phase = phase
            self._bar = self._tqdm(total=total, desc=phase, leave=False)
        self._bar.total = total
        self._bar.n = done
        self._bar.refresh()

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()
            self._bar = None


def _run(call: Callable[..., Any], progress: ProgressArg, **kwargs: Any) -> Any:
    """Calls the compiled ``call`` with the progress callback ``progress`` asks for."""
    if progress is None or progress is False:
        return call(progress=None, **kwargs)
    if progress is True:
        try:
            bars = _TqdmBars()
        except ImportError:
            print("apart: progress=True shows a bar when tqdm is installed (pip install tqdm)",
                  file=sys.stderr)
            return call(progress=None, **kwargs)
        try:
            return call(progress=bars, **kwargs)
        finally:
            bars.close()
    if not callable(progress):
        raise InputError(f"progress must be a callable, True or None, not {progress!r}")
    return call(progress=progress, **kwargs)


def load(path: PathLike, *, strict: bool = False, one_part_per_file: bool = False,
         tolerance: Union[None, float, str] = None, units: Optional[str] = None,
         grid_bits: Optional[int] = None, allow_outside: bool = False,
         verify: bool = False, progress: ProgressArg = None,
         timeout: Optional[float] = None, chordal_tolerance: Optional[float] = None,
         angular_tolerance: Optional[float] = None) -> "Assembly":
    """Loads an assembly: a folder of mesh files (one part per file), one mesh file
    with several objects, an ``assembly.json`` manifest, or a STEP file (``.step``,
    ``.stp``; needs ``pip install './python[step]'``): every solid instance of its
    product tree, placed and named, tessellated with ``chordal_tolerance`` (a length
    in ``units``, default millimetres; by default 1/1000 of the assembly's diagonal)
    and ``angular_tolerance`` (radians, default 0.5), see :mod:`apart.step`. The other options are the
    command line's: ``strict`` repairs nothing, ``one_part_per_file`` keeps a file
    holding several solids as one part, ``tolerance`` (a length in input units, a
    length with a unit such as ``"5um"`` together with ``units``, or ``"auto"``) makes
    every convex piece that much smaller, ``grid_bits`` sets the snapping grid,
    ``allow_outside`` reads files outside the assembly's folder, ``verify`` checks
    every convex decomposition exactly.

    Problems with parts do not raise: they are in ``Assembly.problems`` (and
    ``check()``); planning an invalid assembly raises :class:`InvalidAssemblyError`.
    A path that cannot be loaded at all raises :class:`InputError` with ``file`` set.
    """
    fspath = os.fspath(path)
    if os.path.splitext(fspath)[1].lower() in (".step", ".stp"):
        from . import step

        return step.load(fspath, chordal_tolerance=chordal_tolerance,
                         angular_tolerance=(step.DEFAULT_ANGULAR_TOLERANCE
                                            if angular_tolerance is None else angular_tolerance),
                         units=units, strict=strict, tolerance=tolerance,
                         grid_bits=grid_bits, verify=verify, progress=progress,
                         timeout=timeout)
    if chordal_tolerance is not None or angular_tolerance is not None:
        raise InputError("chordal_tolerance and angular_tolerance apply to STEP files (.step, .stp) only")
    opts = _load_options(tolerance, units, grid_bits, strict, one_part_per_file, verify)
    inner = _run(_apart.load, progress, path=fspath, allow_outside=bool(allow_outside),
                 timeout=_timeout(timeout), **opts)
    return Assembly._wrap(inner)


MeshLike = Any


def _trimesh_parts(obj: Any, name: Optional[str]) -> Optional[List[Tuple[str, Any, Any]]]:
    """The parts of a trimesh ``Trimesh`` or ``Scene`` (None for anything else)."""
    mod = type(obj).__module__
    if not mod.startswith("trimesh"):
        return None
    import trimesh

    if isinstance(obj, trimesh.Scene):
        parts = []
        for node in obj.graph.nodes_geometry:
            transform, geom_name = obj.graph[node]
            geom = obj.geometry[geom_name]
            if not isinstance(geom, trimesh.Trimesh):
                continue
            verts = trimesh.transformations.transform_points(geom.vertices, transform)
            parts.append((str(node), verts, geom.faces))
        return parts
    if isinstance(obj, trimesh.Trimesh):
        part = name or obj.metadata.get("name") or "part"
        return [(str(part), obj.vertices, obj.faces)]
    return None


def _as_parts(meshes: Any) -> List[Tuple[str, Any, Any]]:
    """(name, vertices, faces) of every part of ``meshes``: a sequence of
    (name, vertices, faces) tuples or trimesh objects, a dict of name to mesh, or one
    trimesh ``Scene``."""
    one = _trimesh_parts(meshes, None)
    if one is not None:
        return one
    if isinstance(meshes, dict):
        items: Iterable[Any] = [(k, v) for k, v in meshes.items()]
    else:
        try:
            items = list(meshes)
        except TypeError:
            raise InputError(f"meshes must be a list of (name, vertices, faces), not {type(meshes).__name__}") from None
    parts: List[Tuple[str, Any, Any]] = []
    for k, item in enumerate(items):
        tm = _trimesh_parts(item, None)
        if tm is not None:
            if len(tm) == 1 and tm[0][0] == "part":
                tm = [(f"part{k + 1}", tm[0][1], tm[0][2])]
            parts.extend(tm)
            continue
        if isinstance(item, tuple) and len(item) == 2:
            nm, mesh = item
            tm = _trimesh_parts(mesh, str(nm))
            if tm is not None:
                if len(tm) == 1:
                    tm = [(str(nm), tm[0][1], tm[0][2])]
                parts.extend(tm)
                continue
            if isinstance(mesh, tuple) and len(mesh) == 2:
                parts.append((nm, mesh[0], mesh[1]))
                continue
        if not (isinstance(item, (tuple, list)) and len(item) == 3):
            raise InputError(f"meshes[{k}] must be (name, vertices, faces) or a trimesh object, not {type(item).__name__}")
        parts.append((item[0], item[1], item[2]))
    return parts


def _real_array(x: Any, what: str, **where: Any) -> np.ndarray:
    """``x`` as a float64 array of real numbers, or :class:`InputError` naming ``what``:
    complex numbers (which numpy would cast to their real part with only a warning),
    booleans, strings and objects that are not real numbers are refused."""
    try:
        a = np.asarray(x)
    except (TypeError, ValueError) as e:
        raise InputError(f"{what} are not numbers ({e})", **where) from None
    kind = a.dtype.kind
    if kind == "O":
        if any(isinstance(e, (bool, np.bool_, complex, np.complexfloating, str, bytes))
               for e in a.flat):
            raise InputError(f"{what} must be real numbers, not {a.dtype} holding non-real values",
                             **where)
        try:
            return a.astype(np.float64)
        except (TypeError, ValueError) as e:
            raise InputError(f"{what} are not real numbers ({e})", **where) from None
    if kind not in "iuf":
        raise InputError(f"{what} must be real numbers, not {a.dtype}", **where)
    return a.astype(np.float64)


def _arrays(name: Any, vertices: Any, faces: Any) -> Tuple[str, bytes, bytes]:
    """One part's arrays, checked, as little-endian bytes: ``vertices`` n x 3 finite
    real numbers, ``faces`` m x 3 integers (or floats of integer value) in 0..n-1."""
    if not isinstance(name, str) or not name:
        raise InputError(f"a part name must be a non-empty string, not {name!r}")
    v = _real_array(vertices, f'part "{name}": vertices', part=name, element="vertices")
    if v.ndim != 2 or v.shape[1] != 3:
        raise InputError(f'part "{name}": vertices must be an n x 3 array, not of shape {v.shape}',
                         part=name, element="vertices")
    bad = ~np.isfinite(v).all(axis=1)
    if bad.any():
        k = int(np.flatnonzero(bad)[0])
        raise InputError(f'part "{name}": vertex {k} has a coordinate that is not a finite number ({v[k].tolist()})',
                         part=name, element=f"vertex {k}")
    try:
        f_in = np.asarray(faces)
    except (TypeError, ValueError) as e:
        raise InputError(f'part "{name}": faces are not integers ({e})', part=name,
                         element="faces") from None
    if f_in.dtype.kind == "f":
        if not np.all(np.isfinite(f_in)) or not np.all(f_in == np.round(f_in)):
            raise InputError(f'part "{name}": face indices must be integers', part=name, element="faces")
    elif f_in.dtype.kind not in "iu":
        raise InputError(f'part "{name}": face indices must be integers, not {f_in.dtype}',
                         part=name, element="faces")
    if f_in.ndim != 2 or f_in.shape[1] != 3:
        raise InputError(f'part "{name}": faces must be an m x 3 array of vertex indices, not of shape {f_in.shape}',
                         part=name, element="faces")
    out = (f_in < 0) | (f_in >= len(v))
    if out.any():
        k = int(np.flatnonzero(out.any(axis=1))[0])
        i = f_in[k][out[k]][0]
        raise InputError(f'part "{name}": face {k}: vertex index {i.item()!r} is not one of the {len(v)} vertices',
                         part=name, element=f"face {k}")
    f = f_in.astype(np.int64)
    return (name, np.ascontiguousarray(v, dtype="<f8").tobytes(),
            np.ascontiguousarray(f, dtype="<i8").tobytes())


class Assembly:
    """An assembly: named parts in their assembled pose, snapped to one grid, with every
    problem found while loading. Make one with :func:`load`, :meth:`from_meshes` or
    :meth:`from_trimesh`."""

    _inner: Any

    def __init__(self) -> None:
        raise TypeError("use apart.load(path), Assembly.from_meshes(...) or Assembly.from_trimesh(...)")

    @classmethod
    def _wrap(cls, inner: Any) -> "Assembly":
        a = cls.__new__(cls)
        a._inner = inner
        return a

    @classmethod
    def from_meshes(cls, meshes: Any, *, name: str = "assembly", strict: bool = False,
                    one_part_per_file: bool = False,
                    tolerance: Union[None, float, str] = None, units: Optional[str] = None,
                    grid_bits: Optional[int] = None, verify: bool = False,
                    progress: ProgressArg = None, timeout: Optional[float] = None) -> "Assembly":
        """An assembly of triangle meshes: a list of ``(name, vertices, faces)`` with
        ``vertices`` an n x 3 float array and ``faces`` an m x 3 integer array of vertex
        indices (or a dict of name to ``(vertices, faces)``); trimesh ``Trimesh`` and
        ``Scene`` objects are accepted as items or as the whole input. Each mesh is a
        part, loaded as the library loads a file (repaired unless ``strict``)."""
        opts = _load_options(tolerance, units, grid_bits, strict, one_part_per_file, verify)
        parts = [_arrays(*p) for p in _as_parts(meshes)]
        if not parts:
            raise InputError("no meshes given")
        inner = _run(_apart.from_meshes, progress, name=str(name), parts=parts,
                     timeout=_timeout(timeout), **opts)
        return cls._wrap(inner)

    @classmethod
    def from_trimesh(cls, obj: Any, **options: Any) -> "Assembly":
        """An assembly of a trimesh ``Scene`` (each geometry node a part, named by its
        node, its transform applied) or of ``Trimesh`` objects (a list, or a dict of
        name to mesh). Options as :meth:`from_meshes`."""
        return cls.from_meshes(obj, **options)

    @property
    def name(self) -> str:
        """The assembly's name."""
        return self._inner.name

    @property
    def parts(self) -> List[str]:
        """The part names, in order."""
        return list(self._inner.names)

    @property
    def valid(self) -> bool:
        """True when loading found no error."""
        return self._inner.valid

    @property
    def problems(self) -> List[Problem]:
        """Every problem found while loading."""
        return self.check().problems

    def check(self) -> CheckReport:
        """The parts, the grid and every problem found while loading (``apart check``)."""
        return CheckReport(json.loads(self._inner.check_json()))

    def partition(self, first: bool = False, direction: Optional[Seq[float]] = None, *,
                  limit: Optional[int] = None, max_per_set: Optional[int] = None,
                  all: bool = False, max_solutions: Optional[int] = None,
                  progress: ProgressArg = None,
                  timeout: Optional[float] = None) -> Union[Partition, DirectionAnswer]:
        """Every direction and minimal subset of parts that separates the assembly by one
        translation (``apart partition``); ``first=True`` stops at the first solution;
        ``direction=(x, y, z)`` answers one direction's blocking graph instead
        (a :class:`DirectionAnswer`).

        The listing is bounded as the command line's: at most ``limit`` moving sets
        (default 20, ``--limit``), each with at most ``max_per_set`` solutions of each
        kind, face, edge and vertex (default 5); ``None`` means these defaults.
        ``all=True`` lists every moving set and every solution (``--all``; assemblies
        of many loose parts have millions, which may not fit in memory), and takes no
        ``limit`` or ``max_per_set``. Every solution is counted either way
        (``solution_count``, each group's counts; ``truncated`` says whether some are
        not listed). ``max_solutions`` stops the search once that many are listed
        (the counts then cover only what was found).

        ``progress`` is a callable ``(phase, done, total)`` or True for a tqdm bar;
        ``timeout`` (seconds) stops with the partial answer, as does the memory budget
        (:func:`apart.set_memory_budget`; ``status`` is then ``"out of memory"``)."""
        d = None
        if direction is not None:
            arr = _real_array(direction, "direction")
            if arr.shape != (3,):
                raise InputError(f"direction must be three numbers, not {direction!r}")
            if not np.isfinite(arr).all() or not arr.any():
                raise InputError(f"direction must be three finite numbers, not all zero, not {direction!r}")
            d = [float(x) for x in arr]
        for label, v in (("max_solutions", max_solutions), ("max_per_set", max_per_set),
                         ("limit", limit)):
            if v is not None and (isinstance(v, bool) or not isinstance(v, int) or v < 1):
                raise InputError(f"{label} must be an integer of 1 or more, not {v!r}")
        if all and (limit is not None or max_per_set is not None):
            raise InputError("all=True lists every solution: it takes no limit or max_per_set")
        raw = json.loads(_run(self._inner.partition_json, progress, first=bool(first),
                              direction=d, max_solutions=max_solutions,
                              max_per_set=max_per_set, limit=limit, all=bool(all),
                              timeout=_timeout(timeout)))
        return DirectionAnswer(raw) if d is not None else Partition(raw)

    def sequence(self, base: Optional[str] = None, *, first: bool = False,
                 prefer_single: bool = False,
                 prefer_connected: bool = False, prefer_axes: bool = False,
                 max_depth: Optional[int] = None, growth: bool = False,
                 ranking: str = "auto",
                 progress: ProgressArg = None, timeout: Optional[float] = None) -> Sequence:
        """A complete disassembly plan by recursive two-handed partitioning
        (``apart sequence``): ``base`` never moves; the ``prefer_*`` options rank the
        steps as the command line's flags do; ``max_depth`` leaves subassemblies below
        whole; ``growth`` computes each step's largest uniform growth. ``ranking``
        (``apart sequence --ranking``) says how each step is chosen: ``"auto"`` ranks
        small subassemblies over their full motion space and larger ones by the local
        rules (a single part's widest-clearance face, then sets along likely
        directions, the full motion space only when nothing simpler splits them),
        ``"full"`` ranks every subassembly in full, ``"local"`` always takes the local
        rules; each step's ``rule`` says which chose it. ``first``
        (``apart sequence --first``) splits each subassembly along the first likely
        direction that frees a subset, without ranking (much faster on tessellated
        parts; not with ``prefer_*``, ``growth`` or ``ranking``). Iterate the result for
        its steps."""
        if max_depth is not None and (isinstance(max_depth, bool) or not isinstance(max_depth, int) or max_depth < 1):
            raise InputError(f"max_depth must be an integer of 1 or more, not {max_depth!r}")
        if ranking not in ("auto", "full", "local"):
            raise InputError(f"ranking must be 'auto', 'full' or 'local', not {ranking!r}")
        if first and (prefer_single or prefer_connected or prefer_axes or growth):
            raise InputError("first=True ranks no steps: it takes no prefer_* options and no growth")
        if first and ranking != "auto":
            raise InputError("first=True ranks no steps: it takes no ranking")
        text, plan = _run(self._inner.sequence_json, progress, base=base, first=bool(first),
                          prefer_single=bool(prefer_single),
                          prefer_connected=bool(prefer_connected),
                          prefer_axes=bool(prefer_axes), max_depth=max_depth,
                          growth=bool(growth), timeout=_timeout(timeout), ranking=ranking)
        return Sequence(json.loads(text), plan)

    def render(self, path: PathLike, *, format: Optional[str] = None,
               projection: str = "equal-area", progress: ProgressArg = None,
               timeout: Optional[float] = None) -> None:
        """Writes the picture of the motion-space sphere (``apart partition --svg`` or
        ``--png``): both hemispheres, the blocked regions shaded by how many pairs block
        them, every solution marked. ``format`` is ``"svg"`` or ``"png"`` (default: from
        the file's extension); ``projection`` is ``"equal-area"`` or ``"orthographic"``.
        The file is the command line's, byte for byte."""
        fspath = os.fspath(path)
        fmt = (format or os.path.splitext(fspath)[1].lstrip(".")).lower()
        if fmt not in ("svg", "png"):
            raise InputError(f"render writes svg or png, not {fmt!r} (say format= or use a .svg/.png name)")
        if projection not in ("equal-area", "orthographic"):
            raise InputError(f"projection must be 'equal-area' or 'orthographic', not {projection!r}")
        data = _run(self._inner.motion_space_picture, progress, svg=fmt == "svg",
                    orthographic=projection == "orthographic", timeout=_timeout(timeout))
        with open(fspath, "wb") as f:
            f.write(data)

    def place(self, part: str, *, target: Seq[float] = (0.0, 0.0, 0.0),
              weight: Optional[float] = None, floor_point: Seq[float] = (0.0, 0.0, 0.0),
              region: Optional[Seq[float]] = None, translations: Optional[Seq[float]] = None,
              dtheta: float = 360.0, bases: Optional[Seq[Tuple[float, float]]] = None,
              clearance: Optional[float] = None, candidates: int = 5,
              timeout: Optional[float] = None) -> PlaceResult:
        """Interference-free positions of ``part`` among the other (fixed) parts,
        cheapest first (``apart place ASSEMBLY NAME``): the cost is the squared distance
        of the translation to ``target``, or eq. (1) with ``weight`` in [0, 1] about
        ``floor_point``; ``region=(x0, y0, z0, x1, y1, z1)`` bounds the whole placed
        part (default: every part's box grown by the part's size), or
        ``translations=`` bounds the translation itself; ``dtheta`` (degrees, 0.1 to
        360; 360 keeps the part as given), ``bases`` as (phi, psi) quarter turns in
        degrees, ``clearance`` from the fixed parts, ``candidates`` (1 to 1000) to list.
        The part may be given where it overlaps the others."""
        if isinstance(candidates, bool) or not isinstance(candidates, int) or not 1 <= candidates <= 1000:
            raise InputError(f"candidates must be an integer from 1 to 1000, not {candidates!r}")
        dtheta = _number(dtheta, "dtheta")
        if not 0.1 <= dtheta <= 360:
            raise InputError(f"dtheta must be from 0.1 to 360 degrees, not {dtheta!r}")
        if weight is not None:
            weight = _number(weight, "weight")
            if not 0 <= weight <= 1:
                raise InputError(f"weight must be in [0, 1], not {weight!r}")
        if region is not None and translations is not None:
            raise InputError("give region= or translations=, not both")

        def numbers(v: Any, n: int, what: str) -> List[float]:
            try:
                out = [_number(x, what) for x in v]
            except TypeError:
                raise InputError(f"{what} must be {n} numbers, not {v!r}") from None
            if len(out) != n:
                raise InputError(f"{what} must be {n} numbers, not {v!r}")
            return out

        def box(v: Any, what: str) -> Optional[List[float]]:
            if v is None:
                return None
            b = numbers(v, 6, what)
            if not all(b[i] <= b[i + 3] for i in range(3)):
                raise InputError(f"{what} {tuple(v)!r} is empty (a low corner above the high one)")
            return b

        if clearance is not None and not _number(clearance, "clearance") >= 0:
            raise InputError(f"clearance must be 0 or more, not {clearance!r}")
        raw = json.loads(self._inner.place_json(part=str(part),
                              target=numbers(target, 3, "target"), weight=weight,
                              floor_point=numbers(floor_point, 3, "floor_point"),
                              region=box(region, "region"),
                              translations=box(translations, "translations"),
                              dtheta=dtheta, bases=_quarters(bases),
                              clearance=None if clearance is None else float(clearance),
                              candidates=candidates, timeout=_timeout(timeout)))
        return PlaceResult(raw)

    def disassemble(self, *, axes: bool = False, max_moves: Optional[int] = None,
                    max_states: Optional[int] = None, symmetry: bool = True,
                    progress: ProgressArg = None,
                    timeout: Optional[float] = None) -> Disassembly:
        """A plan of several moves with the puzzle's level (``apart disassemble``):
        finite translations (exact rationals, off the grid), then one to infinity,
        recursively on the separated groups. ``axes`` allows only moves along the axes
        (on voxel puzzles, BurrTools' level); ``max_moves`` (default 200) bounds each
        subassembly's moves, ``max_states`` (default 2,000,000) its search; ``symmetry``
        makes translated copies of one part interchangeable. A plan that is not
        ``complete`` says why in ``verdict`` (exhaustive, or cut off by a bound)."""
        for name, v in (("max_moves", max_moves), ("max_states", max_states)):
            if v is not None and (isinstance(v, bool) or not isinstance(v, int) or v < 1):
                raise InputError(f"{name} must be an integer of 1 or more, not {v!r}")
        raw = json.loads(_run(self._inner.disassemble_json, progress, axes=bool(axes),
                              max_moves=max_moves, max_states=max_states,
                              symmetry=bool(symmetry), timeout=_timeout(timeout)))
        return Disassembly(raw)

    def separate(self, a: str, b: str, *, progress: ProgressArg = None,
                 timeout: Optional[float] = None) -> Separation:
        """Every direction along which part ``a`` leaves part ``b`` (``apart separate``)."""
        raw = json.loads(_run(self._inner.separate_json, progress, a=str(a), b=str(b),
                              timeout=_timeout(timeout)))
        return Separation(raw)

    def stack(self, part: Optional[str] = None, count: int = 10, *, weight: float = 0.5,
              floor: Optional[Seq[float]] = None, floor_z: float = 0.0,
              max_height: Optional[float] = None, dtheta: float = 90.0,
              bases: Optional[Seq[Tuple[float, float]]] = None,
              clearance: Optional[float] = None, max_candidates: int = 500,
              extrapolate: bool = True, progress: ProgressArg = None,
              timeout: Optional[float] = None) -> StackPlan:
        """Stacks ``count`` copies of ``part`` (the only part when None) on a floor
        (``apart stack``): ``weight`` in [0, 1] of eq. (1), ``floor=(x0, y0, x1, y1)``
        (default: a square sized for the count), ``floor_z``, ``max_height``,
        ``dtheta`` (degrees, 0.1 to 360), ``bases`` as (phi, psi) quarter turns in
        degrees, ``clearance`` between parts, ``max_candidates`` per part (1 to
        100000), ``extrapolate`` obstacles between orientations."""
        if part is None:
            if len(self.parts) != 1:
                raise InputError(f"{self.name!r} holds {len(self.parts)} parts; name the one to stack")
            part = self.parts[0]
        if isinstance(count, bool) or not isinstance(count, int) or not 1 <= count <= 1000:
            raise InputError(f"count must be an integer from 1 to 1000, not {count!r}")
        if isinstance(max_candidates, bool) or not isinstance(max_candidates, int) or not 1 <= max_candidates <= 100000:
            raise InputError(f"max_candidates must be an integer from 1 to 100000, not {max_candidates!r}")
        weight, floor_z, dtheta = _number(weight, "weight"), _number(floor_z, "floor_z"), _number(dtheta, "dtheta")
        if not 0 <= weight <= 1:
            raise InputError(f"weight must be in [0, 1], not {weight!r}")
        if not 0.1 <= dtheta <= 360:
            raise InputError(f"dtheta must be from 0.1 to 360 degrees, not {dtheta!r}")
        f = None
        if floor is not None:
            f = [_number(x, "floor") for x in floor]
            if len(f) != 4 or not (f[0] < f[2] and f[1] < f[3]):
                raise InputError(f"floor must be (x0, y0, x1, y1) with x0 < x1 and y0 < y1, not {floor!r}")
        if max_height is not None and not _number(max_height, "max_height") > 0:
            raise InputError(f"max_height must be a positive length, not {max_height!r}")
        if clearance is not None and not _number(clearance, "clearance") >= 0:
            raise InputError(f"clearance must be 0 or more, not {clearance!r}")
        quarters = _quarters(bases)
        raw = json.loads(_run(self._inner.stack_json, progress, part=str(part), count=count,
                              weight=weight, floor=f, floor_z=floor_z,
                              max_height=None if max_height is None else float(max_height),
                              dtheta=dtheta, bases=quarters,
                              clearance=None if clearance is None else float(clearance),
                              max_candidates=max_candidates, extrapolate=bool(extrapolate),
                              timeout=_timeout(timeout)))
        return StackPlan(raw)

    def __repr__(self) -> str:
        state = "valid" if self.valid else "invalid"
        parts = self.parts
        shown = ", ".join(repr(p) for p in parts[:6]) + (", ..." if len(parts) > 6 else "")
        return f"<Assembly {self.name!r}: {len(parts)} parts ({shown}), {state}>"


def _quarters(bases: Optional[Seq[Tuple[float, float]]]) -> Optional[List[Tuple[int, int]]]:
    """Base orientations (phi, psi) in degrees as quarter turns."""
    if bases is None:
        return None
    quarters = []
    for b in bases:
        phi, psi = (_number(x, "bases") for x in b)
        if phi % 90 or psi % 90:
            raise InputError(f"bases: angles must be multiples of 90 degrees, not {b!r}")
        quarters.append((int(phi // 90) % 4, int(psi // 90) % 4))
    return quarters


def _number(v: Any, what: str) -> float:
    """A finite float, or InputError naming ``what``."""
    if isinstance(v, (bool, np.bool_, complex, np.complexfloating, str, bytes)):
        raise InputError(f"{what} must be a real number, not {v!r}")
    try:
        x = float(v)
    except (TypeError, ValueError):
        raise InputError(f"{what} must be a number, not {v!r}") from None
    if not np.isfinite(x):
        raise InputError(f"{what} must be a finite number, not {v!r}")
    return x


def stack(part: Union[PathLike, Assembly], count: int = 10, *, part_name: Optional[str] = None,
          strict: bool = False, grid_bits: Optional[int] = None, **options: Any) -> StackPlan:
    """Stacks ``count`` copies of a part on a floor (``apart stack PART``): ``part`` is a
    mesh file (or folder, with ``part_name``) or an :class:`Assembly`; the options are
    :meth:`Assembly.stack`'s."""
    if not isinstance(part, Assembly):
        opts = _load_options(None, None, grid_bits, strict, False, False)
        inner = _apart.load(os.fspath(part), allow_outside=False, progress=None, timeout=None,
                            decompose_all=True, **opts)
        part = Assembly._wrap(inner)
    return part.stack(part_name, count, **options)


def place(assembly: Union[PathLike, Assembly], part: str, *, strict: bool = False,
          grid_bits: Optional[int] = None, **options: Any) -> PlaceResult:
    """Interference-free positions of ``part`` among the other parts of ``assembly``
    (an :class:`Assembly`, or a path loaded as ``apart place ASSEMBLY NAME`` loads it),
    cheapest first; the options are :meth:`Assembly.place`'s."""
    if not isinstance(assembly, Assembly):
        opts = _load_options(None, None, grid_bits, strict, False, False)
        inner = _apart.load(os.fspath(assembly), allow_outside=False, progress=None,
                            timeout=None, decompose_all=True, **opts)
        assembly = Assembly._wrap(inner)
    return assembly.place(part, **options)


def disassemble(assembly: Union[PathLike, Assembly], **options: Any) -> Disassembly:
    """A plan of several moves with the puzzle's level for ``assembly`` (an
    :class:`Assembly`, or a path loaded as ``apart disassemble`` loads it); the options
    are :meth:`Assembly.disassemble`'s."""
    if not isinstance(assembly, Assembly):
        assembly = load(assembly)
    return assembly.disassemble(**options)


def separate(assembly: Assembly, a: str, b: str, **options: Any) -> Separation:
    """Every direction along which part ``a`` of ``assembly`` leaves part ``b``."""
    return assembly.separate(a, b, **options)
