"""Many assemblies: the lines of ``apart batch``, made in this process.

:func:`assemblies_under` finds the assemblies under a folder as ``apart batch`` does
(every folder with an ``assembly.json`` or mesh files of its own, not descending into
it), and :func:`answer_line` answers one of them with the same fields as that
command's JSON line (``assembly``, ``command``, ``status``, ``parts``, the answer's
counts, ``seconds``, ``error``). :mod:`apart.ray` runs :func:`answer_line` on a Ray
cluster.
"""

from __future__ import annotations

import os
import time
from pathlib import Path
from typing import Any, Dict, List, Optional, Union

from ._core import load
from ._errors import ApartError, InputError, InvalidAssemblyError, StoppedError

#: Mesh file endings the loader reads (as the command line's ``Format::from_path``).
MESH_SUFFIXES = {".off", ".obj", ".stl", ".ply", ".gltf", ".glb"}

#: Statuses of a line, as ``apart batch`` writes them.
STATUSES = ("ok", "interlocked", "invalid input", "timeout", "out of memory", "failed")

#: The answer's fields a line copies (a plan's ``steps`` as their number).
_COPIED = ("parts", "solution_count", "moving_set_count", "interlocked", "complete",
           "steps", "valid", "tolerance", "repairs", "stats")


def assemblies_under(folder: Union[str, os.PathLike]) -> List[Path]:
    """The assemblies under ``folder``, sorted, found as ``apart batch`` finds them."""
    out: List[Path] = []
    stack = [Path(folder)]
    while stack:
        d = stack.pop()
        subdirs, is_assembly = [], False
        for e in d.iterdir():
            if e.name.startswith("."):
                continue
            if e.is_dir() and not e.is_symlink():
                subdirs.append(e)
            elif e.is_file() and (e.name == "assembly.json"
                                  or e.suffix.lower() in MESH_SUFFIXES):
                is_assembly = True
        if is_assembly:
            out.append(d)
        else:
            stack.extend(subdirs)
    return sorted(out, key=lambda p: str(p))


def key_of(folder: Union[str, os.PathLike], assembly: Union[str, os.PathLike]) -> str:
    """An assembly's key in the lines: its path relative to the batch folder."""
    rel = os.path.relpath(assembly, folder)
    return "." if rel in ("", ".") else Path(rel).as_posix()


def answer_line(path: Union[str, os.PathLike], command: str = "partition",
                key: Optional[str] = None, timeout: Optional[float] = None,
                **load_options: Any) -> Dict[str, Any]:
    """One assembly's line: ``command`` (``partition``, ``sequence`` or ``check``) run
    in this process with ``load_options`` (those of :func:`apart.load`), bounded by
    ``timeout`` seconds. Never raises for a bad assembly: the line says what happened."""
    if command not in ("partition", "sequence", "check"):
        raise ValueError(f"command must be partition, sequence or check, not {command!r}")
    t = time.perf_counter()
    line: Dict[str, Any] = {"assembly": key if key is not None else str(path),
                            "command": command}
    answer: Optional[Dict[str, Any]] = None
    try:
        asm = load(path, **load_options)
        if command == "check":
            answer = asm.check().to_dict()
            status = "ok" if asm.valid else "invalid input"
        elif not asm.valid:
            status = "invalid input"
            line["valid"] = False
            errors = [p for p in asm.problems if p.severity == "error"]
            if errors:
                line["error"] = str(errors[0])
        else:
            result = (asm.partition(timeout=timeout) if command == "partition"
                      else asm.sequence(timeout=timeout))
            answer = result.to_dict()
            if answer.get("status") == "timeout":
                status = "timeout"
            elif answer.get("interlocked") or (command == "sequence" and answer.get("stuck")):
                status = "interlocked"
            else:
                status = "ok"
    except (InputError, InvalidAssemblyError) as e:
        status, line["error"] = "invalid input", str(e)
    except StoppedError as e:
        status, line["error"] = "timeout", str(e)
    except MemoryError as e:
        status, line["error"] = "out of memory", str(e)
    except (ApartError, OSError, ValueError) as e:
        status, line["error"] = "failed", str(e)
    line["status"] = status
    if answer is not None:
        for k in _COPIED:
            if k in answer:
                v = answer[k]
                line[k] = len(v) if k == "steps" and isinstance(v, list) else v
    line["seconds"] = time.perf_counter() - t
    return line
