"""apart: how a set of polyhedral parts comes apart, exactly.

Load an assembly (:func:`load`, :meth:`Assembly.from_meshes`,
:meth:`Assembly.from_trimesh`), then ask it: :meth:`Assembly.check`,
:meth:`Assembly.partition`, :meth:`Assembly.sequence`, :func:`separate`. Answers are
typed objects whose ``to_dict()`` is the command line's ``--json`` output. The
geometry is the Rust library's, called through the compiled module ``apart._apart``.

>>> import apart
>>> star = apart.load("examples/split-star")            # doctest: +SKIP
>>> for s in star.partition():                          # doctest: +SKIP
...     print(s.moving, s.exact_direction)
"""

from ._core import UNITS, Assembly, load, separate, stack
from ._errors import (
    ApartError,
    InputError,
    InternalError,
    InvalidAssemblyError,
    Stop,
    StoppedError,
)
from ._results import (
    CheckReport,
    DirectionAnswer,
    MovingSet,
    PartInfo,
    Partition,
    Problem,
    Separation,
    Sequence,
    Solution,
    Placement,
    StackPlan,
    Step,
)

__version__ = "0.1.0"

__all__ = [
    "Assembly",
    "load",
    "separate",
    "stack",
    "UNITS",
    "ApartError",
    "InputError",
    "InvalidAssemblyError",
    "InternalError",
    "Stop",
    "StoppedError",
    "CheckReport",
    "DirectionAnswer",
    "MovingSet",
    "PartInfo",
    "Partition",
    "Problem",
    "Separation",
    "Sequence",
    "Solution",
    "Step",
    "Placement",
    "StackPlan",
]
