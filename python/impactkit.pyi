"""Type stubs of the impactkit package: the compiled module's names
(python/src/*.cpp) and the tables of python/impactkit/_tables.py;
docstrings there. Installed as impactkit/__init__.pyi, beside py.typed."""

from os import PathLike
from typing import TYPE_CHECKING, Any, Callable, Iterator, Literal, Optional, TypedDict, overload

import numpy as np
import numpy.typing as npt

if TYPE_CHECKING:  # optional: only the tables need them
    import pandas
    import xarray

__version__: str

FloatArray = npt.NDArray[np.float64]
ComplexArray = npt.NDArray[np.complex128]
BoolArray = npt.NDArray[np.bool_]
IntArray = npt.NDArray[np.int64]

Termination = Literal[
    "converged", "no_convergence", "failure", "completed", "stopped", "event_limit", "work_limit",
    "stalled", "no_impact", "grazing", "sticking", "other_stop", "not_released", "no_chatter",
    "no_sticking", "no_release", "met_while_held", "early_release", "parameter_bound",
    "branch_point", "max_points", "corrector_failed", "closed"
]

class ProgressReport(TypedDict):
    stage: Literal["sweep", "branch", "curve", "diagram", "grid"]
    done: int
    total: int
    parameter: Optional[float]
    parameter2: Optional[float]

Progress = bool | Callable[[ProgressReport], None]

class NumericalError(RuntimeError): ...

# Stub only (no such class at run time): the mapping protocol every option
# set (SweepOptions, ContinuationOptions, ...) has, for `f(..., **options)`.
class _OptionSet:
    def keys(self) -> list[str]: ...
    def __getitem__(self, key: str) -> Any: ...
    def __iter__(self) -> Iterator[str]: ...
    def __len__(self) -> int: ...
    def to_dict(self) -> dict[str, Any]: ...

class StopDict(TypedDict, total=False):
    dof: int
    side: Literal["upper", "lower"]
    position: float
    restitution: float

class System:
    def __init__(self) -> None: ...
    @staticmethod
    def paper(omega: float = 1.0) -> System: ...
    @staticmethod
    def chain(
        *,
        n: int = 2,
        m: float = 1.0,
        k: float = 1.0,
        c: float = 0.1,
        forcing: Optional[npt.ArrayLike] = None,
        omega: float = 1.0,
        xs: float = 0.1,
        r: float = 0.7,
    ) -> System: ...
    @staticmethod
    def general(
        mass: npt.ArrayLike,
        damping: npt.ArrayLike,
        stiffness: npt.ArrayLike,
        forcing: npt.ArrayLike,
        *,
        omega: float = 1.0,
        xs: float = 0.1,
        r: float = 0.7,
        contact_dof: Optional[int] = None,
    ) -> System: ...
    @staticmethod
    def from_file(path: str | PathLike[str]) -> System: ...
    @property
    def dof(self) -> int: ...
    @property
    def mass(self) -> FloatArray: ...
    @property
    def damping(self) -> FloatArray: ...
    @property
    def stiffness(self) -> FloatArray: ...
    @property
    def forcing(self) -> FloatArray: ...
    @property
    def stops(self) -> list[StopDict]: ...
    def with_stops(self, stops: list[StopDict]) -> System: ...
    @property
    def is_chain(self) -> bool: ...
    @property
    def forcing_period(self) -> float: ...
    def parameter_names(self) -> list[str]: ...
    def get(self, name: str) -> float: ...
    def set(self, name: str, value: float) -> None: ...
    def with_parameter(self, name: str, value: float) -> System: ...
    def __getitem__(self, name: str) -> float: ...
    def __setitem__(self, name: str, value: float) -> None: ...
    def validate(self) -> None: ...
    def to_json(self) -> str: ...
    def __copy__(self) -> System: ...
    def __deepcopy__(self, memo: dict[int, Any]) -> System: ...

class Samples(TypedDict):
    t: FloatArray
    x: FloatArray
    v: FloatArray
    stuck: BoolArray
    event: npt.NDArray[np.str_]

class Impacts(TypedDict):
    t: FloatArray
    phase: FloatArray
    velocity: FloatArray
    stop: IntArray
    x: FloatArray
    v: FloatArray

class State(TypedDict):
    t: float
    x: FloatArray
    v: FloatArray
    stuck: bool

class Simulation(TypedDict):
    samples: Samples
    impacts: Impacts
    strobe: Samples
    sticking: FloatArray
    termination: Termination
    chatter_jumps: int
    landings: int
    stuck_time: float
    seconds: float
    final_state: State

class SimulationResult(dict[str, Any]):
    """simulate's result: the keys of Simulation, and its tables."""
    options: dict[str, Any]
    provenance: dict[str, str]
    def samples_to_pandas(self) -> pandas.DataFrame: ...
    def impacts_to_pandas(self) -> pandas.DataFrame: ...

def simulate(
    system: System,
    t_end: float,
    *,
    x0: Optional[npt.ArrayLike] = None,
    v0: Optional[npt.ArrayLike] = None,
    record_from: float = 0.0,
    dt: float = 0.0,
    chatter: Literal["accumulation", "threshold"] = "accumulation",
    chatter_span: float = 1e-4,
    chatter_threshold: float = 1e-4,
    bounce_height_resolution: float = 1e-10,
    max_events_per_period: int = 100_000,
    max_events: int = 200_000_000,
    events: bool = False,
) -> SimulationResult: ...

class Orbit:
    @property
    def section(self) -> Literal["impact", "release"]: ...
    @property
    def p(self) -> int: ...
    @property
    def q(self) -> int: ...
    @property
    def releases(self) -> int: ...
    @property
    def stick_phases(self) -> FloatArray: ...
    @property
    def release_phases(self) -> FloatArray: ...
    @property
    def stuck_durations(self) -> FloatArray: ...
    @property
    def stuck_stops(self) -> IntArray: ...
    @property
    def contact_margin(self) -> Optional[float]: ...
    @property
    def omega(self) -> float: ...
    @property
    def eta(self) -> FloatArray: ...
    @property
    def jacobian(self) -> FloatArray: ...
    @property
    def multipliers(self) -> ComplexArray: ...
    @property
    def stable(self) -> bool: ...
    @property
    def residual(self) -> float: ...
    @property
    def impact_times(self) -> FloatArray: ...
    @property
    def impact_phases(self) -> FloatArray: ...
    @property
    def impact_velocities(self) -> FloatArray: ...
    @property
    def impact_stops(self) -> IntArray: ...
    @property
    def clearance(self) -> Optional[float]: ...

def find_orbit(
    system: System,
    *,
    p: Optional[int] = None,
    q: Optional[int] = None,
    releases: Optional[int] = None,
    seed: Optional[npt.ArrayLike] = None,
    stop: int = 0,
    jacobian: Literal["analytic", "finite_difference"] = "analytic",
    residual_tolerance: float = 1e-11,
    max_iterations: int = 50,
    least_squares_fallback: bool = True,
    transient: int = 500,
) -> Orbit: ...

SpecialPointType = Literal[
    "fold", "period_doubling", "neimark_sacker", "grazing", "sticking", "branch_point",
    "pitchfork", "no_sticking", "early_release", "user_test"
]

class SpecialPoint:
    @property
    def type(self) -> SpecialPointType: ...
    @property
    def user_test(self) -> str: ...
    @property
    def parameter(self) -> float: ...
    @property
    def multiplier(self) -> complex: ...
    @property
    def multipliers(self) -> ComplexArray: ...
    @property
    def eigenvector(self) -> FloatArray: ...
    @property
    def monitor(self) -> float: ...
    @property
    def vanishing_impact(self) -> int: ...
    @property
    def orbit(self) -> Orbit: ...
    @property
    def normal_form(self) -> Optional[dict[str, Any]]: ...
    @property
    def normal_form_note(self) -> str: ...
    def describe(self, parameter_name: str) -> str: ...

class UnlocatedZero:
    @property
    def type(self) -> Literal["fold", "period_doubling"]: ...
    @property
    def values(self) -> tuple[float, float]: ...
    def describe(self, parameter_name: str) -> str: ...

class Branch:
    @property
    def parameter(self) -> str: ...
    @property
    def section(self) -> Literal["impact", "release"]: ...
    @property
    def p(self) -> int: ...
    @property
    def q(self) -> int: ...
    @property
    def releases(self) -> int: ...
    @property
    def values(self) -> FloatArray: ...
    @property
    def arclength(self) -> FloatArray: ...
    @property
    def eta(self) -> FloatArray: ...
    @property
    def multipliers(self) -> ComplexArray: ...
    @property
    def stable(self) -> BoolArray: ...
    @property
    def orbits(self) -> list[Orbit]: ...
    @property
    def special_points(self) -> list[SpecialPoint]: ...
    @property
    def unlocated(self) -> list[UnlocatedZero]: ...
    @property
    def end(self) -> Termination: ...
    @property
    def end_message(self) -> str: ...
    @property
    def begin(self) -> Optional[Termination]: ...
    @property
    def begin_message(self) -> str: ...
    @property
    def seconds(self) -> float: ...
    def to_json(self) -> str: ...
    def write_csv(self, path: str | PathLike[str]) -> None: ...
    def to_pandas(self) -> pandas.DataFrame: ...
    def special_points_to_pandas(self) -> pandas.DataFrame: ...
    def __len__(self) -> int: ...

class BranchStart:
    @property
    def system(self) -> System: ...
    @property
    def orbit(self) -> Orbit: ...
    @property
    def direction(self) -> FloatArray: ...

class GrazingSeed:
    @property
    def system(self) -> System: ...
    @property
    def p(self) -> int: ...
    @property
    def q(self) -> int: ...
    @property
    def releases(self) -> int: ...
    @property
    def stop(self) -> int: ...
    @property
    def eta(self) -> FloatArray: ...

class ContinuationOptions(_OptionSet):
    def __init__(
        self,
        *,
        parameter: str = "omega",
        from_: Optional[float] = None,
        to: Optional[float] = None,
        direction: Literal["increasing", "decreasing", "both"] = "increasing",
        initial_step: float = 0.01,
        min_step: float = 1e-7,
        max_step: float = 0.02,
        max_points: int = 10000,
        locate_bifurcations: bool = True,
    ) -> None: ...
    parameter: str
    from_: Optional[float]
    to: Optional[float]
    direction: Literal["increasing", "decreasing", "both"]
    initial_step: float
    min_step: float
    max_step: float
    max_points: int
    locate_bifurcations: bool

@overload
def continue_branch(
    system: System,
    orbit: Orbit,
    *,
    parameter: str = "omega",
    from_: float,
    to: float,
    direction: Literal["increasing", "decreasing", "both"] = "increasing",
    initial_step: float = 0.01,
    min_step: float = 1e-7,
    max_step: float = 0.02,
    max_points: int = 10000,
    locate_bifurcations: bool = True,
    user_tests: Optional[dict[str, Callable[[Orbit], float]]] = None,
    progress: Progress = False,
) -> Branch: ...
@overload
def continue_branch(
    start: BranchStart,
    *,
    parameter: str = "omega",
    from_: float,
    to: float,
    direction: Literal["increasing", "decreasing", "both"] = "increasing",
    initial_step: float = 0.01,
    min_step: float = 1e-7,
    max_step: float = 0.02,
    max_points: int = 10000,
    locate_bifurcations: bool = True,
    user_tests: Optional[dict[str, Callable[[Orbit], float]]] = None,
    progress: Progress = False,
) -> Branch: ...
def doubled_branch_start(
    system: System, branch: Branch, period_doubling: SpecialPoint, *, offset: float = 1e-3
) -> Optional[BranchStart]: ...
def seeds_at_grazing(
    system: System, branch: Branch, grazing: SpecialPoint, *, offset: float = 1e-3
) -> list[GrazingSeed]: ...

class Sweep(TypedDict):
    values: FloatArray
    kind: list[str]
    description: list[str]
    p: IntArray
    q: IntArray
    range_contact: FloatArray
    range_first: FloatArray
    range_offsets: IntArray
    impact_offsets: IntArray
    impact_t: FloatArray
    impact_phase: FloatArray
    impact_velocity: FloatArray
    impact_stop: IntArray
    summary_csv: str
    termination: Termination
    report: str

class SweepResult(dict[str, Any]):
    """sweep's result: the keys of Sweep, and its tables."""
    options: dict[str, Any]
    provenance: dict[str, str]
    def to_pandas(self) -> pandas.DataFrame: ...
    def impacts_to_pandas(self) -> pandas.DataFrame: ...

class SweepOptions(_OptionSet):
    def __init__(
        self,
        *,
        parameter: str = "omega",
        from_: float = 0.1,
        to: float = 2.5,
        steps: int = 2401,
        transient_periods: int = 500,
        recorded_periods: int = 100,
        threads: int = 1,
        each_from: Literal["previous", "rest"] = "previous",
        chunk_values: int = 100,
        full_transient: bool = False,
    ) -> None: ...
    parameter: str
    from_: float
    to: float
    steps: int
    transient_periods: int
    recorded_periods: int
    threads: int
    each_from: Literal["previous", "rest"]
    chunk_values: int
    full_transient: bool

def sweep(
    system: System,
    *,
    parameter: str = "omega",
    from_: float = 0.1,
    to: float = 2.5,
    steps: int = 2401,
    transient_periods: int = 500,
    recorded_periods: int = 100,
    threads: int = 1,
    each_from: Literal["previous", "rest"] = "previous",
    chunk_values: int = 100,
    full_transient: bool = False,
    progress: Progress = False,
) -> SweepResult: ...

class Lyapunov(TypedDict):
    exponents: FloatArray
    largest: float
    impacts_used: int
    time_span: float

def lyapunov(
    system: System, eta: npt.ArrayLike, *, impacts: int = 2000, transient_impacts: int = 200
) -> Lyapunov: ...

class Peak(TypedDict):
    dof: int
    omega: float
    range: float

class Resonance(TypedDict):
    omega: FloatArray
    range: FloatArray
    phase: FloatArray
    peaks: list[Peak]

def resonance(system: System, *, from_: float, to: float, steps: int) -> Resonance: ...

class DiagramNode:
    @property
    def type(self) -> str: ...
    @property
    def user_test(self) -> str: ...
    @property
    def parameter(self) -> float: ...
    @property
    def multiplier(self) -> complex: ...
    @property
    def multipliers(self) -> ComplexArray: ...
    @property
    def monitor(self) -> float: ...
    @property
    def vanishing_impact(self) -> int: ...
    @property
    def normal_form(self) -> Optional[dict[str, Any]]: ...
    @property
    def p(self) -> int: ...
    @property
    def q(self) -> int: ...
    @property
    def branch(self) -> int: ...
    @property
    def eta(self) -> FloatArray: ...

class DiagramBranch:
    @property
    def branch(self) -> Branch: ...
    @property
    def origin(self) -> str: ...
    @property
    def depth(self) -> int: ...
    @property
    def parent(self) -> int: ...

class Diagram:
    @property
    def parameter(self) -> str: ...
    @property
    def nodes(self) -> list[DiagramNode]: ...
    @property
    def branches(self) -> list[DiagramBranch]: ...
    @property
    def edge_from(self) -> IntArray: ...
    @property
    def edge_to(self) -> IntArray: ...
    @property
    def edge_branch(self) -> IntArray: ...
    @property
    def edge_first(self) -> IntArray: ...
    @property
    def edge_last(self) -> IntArray: ...
    @property
    def duplicate_starts(self) -> int: ...
    @property
    def failed_starts(self) -> int: ...
    @property
    def termination(self) -> Termination: ...
    @property
    def message(self) -> str: ...
    @property
    def seconds(self) -> float: ...
    def to_json(self) -> str: ...
    def brief_report(self) -> str: ...
    def nodes_to_pandas(self) -> pandas.DataFrame: ...
    def edges_to_pandas(self) -> pandas.DataFrame: ...

class DiagramOptions(_OptionSet):
    def __init__(
        self,
        *,
        parameter: str = "omega",
        from_: Optional[float] = None,
        to: Optional[float] = None,
        initial_step: float = 0.01,
        max_step: float = 0.02,
        max_points: int = 10000,
        max_depth: int = 10,
        max_branches: int = 200,
        threads: int = 1,
        switch_period_doubling: bool = True,
        switch_grazing: bool = True,
        switch_branch_points: bool = True,
        switch_pitchforks: bool = True,
    ) -> None: ...
    parameter: str
    from_: Optional[float]
    to: Optional[float]
    initial_step: float
    max_step: float
    max_points: int
    max_depth: int
    max_branches: int
    threads: int
    switch_period_doubling: bool
    switch_grazing: bool
    switch_branch_points: bool
    switch_pitchforks: bool

def trace_diagram(
    seeds: list[tuple[System, Orbit]],
    *,
    parameter: str = "omega",
    from_: float,
    to: float,
    initial_step: float = 0.01,
    max_step: float = 0.02,
    max_points: int = 10000,
    max_depth: int = 10,
    max_branches: int = 200,
    threads: int = 1,
    switch_period_doubling: bool = True,
    switch_grazing: bool = True,
    switch_branch_points: bool = True,
    switch_pitchforks: bool = True,
    user_tests: Optional[dict[str, Callable[[Orbit], float]]] = None,
    progress: Progress = False,
) -> Diagram: ...

def swept_diagram(
    system: System,
    *,
    parameter: str = "omega",
    from_: float,
    to: float,
    sweep_values: int = 481,
    sweep_transient: int = 300,
    sweep_record: int = 40,
    max_q: int = 16,
    refine: int = 5,
    max_depth: int = 10,
    max_branches: int = 200,
    threads: int = 1,
    progress: Progress = False,
) -> Diagram: ...

class MapOptions(_OptionSet):
    def __init__(
        self,
        *,
        parameter: str = "omega",
        from_: Optional[float] = None,
        to: Optional[float] = None,
        steps: Optional[int] = None,
        parameter2: str = "r",
        from2: Optional[float] = None,
        to2: Optional[float] = None,
        steps2: Optional[int] = None,
        transient_periods: int = 500,
        recorded_periods: int = 100,
        threads: int = 1,
        each_from: Literal["previous", "rest"] = "previous",
        chunk_values: int = 100,
        full_transient: bool = False,
    ) -> None: ...
    parameter: str
    from_: Optional[float]
    to: Optional[float]
    steps: Optional[int]
    parameter2: str
    from2: Optional[float]
    to2: Optional[float]
    steps2: Optional[int]
    transient_periods: int
    recorded_periods: int
    threads: int
    each_from: Literal["previous", "rest"]
    chunk_values: int
    full_transient: bool

def parameter_map(
    system: System,
    *,
    parameter: str = "omega",
    from_: float,
    to: float,
    steps: int,
    parameter2: str = "r",
    from2: float,
    to2: float,
    steps2: int,
    transient_periods: int = 500,
    recorded_periods: int = 100,
    threads: int = 1,
    each_from: Literal["previous", "rest"] = "previous",
    chunk_values: int = 100,
    full_transient: bool = False,
    progress: Progress = False,
) -> MapResult: ...

class MapResult(dict[str, Any]):
    """parameter_map's result: its arrays, and the map as a Dataset or a table."""
    options: dict[str, Any]
    provenance: dict[str, str]
    def to_xarray(self) -> xarray.Dataset: ...
    def to_pandas(self) -> pandas.DataFrame: ...

class BasinsResult(dict[str, Any]):
    """basins' result: its arrays, and the picture as a Dataset or a table."""
    options: dict[str, Any]
    provenance: dict[str, str]
    def to_xarray(self) -> xarray.Dataset: ...
    def to_pandas(self) -> pandas.DataFrame: ...

def basins(
    system: System,
    *,
    coordinate: str = "x2",
    from_: float,
    to: float,
    steps: int,
    coordinate2: str = "v2",
    from2: float,
    to2: float,
    steps2: int,
    transient_periods: int = 500,
    recorded_periods: int = 100,
    threads: int = 1,
    orbit_tolerance: float = 1e-4,
    full_transient: bool = False,
    progress: Progress = False,
) -> BasinsResult: ...

class BasinsOptions(_OptionSet):
    def __init__(
        self,
        *,
        coordinate: str = "x2",
        from_: Optional[float] = None,
        to: Optional[float] = None,
        steps: Optional[int] = None,
        coordinate2: str = "v2",
        from2: Optional[float] = None,
        to2: Optional[float] = None,
        steps2: Optional[int] = None,
        transient_periods: int = 500,
        recorded_periods: int = 100,
        threads: int = 1,
        orbit_tolerance: float = 1e-4,
        full_transient: bool = False,
    ) -> None: ...
    coordinate: str
    from_: Optional[float]
    to: Optional[float]
    steps: Optional[int]
    coordinate2: str
    from2: Optional[float]
    to2: Optional[float]
    steps2: Optional[int]
    transient_periods: int
    recorded_periods: int
    threads: int
    orbit_tolerance: float
    full_transient: bool

class Codim2Point:
    @property
    def type(self) -> str: ...
    @property
    def user_test(self) -> str: ...
    @property
    def parameter(self) -> float: ...
    @property
    def parameter2(self) -> float: ...
    @property
    def defining_residual(self) -> float: ...
    @property
    def second_residual(self) -> float: ...
    @property
    def normal_form(self) -> Optional[dict[str, Any]]: ...
    @property
    def normal_form_note(self) -> str: ...
    def describe(self, name1: str, name2: str) -> str: ...

class Curve:
    @property
    def type(self) -> str: ...
    @property
    def parameter(self) -> str: ...
    @property
    def parameter2(self) -> str: ...
    @property
    def p(self) -> int: ...
    @property
    def q(self) -> int: ...
    @property
    def values(self) -> FloatArray: ...
    @property
    def values2(self) -> FloatArray: ...
    @property
    def orbits(self) -> list[Orbit]: ...
    @property
    def codim2_points(self) -> list[Codim2Point]: ...
    @property
    def begin(self) -> Termination: ...
    @property
    def end(self) -> Termination: ...
    @property
    def begin_message(self) -> str: ...
    @property
    def end_message(self) -> str: ...
    @property
    def seconds(self) -> float: ...
    def to_json(self) -> str: ...
    def write_csv(self, path: str | PathLike[str]) -> None: ...
    def to_pandas(self) -> pandas.DataFrame: ...
    def __len__(self) -> int: ...

class CurveOptions(_OptionSet):
    def __init__(
        self,
        *,
        parameter2: str = "r",
        from_: Optional[float] = None,
        to: Optional[float] = None,
        from2: Optional[float] = None,
        to2: Optional[float] = None,
        initial_step: float = 0.01,
        min_step: float = 1e-7,
        max_step: float = 0.02,
        max_points: int = 2000,
        locate_codim2: bool = True,
    ) -> None: ...
    parameter2: str
    from_: Optional[float]
    to: Optional[float]
    from2: Optional[float]
    to2: Optional[float]
    initial_step: float
    min_step: float
    max_step: float
    max_points: int
    locate_codim2: bool

def continue_curve(
    system: System,
    branch: Branch,
    special_point: SpecialPoint,
    *,
    parameter2: str = "r",
    from_: float,
    to: float,
    from2: float,
    to2: float,
    initial_step: float = 0.01,
    min_step: float = 1e-7,
    max_step: float = 0.02,
    max_points: int = 2000,
    locate_codim2: bool = True,
    user_tests: Optional[dict[str, Callable[[Orbit], float]]] = None,
    progress: Progress = False,
) -> Curve: ...
