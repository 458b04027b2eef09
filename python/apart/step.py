"""STEP assemblies (AP203/AP214) read with OpenCASCADE, through OCP.

``apart.load("x.step")`` calls :func:`load`; ``python -m apart.step IN.step OUTDIR``
(or the ``apart-step`` script) writes an assembly folder the command line reads: one
OFF file per part and an ``assembly.json`` manifest. The command line also reads a
STEP file directly (``apart check x.step``): it runs :func:`emit` in a child Python
(``APART_PYTHON``, else ``python3``), which prints the parts on standard output.

Needs the ``step`` extra: ``pip install './python[step]'`` (the ``cadquery-ocp-novtk`` wheel,
which bundles OpenCASCADE). It is imported only when a STEP file is read.

What is read
    Every solid of the product tree (XCAF: ``STEPCAFControl_Reader`` and
    ``XCAFDoc_ShapeTool``), each placed by the locations of every instance above it
    (nested sub-assemblies compose), named after its instance (or its product when the
    instance has no name). Names are made filesystem-safe (letters, digits, ``.``,
    ``_`` and ``-``) and unique (``-2``, ``-3``, ... in reading order); a product
    holding several solids gives ``name-1``, ``name-2``, ...

Units
    OpenCASCADE converts the file's length unit to its working unit, millimetres;
    :func:`read` returns millimetres unless ``units=`` asks for another of
    :data:`apart.UNITS` (the coordinates are then scaled, and the assembly states that
    unit as the command line's ``--units`` does).

Tessellation
    Each solid is meshed by OpenCASCADE's ``BRepMesh_IncrementalMesh`` with the
    chordal tolerance ``chordal_tolerance`` (a length in the output unit; default
    1/1000 of the diagonal of the whole assembly's bounding box, one value for every
    part) and ``angular_tolerance`` (radians, default 0.5). Faces share their edges'
    points, and the faces of a solid are welded by those points, so each solid is one
    closed triangle mesh. Planar faces get no point inside: their vertices are points of
    their edges (the B-rep's vertices, and points of curved edges).

    Mating curved parts: on a face of a cylinder or a cone, a convex face (a pin: the
    material inside the surface) keeps its chords, which lie inside the surface; on a
    concave face (a hole: the material outside) every mesh vertex is moved away from
    the axis by the factor ``1 / cos(a / 2)``, ``a`` the largest angle about the axis
    spanned by one of the face's triangles, so that every triangle lies outside the
    surface (and a further 2^-24 of the assembly's diagonal, so that snapping to the
    loader's grid cannot close that gap). Both meshes then lie inside their solids' material, and a pin meets its
    hole in the mesh no more than it does in the B-rep, whatever the segment counts and
    phases of the two tessellations (and whether or not they are coaxial). The price is
    a gap: a hole grows by at most about the chordal tolerance (``r (1/cos(a/2) - 1)``),
    a pin shrinks by at most the chordal tolerance. Other curved surfaces (spheres,
    tori, B-splines) are tessellated by chords only: there a mesh may leave its solid by
    up to the chordal tolerance, so two such parts in contact may interpenetrate by up to
    twice the tolerance; ``tolerance=`` (the loader's shrinking) absorbs that.
"""

from __future__ import annotations

import math
import os
import re
import sys
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np

from ._errors import InputError

#: The default angular tolerance of the tessellation, radians.
DEFAULT_ANGULAR_TOLERANCE = 0.5
#: The default chordal tolerance, as a fraction of the assembly's bounding-box diagonal.
DEFAULT_RELATIVE_CHORDAL_TOLERANCE = 1e-3

#: Holes are moved a further 2^-24 of the assembly's diagonal away from their axis:
#: more than the snapping of the default grid (2^30 steps) can take back.
HOLE_MARGIN = 2.0 ** -24

_INSTALL = ("reading STEP files needs OCP (OpenCASCADE): pip install './python[step]', "
            "or pip install cadquery-ocp-novtk")


def _ocp() -> Any:
    """The OCP modules used here, imported on first use."""
    try:
        import OCP  # noqa: F401
    except ImportError as e:
        raise ImportError(f"{_INSTALL} ({e})") from e
    from OCP import (BRep, BRepBndLib, BRepMesh, Bnd, GeomAbs, IFSelect, STEPCAFControl,
                     TCollection, TDataStd, TDF, TDocStd, TopAbs, TopExp, TopLoc, TopoDS,
                     XCAFDoc)
    from OCP import BRepAdaptor, collections
    return dict(BRep=BRep, BRepBndLib=BRepBndLib, BRepMesh=BRepMesh, Bnd=Bnd,
                GeomAbs=GeomAbs, IFSelect=IFSelect, STEPCAFControl=STEPCAFControl,
                TCollection=TCollection, TDataStd=TDataStd, TDF=TDF, TDocStd=TDocStd,
                TopAbs=TopAbs, TopExp=TopExp, TopLoc=TopLoc, TopoDS=TopoDS, XCAFDoc=XCAFDoc,
                BRepAdaptor=BRepAdaptor, collections=collections)


@dataclass
class StepPart:
    """One solid of a STEP assembly, tessellated and placed."""

    name: str
    vertices: np.ndarray
    faces: np.ndarray
    #: The names of the instances from the root down to the solid.
    path: Tuple[str, ...] = ()


@dataclass
class StepAssembly:
    """The parts of a STEP file, with the facts of their reading."""

    name: str
    parts: List[StepPart]
    #: The unit of the coordinates (one of :data:`apart.UNITS`).
    units: str
    #: The unit of the document OpenCASCADE read the file into, in metres (its
    #: coordinates, before the conversion to ``units``; 1e-3: millimetres).
    document_unit_m: float
    chordal_tolerance: float
    angular_tolerance: float
    #: Faces of cylinders and cones whose vertices were moved off the axis (holes).
    concave_faces: int = 0
    notes: List[str] = field(default_factory=list)

    def meshes(self) -> List[Tuple[str, np.ndarray, np.ndarray]]:
        """``(name, vertices, faces)`` of every part, for :meth:`Assembly.from_meshes`."""
        return [(p.name, p.vertices, p.faces) for p in self.parts]


def _label_name(ocp: Any, label: Any) -> Optional[str]:
    n = ocp["TDataStd"].TDataStd_Name()
    if label.FindAttribute(ocp["TDataStd"].TDataStd_Name.GetID_s(), n):
        text = n.Get().ToExtString()
        return text.strip() or None
    return None


def _safe(name: str) -> str:
    """A filesystem-safe name: letters, digits, '.', '_' and '-' (others become '_')."""
    s = re.sub(r"[^A-Za-z0-9._-]+", "_", name).strip("._") or "part"
    return s[:100]


def _solids(ocp: Any, label: Any, loc: Any, path: Tuple[str, ...], out: List[Any]) -> None:
    """Appends (path, solid, location) of every solid under ``label``, its location
    composed with ``loc``."""
    st = ocp["XCAFDoc"].XCAFDoc_ShapeTool
    if st.IsAssembly_s(label):
        comps = ocp["collections"].Sequence_TDF_Label()
        st.GetComponents_s(label, comps, False)
        for i in range(1, comps.Length() + 1):
            comp = comps.Value(i)
            ref = ocp["TDF"].TDF_Label()
            if st.IsReference_s(comp):
                st.GetReferredShape_s(comp, ref)
            else:
                ref = comp
            name = _label_name(ocp, comp) or _label_name(ocp, ref) or "part"
            _solids(ocp, ref, loc.Multiplied(st.GetLocation_s(comp)), path + (name,), out)
        return
    shape = st.GetShape_s(label)
    if not path:
        path = (_label_name(ocp, label) or "part",)
    ta = ocp["TopAbs"]
    found = []
    exp = ocp["TopExp"].TopExp_Explorer(shape, ta.TopAbs_SOLID)
    while exp.More():
        found.append(exp.Current())
        exp.Next()
    for k, solid in enumerate(found):
        p = path if len(found) == 1 else path[:-1] + (f"{path[-1]}-{k + 1}",)
        out.append((p, solid, loc))


def _mesh_solid(ocp: Any, solid: Any, loc: Any, margin: float) -> Tuple[np.ndarray, np.ndarray, int]:
    """The closed triangle mesh of one meshed solid placed by ``loc``: vertices welded
    by equal coordinates (faces share their edges' points), triangles outward, and the
    vertices of concave cylindrical and conical faces moved off the axis."""
    BRep_Tool = ocp["BRep"].BRep_Tool
    ta = ocp["TopAbs"]
    ga = ocp["GeomAbs"]
    placed = solid.Moved(loc)
    index: Dict[Tuple[float, float, float], int] = {}
    points: List[Tuple[float, float, float]] = []
    tris: List[Tuple[int, int, int]] = []
    curved: List[Tuple[Any, List[int], List[Tuple[int, int, int]]]] = []
    exp = ocp["TopExp"].TopExp_Explorer(placed, ta.TopAbs_FACE)
    while exp.More():
        face = ocp["TopoDS"].TopoDS.Face(exp.Current())
        exp.Next()
        floc = ocp["TopLoc"].TopLoc_Location()
        tri = BRep_Tool.Triangulation_s(face, floc)
        if tri is None:
            raise InputError("a face of a solid could not be tessellated")
        trsf = floc.Transformation()
        ids = []
        for i in range(1, tri.NbNodes() + 1):
            p = tri.Node(i).Transformed(trsf)
            key = (p.X(), p.Y(), p.Z())
            k = index.get(key)
            if k is None:
                k = index[key] = len(points)
                points.append(key)
            ids.append(k)
        reverse = face.Orientation() == ta.TopAbs_REVERSED
        face_tris = []
        for i in range(1, tri.NbTriangles() + 1):
            a, b, c = tri.Triangle(i).Get()
            t = (ids[a - 1], ids[c - 1], ids[b - 1]) if reverse else (ids[a - 1], ids[b - 1], ids[c - 1])
            if len(set(t)) == 3:
                face_tris.append(t)
        tris.extend(face_tris)
        kind = ocp["BRepAdaptor"].BRepAdaptor_Surface(face).GetType()
        if kind in (ga.GeomAbs_Cylinder, ga.GeomAbs_Cone):
            s = ocp["BRepAdaptor"].BRepAdaptor_Surface(face)
            ax = (s.Cylinder() if kind == ga.GeomAbs_Cylinder else s.Cone()).Axis()
            curved.append((ax, sorted(set(ids)), face_tris))
    v = np.array(points, dtype=np.float64).reshape(-1, 3)
    f = np.array(tris, dtype=np.int64).reshape(-1, 3)
    return v, f, _push_holes(v, f, curved, margin)


def _push_holes(v: np.ndarray, f: np.ndarray, curved: List[Any], margin: float) -> int:
    """Moves the vertices of every concave face of a cylinder or cone (its triangles
    facing the axis) away from the axis by 1 / cos(a / 2), ``a`` the largest angle
    about the axis one of its triangles spans, and then by ``margin``: each of its
    triangles then lies outside the surface, by at least ``margin`` (which keeps a pin
    that touches the surface from overlapping after snapping). A vertex on several
    concave faces about one axis moves once, by the largest factor. Returns the number
    of faces moved."""
    moves: Dict[int, List[Tuple[np.ndarray, np.ndarray, float]]] = {}
    count = 0
    original = v.copy()
    for ax, ids, face_tris in curved:
        if not face_tris:
            continue
        o = np.array(ax.Location().Coord())
        d = np.array(ax.Direction().Coord())
        t = np.array(face_tris)
        p = original[t]  # (m, 3, 3)
        rel = p - o
        radial = rel - np.einsum("mki,i->mk", rel, d)[..., None] * d
        normals = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
        centre_radial = radial.mean(axis=1)
        if np.einsum("mi,mi->", normals, centre_radial) >= 0:
            continue  # convex (a pin): the chords lie inside the surface
        r = np.linalg.norm(radial, axis=2)
        # A cone's apex lies on the axis: it stays, and spans no angle (the triangles
        # from it to pushed rim points still lie outside, the radius being linear).
        on_axis = r <= 1e-12 * (1 + np.abs(rel).max())
        u = radial / np.where(on_axis, 1.0, r)[..., None]
        cos = np.stack([np.where(on_axis[:, i] | on_axis[:, j], 1.0,
                                 np.einsum("mi,mi->m", u[:, i], u[:, j]))
                        for i, j in ((0, 1), (1, 2), (0, 2))], axis=1)
        span = float(np.arccos(np.clip(cos, -1.0, 1.0)).max())
        if span >= math.pi * 0.99:
            continue  # a triangle across the axis: nothing sensible to push
        factor = 1.0 / math.cos(span / 2)
        count += 1
        for i in ids:
            moves.setdefault(i, []).append((o, d, factor))
    for i, ms in moves.items():
        # One axis: the largest factor once; several axes: each in turn.
        groups: List[Tuple[np.ndarray, np.ndarray, float]] = []
        for o, d, fac in ms:
            for g, (go, gd, gf) in enumerate(groups):
                same = abs(abs(float(np.dot(d, gd))) - 1) < 1e-12 and \
                    np.linalg.norm(np.cross(o - go, gd)) < 1e-9 * (1 + np.linalg.norm(o - go))
                if same:
                    groups[g] = (go, gd, max(gf, fac))
                    break
            else:
                groups.append((o, d, fac))
        x = v[i]
        for o, d, fac in groups:
            rel = x - o
            along = np.dot(rel, d) * d
            radial = rel - along
            r = float(np.linalg.norm(radial))
            if r <= 1e-12 * (1 + float(np.linalg.norm(rel))):
                continue  # a cone's apex
            x = o + along + radial * ((r * fac + margin) / r)
        v[i] = x
    return count


def read(path: "os.PathLike[str] | str", *, chordal_tolerance: Optional[float] = None,
         angular_tolerance: float = DEFAULT_ANGULAR_TOLERANCE,
         units: Optional[str] = None) -> StepAssembly:
    """Reads a STEP assembly and tessellates every solid instance (see the module's
    documentation): ``chordal_tolerance`` in the output unit (default 1/1000 of the
    assembly's bounding-box diagonal), ``angular_tolerance`` in radians, ``units`` the
    output unit (default ``"mm"``, OpenCASCADE's)."""
    from ._core import UNITS

    units = units or "mm"
    if units not in UNITS:
        raise InputError(f"units {units!r} is none of {', '.join(UNITS)}")
    if chordal_tolerance is not None:
        ct = float(chordal_tolerance)
        if not (math.isfinite(ct) and ct > 0):
            raise InputError(f"chordal_tolerance must be a positive length, not {chordal_tolerance!r}")
    at = float(angular_tolerance)
    if not (math.isfinite(at) and 0 < at <= math.pi):
        raise InputError(f"angular_tolerance must be an angle in (0, pi] radians, not {angular_tolerance!r}")
    fspath = os.fspath(path)
    if not os.path.isfile(fspath):
        raise InputError(f"cannot read {fspath}: no such file", file=fspath)
    ocp = _ocp()
    doc = ocp["TDocStd"].TDocStd_Document(ocp["TCollection"].TCollection_ExtendedString("XCAF"))
    reader = ocp["STEPCAFControl"].STEPCAFControl_Reader()
    reader.SetNameMode(True)
    if reader.ReadFile(fspath) != ocp["IFSelect"].IFSelect_RetDone:
        raise InputError(f"cannot read {fspath}: not a STEP file OpenCASCADE can read", file=fspath)
    if not reader.Transfer(doc):
        raise InputError(f"cannot read {fspath}: OpenCASCADE could not transfer its shapes", file=fspath)
    st = ocp["XCAFDoc"].XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())
    # The document's unit, in metres (its coordinates are in it).
    unit_m = 1e-3
    got = ocp["XCAFDoc"].XCAFDoc_DocumentTool.GetLengthUnit_s(doc, 0.0)
    if isinstance(got, tuple) and got[0] and got[1] > 0:
        unit_m = float(got[1])
    scale = unit_m / UNITS[units]
    roots = ocp["collections"].Sequence_TDF_Label()
    st.GetFreeShapes(roots)
    found: List[Any] = []
    for i in range(1, roots.Length() + 1):
        _solids(ocp, roots.Value(i), ocp["TopLoc"].TopLoc_Location(), (), found)
    if not found:
        raise InputError(f"{fspath} holds no solid", file=fspath)
    # One chordal tolerance for every part, in the document's unit.
    box = ocp["Bnd"].Bnd_Box()
    for _, solid, loc in found:
        ocp["BRepBndLib"].BRepBndLib.Add_s(solid.Moved(loc), box)
    lo, hi = box.CornerMin(), box.CornerMax()
    x0, y0, z0, x1, y1, z1 = lo.X(), lo.Y(), lo.Z(), hi.X(), hi.Y(), hi.Z()
    diag = math.dist((x0, y0, z0), (x1, y1, z1))
    ct_doc = (diag * DEFAULT_RELATIVE_CHORDAL_TOLERANCE if chordal_tolerance is None
              else float(chordal_tolerance) / scale)
    parts: List[StepPart] = []
    names: Dict[str, int] = {}
    concave = 0
    for p, solid, loc in found:
        # Instances of one product share its triangulation (meshed once: faces already
        # meshed to this tolerance are kept).
        ocp["BRepMesh"].BRepMesh_IncrementalMesh(solid, ct_doc, False, at, False)
        v, f, c = _mesh_solid(ocp, solid, loc, diag * HOLE_MARGIN)
        concave += c
        name = _safe(p[-1])
        n = names.get(name, 0) + 1
        names[name] = n
        if n > 1:
            name = f"{name}-{n}"
            while name in names:
                n += 1
                name = f"{_safe(p[-1])}-{n}"
            names[name] = 1
        parts.append(StepPart(name=name, vertices=v * scale, faces=f, path=tuple(p)))
    stem = os.path.splitext(os.path.basename(fspath))[0]
    return StepAssembly(name=_safe(stem), parts=parts, units=units, document_unit_m=unit_m,
                        chordal_tolerance=ct_doc * scale, angular_tolerance=at,
                        concave_faces=concave)


def load(path: "os.PathLike[str] | str", *, chordal_tolerance: Optional[float] = None,
         angular_tolerance: float = DEFAULT_ANGULAR_TOLERANCE, units: Optional[str] = None,
         **options: Any) -> Any:
    """A STEP assembly as an :class:`apart.Assembly`: :func:`read`, then
    :meth:`Assembly.from_meshes` with ``options`` (``tolerance``, ``strict``,
    ``grid_bits``, ``progress``, ...). ``units`` is the unit of the coordinates and of
    ``tolerance`` (default millimetres)."""
    from ._core import Assembly

    s = read(path, chordal_tolerance=chordal_tolerance, angular_tolerance=angular_tolerance,
             units=units)
    options.pop("one_part_per_file", None)
    options.pop("allow_outside", None)
    return Assembly.from_meshes(s.meshes(), name=s.name, units=s.units, **options)


def _off(v: np.ndarray, f: np.ndarray) -> str:
    lines = ["OFF", f"{len(v)} {len(f)} 0"]
    lines += [" ".join(repr(float(c)) for c in p) for p in v]
    lines += ["3 " + " ".join(str(int(i)) for i in t) for t in f]
    return "\n".join(lines) + "\n"


def write_folder(step: StepAssembly, outdir: "os.PathLike[str] | str") -> str:
    """Writes ``step`` as an assembly folder the command line reads: ``NAME.off`` per
    part (every coordinate in its shortest exact decimal) and ``assembly.json``.
    Returns the manifest's path."""
    import json

    out = os.fspath(outdir)
    os.makedirs(out, exist_ok=True)
    entries = []
    for p in step.parts:
        file = f"{p.name}.off"
        with open(os.path.join(out, file), "w") as fh:
            fh.write(_off(p.vertices, p.faces))
        entries.append({"name": p.name, "mesh": file})
    manifest = os.path.join(out, "assembly.json")
    with open(manifest, "w") as fh:
        json.dump({"name": step.name, "parts": entries,
                   "units": step.units, "chordal_tolerance": step.chordal_tolerance},
                  fh, indent=1)
        fh.write("\n")
    return manifest


#: Exit status of :func:`emit` when this Python cannot read STEP files (no OCP).
EXIT_NEEDS_EXTRA = 3


def emit(argv: Optional[Sequence[str]] = None) -> int:
    """The command line's STEP reader (``apart check x.step`` runs it in a child Python):
    ``IN.step [--chordal-tolerance L] [--angular-tolerance RAD] [--units U]`` read as
    :func:`read` reads it, printed on standard output as one JSON object: ``name``,
    ``units``, ``chordal_tolerance``, ``angular_tolerance`` and ``parts``, each with its
    ``name``, ``vertices`` (the 3n coordinates as the bit patterns of IEEE 754 doubles,
    unsigned 64-bit integers, so that the command line gets the very numbers
    :func:`load` hands to the loader) and ``triangles`` (3m vertex indices). A file
    that cannot be read: its message on standard error, status 1; no OCP: status
    :data:`EXIT_NEEDS_EXTRA`."""
    import argparse
    import json

    ap = argparse.ArgumentParser(prog="apart-step-emit")
    ap.add_argument("input")
    ap.add_argument("--chordal-tolerance", type=float, default=None)
    ap.add_argument("--angular-tolerance", type=float, default=DEFAULT_ANGULAR_TOLERANCE)
    ap.add_argument("--units", default="mm")
    a = ap.parse_args(argv)
    # Standard output carries the answer alone: whatever OpenCASCADE (or anything else)
    # prints while reading goes to standard error.
    sys.stdout.flush()
    saved, stdout = os.dup(1), sys.stdout
    os.dup2(2, 1)
    sys.stdout = sys.stderr
    try:
        s = read(a.input, chordal_tolerance=a.chordal_tolerance,
                 angular_tolerance=a.angular_tolerance, units=a.units)
    except ImportError as e:
        print(e, file=sys.stderr)
        return EXIT_NEEDS_EXTRA
    except InputError as e:
        print(e, file=sys.stderr)
        return 1
    finally:
        sys.stdout = stdout
        os.dup2(saved, 1)
        os.close(saved)
    parts = [{"name": p.name,
              "vertices": np.ascontiguousarray(p.vertices, dtype="<f8").view("<u8").ravel().tolist(),
              "triangles": np.asarray(p.faces, dtype=np.int64).ravel().tolist()}
             for p in s.parts]
    json.dump({"name": s.name, "units": s.units, "chordal_tolerance": s.chordal_tolerance,
               "angular_tolerance": s.angular_tolerance, "parts": parts},
              sys.stdout, separators=(",", ":"))
    sys.stdout.write("\n")
    sys.stdout.flush()
    return 0


def main(argv: Optional[Sequence[str]] = None) -> int:
    """``python -m apart.step IN.step OUTDIR [--chordal-tolerance L]
    [--angular-tolerance RAD] [--units mm]``."""
    import argparse

    ap = argparse.ArgumentParser(
        prog="python -m apart.step",
        description="Converts a STEP assembly into an assembly folder (one OFF mesh per "
                    "solid instance, placed, and assembly.json) that the apart command line reads.")
    ap.add_argument("input", help="the STEP file (.step, .stp)")
    ap.add_argument("outdir", help="the folder to write (created if missing)")
    ap.add_argument("--chordal-tolerance", type=float, default=None, metavar="L",
                    help="largest distance between a chord and its surface, in the output "
                         "unit (default: 1/1000 of the assembly's bounding-box diagonal)")
    ap.add_argument("--angular-tolerance", type=float, default=DEFAULT_ANGULAR_TOLERANCE,
                    metavar="RAD", help="largest angle between adjacent chords (radians)")
    ap.add_argument("--units", default="mm", help="unit of the written coordinates (default mm)")
    a = ap.parse_args(argv)
    try:
        s = read(a.input, chordal_tolerance=a.chordal_tolerance,
                 angular_tolerance=a.angular_tolerance, units=a.units)
    except (InputError, ImportError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 1
    manifest = write_folder(s, a.outdir)
    print(f"{len(s.parts)} parts in {s.units} (chordal tolerance {s.chordal_tolerance:g} {s.units}) "
          f"-> {manifest}; run: apart check {a.outdir} --units {s.units}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
