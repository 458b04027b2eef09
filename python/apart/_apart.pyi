"""The compiled half of apart (Rust, pyo3): loading and planning, answers as JSON text
with the command line's ``--json`` fields. Use the package ``apart`` instead: it checks
arguments and wraps the answers in typed objects."""

from typing import Callable, List, Optional, Sequence, Tuple, Union

ProgressCallback = Callable[[str, int, int], object]

#: The default bits of a snapped coordinate.
DEFAULT_GRID_BITS: int
#: The bits of a snapped coordinate the grid supports (lowest, highest).
GRID_BITS_RANGE: Tuple[int, int]
#: The default memory budget in bytes (80 % of the machine's memory; None: unknown).
DEFAULT_MEMORY_BUDGET: Optional[int]
#: The smallest memory budget accepted, in bytes.
MIN_MEMORY_BUDGET: int

def set_memory_budget(size: Union[None, int, str]) -> None:
    """Sets the memory budget (bytes, a size such as ``"4G"``, ``"default"``, or None)."""

def memory_budget() -> Optional[int]:
    """The memory budget in bytes (None: none)."""

def memory_in_use() -> int:
    """The extension's live heap in bytes, as the budget counts it."""

class Assembly:
    """A loaded assembly (parts snapped to one grid, every problem found)."""

    @property
    def name(self) -> str:
        """The assembly's name."""
    @property
    def names(self) -> List[str]:
        """The part names, in order."""
    @property
    def valid(self) -> bool:
        """True when no problem found while loading is an error."""
    def check_json(self) -> str:
        """The check report (``apart check --json``)."""
    def require_valid(self) -> None:
        """Raises ``InvalidAssemblyError`` when loading found errors."""
    def partition_json(
        self,
        *,
        first: bool = False,
        direction: Optional[Sequence[float]] = None,
        max_solutions: Optional[int] = None,
        max_per_set: Optional[int] = None,
        limit: Optional[int] = None,
        all: bool = False,
        progress: Optional[ProgressCallback] = None,
        timeout: Optional[float] = None,
    ) -> str:
        """The solutions (listed as the command line lists them: ``limit`` moving sets,
        default 20, ``max_per_set`` of each kind per set, default 5, or every one with
        ``all``), the first, or one direction's blocking graph, as JSON."""
    def sequence_json(
        self,
        *,
        base: Optional[str],
        first: bool,
        prefer_single: bool,
        prefer_connected: bool,
        prefer_axes: bool,
        max_depth: Optional[int],
        growth: bool,
        progress: Optional[ProgressCallback],
        timeout: Optional[float],
        ranking: Optional[str] = None,
    ) -> Tuple[str, Optional["Plan"]]:
        """A disassembly plan, as JSON, with the plan for its pictures (None when
        stopped)."""
    def motion_space_picture(
        self,
        *,
        svg: bool,
        orthographic: bool,
        progress: Optional[ProgressCallback],
        timeout: Optional[float],
    ) -> bytes:
        """The motion-space sphere (``apart partition --svg``/``--png``), as bytes."""
    def place_json(
        self,
        part: str,
        *,
        target: Sequence[float],
        weight: Optional[float],
        floor_point: Sequence[float],
        region: Optional[Sequence[float]],
        translations: Optional[Sequence[float]],
        dtheta: float,
        bases: Optional[List[Tuple[int, int]]],
        clearance: Optional[float],
        candidates: int,
        timeout: Optional[float],
    ) -> str:
        """Positions of ``part`` among the others (``apart place --json``)."""
    def disassemble_json(
        self,
        *,
        axes: bool,
        max_moves: Optional[int],
        max_states: Optional[int],
        symmetry: bool,
        progress: Optional[ProgressCallback],
        timeout: Optional[float],
    ) -> str:
        """A plan of several moves with the puzzle's level, as JSON."""
    def separate_json(
        self,
        a: str,
        b: str,
        *,
        progress: Optional[ProgressCallback],
        timeout: Optional[float],
    ) -> str:
        """Every direction along which part ``a`` leaves part ``b``, as JSON."""

    def stack_json(
        self,
        part: str,
        *,
        count: int,
        weight: float,
        floor: Optional[Sequence[float]],
        floor_z: float,
        max_height: Optional[float],
        dtheta: float,
        bases: Optional[List[Tuple[int, int]]],
        clearance: Optional[float],
        max_candidates: int,
        extrapolate: bool,
        progress: Optional[ProgressCallback],
        timeout: Optional[float],
    ) -> str:
        """A stack of copies of ``part`` on a floor (``apart stack --json``)."""

class Plan:
    """A disassembly plan with its assembly, for its pictures."""

    def glb(self) -> bytes:
        """The animated GLB (``apart sequence --glb``)."""
    def html(self) -> str:
        """The self-contained HTML viewer (``apart sequence --html``)."""

def load(
    path: str,
    *,
    grid_bits: int,
    tolerance: Optional[float],
    tolerance_auto: bool,
    strict: bool,
    one_part_per_file: bool,
    allow_outside: bool,
    verify: bool,
    units: Optional[str],
    progress: Optional[ProgressCallback],
    timeout: Optional[float],
    decompose_all: bool = False,
) -> Assembly:
    """Loads a folder, a mesh file or an ``assembly.json`` manifest (``decompose_all``:
    every non-convex part decomposed, also a single one)."""

def from_meshes(
    name: str,
    parts: List[Tuple[str, bytes, bytes]],
    *,
    grid_bits: int,
    tolerance: Optional[float],
    tolerance_auto: bool,
    strict: bool,
    one_part_per_file: bool,
    verify: bool,
    units: Optional[str],
    progress: Optional[ProgressCallback],
    timeout: Optional[float],
) -> Assembly:
    """An assembly of triangle meshes: per part its name, little-endian float64
    vertices (n x 3) and int64 faces (m x 3) as bytes."""
