"""The exceptions of apart: every problem the library reports, with its file, part and
element where the library's problem values name them."""

from __future__ import annotations

import json
from typing import Any, Dict, List, Optional


class ApartError(Exception):
    """Base class of every error apart raises."""

    def __init__(self, message: str, *, file: Optional[str] = None,
                 part: Optional[str] = None, element: Optional[str] = None) -> None:
        super().__init__(message)
        self.message = message
        #: The file the problem was found in (None for arrays, or when unknown).
        self.file = file
        #: The part it belongs to (None when unknown).
        self.part = part
        #: The element: "face 12", "vertex 5", "edge (3, 7) at ..." (None when unknown).
        self.element = element


class InputError(ApartError, ValueError):
    """Bad input: a missing or unreadable file, a mesh that is not a closed solid,
    arrays of the wrong shape or type, a wrong part name or option."""


class InvalidAssemblyError(InputError):
    """Loading found errors, so the assembly cannot be planned. ``problems`` lists every
    problem found; ``file``, ``part`` and ``element`` are the first error's."""

    def __init__(self, message: str, *, problems: Optional[List[Dict[str, Any]]] = None,
                 **where: Any) -> None:
        super().__init__(message, **where)
        from ._results import Problem

        #: Every problem found while loading (errors, warnings and notes).
        self.problems = [Problem._from(p) for p in (problems or [])]


class StoppedError(ApartError, RuntimeError):
    """The run was stopped (timeout or a callback raising :class:`Stop`) before it had
    any answer to return."""


class OutOfMemoryBudget(ApartError, MemoryError):
    """The memory budget (:func:`apart.set_memory_budget`; by default 80 % of the
    machine's memory, as the command line's ``--max-memory``) stopped a call that has no
    partial answer, or the call's heap passed the budget itself: "out of memory budget
    (SIZE) during PHASE: DETAIL". ``phase`` and ``detail`` say where and what;
    ``budget`` is the budget in bytes. The interpreter and earlier results are
    unharmed: a later call (with a larger budget, or on a smaller input) works."""


class InternalError(ApartError, RuntimeError):
    """A bug in apart (a panic caught at the boundary): please report it."""


class Stop(Exception):
    """Raise this from a progress callback to stop the run: the planner returns what it
    found so far (``complete`` is False, ``status`` is ``"stopped"``)."""


def _make(kind: str, message: str, details: str) -> ApartError:
    """Builds the exception ``kind`` (called by the compiled module)."""
    d = json.loads(details)
    where = {k: d.get(k) for k in ("file", "part", "element")}
    if kind == "InvalidAssemblyError":
        return InvalidAssemblyError(message, problems=d.get("problems"), **where)
    cls = {"InputError": InputError, "StoppedError": StoppedError,
           "OutOfMemoryBudget": OutOfMemoryBudget,
           "InternalError": InternalError}.get(kind, ApartError)
    e = cls(message, **where)
    for k, v in d.items():
        if k not in where:
            setattr(e, k, v)
    return e
