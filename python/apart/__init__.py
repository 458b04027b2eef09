"""apart: how a set of polyhedral parts comes apart, exactly.

Load an assembly (:func:`load`, :meth:`Assembly.from_meshes`,
:meth:`Assembly.from_trimesh`), then ask it: :meth:`Assembly.check`,
:meth:`Assembly.partition`, :meth:`Assembly.sequence`, :func:`disassemble`, :func:`separate`,
:func:`place`, :func:`stack`; pictures with :meth:`Assembly.render`,
:meth:`Sequence.to_glb` and :meth:`Sequence.to_html`. STEP assemblies load with
``load("x.step")`` when the ``step`` extra is installed (:mod:`apart.step`). Answers are
typed objects whose ``to_dict()`` is the command line's ``--json`` output. The
geometry is the Rust library's, called through the compiled module ``apart._apart``.

>>> import apart
>>> star = apart.load("examples/split-star")            # doctest: +SKIP
>>> for s in star.partition():                          # doctest: +SKIP
...     print(s.moving, s.exact_direction)
"""

from ._core import (
    UNITS,
    Assembly,
    disassemble,
    load,
    memory_budget,
    memory_in_use,
    place,
    separate,
    set_memory_budget,
    stack,
)
from ._errors import (
    ApartError,
    InputError,
    InternalError,
    InvalidAssemblyError,
    OutOfMemoryBudget,
    Stop,
    StoppedError,
)
from ._results import (
    CheckReport,
    DirectionAnswer,
    Disassembly,
    Move,
    MovingSet,
    PartInfo,
    Partition,
    Problem,
    Separation,
    Sequence,
    Solution,
    Placement,
    PlaceCandidate,
    PlaceResult,
    StackPlan,
    Step,
)

__version__ = "0.1.0"

__all__ = [
    "Assembly",
    "load",
    "disassemble",
    "separate",
    "place",
    "stack",
    "set_memory_budget",
    "memory_budget",
    "memory_in_use",
    "UNITS",
    "ApartError",
    "InputError",
    "InvalidAssemblyError",
    "InternalError",
    "OutOfMemoryBudget",
    "Stop",
    "StoppedError",
    "CheckReport",
    "DirectionAnswer",
    "MovingSet",
    "PartInfo",
    "Partition",
    "Problem",
    "Separation",
    "Disassembly",
    "Move",
    "Sequence",
    "Solution",
    "Step",
    "Placement",
    "PlaceCandidate",
    "PlaceResult",
    "StackPlan",
]
