# Type stub of the batchccd module (python/src/module.cpp), for editors and
# type checkers. The options every call takes are the keywords of Options.
from enum import IntEnum
from typing import Literal, Mapping, Sequence, TypedDict, Union

import numpy as np
import numpy.typing as npt
from typing_extensions import Unpack

from . import ipc as ipc

__version__: str

class Status(IntEnum):
    OK = 0
    INVALID_INPUT = 1

STATUS_OK: Status  # Status.OK
STATUS_INVALID_INPUT: Status  # Status.INVALID_INPUT

Kind = Literal["vf", "ee", "ve", "vv", "vertex_face", "edge_edge", "vertex_edge", "vertex_vertex"]
Point = Union[npt.ArrayLike, Sequence[float]]

class Options(TypedDict, total=False):
    mode: str  # "conservative" (default) or "exact"; modes() lists them
    min_distance: float
    tmax: float
    need_toi: bool
    evaluate_vertex_face: bool  # Options::vertex_face (the name is mesh_ccd's list)
    evaluate_edge_edge: bool
    evaluate_vertex_edge: bool
    evaluate_vertex_vertex: bool
    per_candidate_results: bool
    hit_list: bool
    isa: str  # "auto", "scalar", "sse4", "avx2", "avx512", "neon"
    threads: int
    tolerance: float
    toi_tolerance: float
    max_iterations: int
    exact_stage_iterations: int

class InputError(ValueError): ...

class QueryResult:
    @property
    def hit(self) -> bool: ...
    @property
    def toi(self) -> float: ...
    @property
    def status(self) -> Status: ...

class BatchResult:
    @property
    def earliest_toi(self) -> float: ...
    @property
    def counters(self) -> dict[str, int]: ...
    @property
    def hit(self) -> npt.NDArray[np.bool_] | None: ...
    @property
    def toi(self) -> npt.NDArray[np.float64] | None: ...
    @property
    def status(self) -> npt.NDArray[np.int32] | None: ...
    @property
    def hit_candidates(self) -> npt.NDArray[np.int64] | None: ...
    @property
    def hit_tois(self) -> npt.NDArray[np.float64] | None: ...
    @property
    def hit_statuses(self) -> npt.NDArray[np.int32] | None: ...

def mesh_ccd(
    x0: npt.ArrayLike,
    x1: npt.ArrayLike,
    faces: npt.ArrayLike | None = None,
    edges: npt.ArrayLike | None = None,
    vertex_face: npt.ArrayLike | None = None,
    edge_edge: npt.ArrayLike | None = None,
    vertex_edge: npt.ArrayLike | None = None,
    vertex_vertex: npt.ArrayLike | None = None,
    *,
    min_distances: npt.ArrayLike | Mapping[str, npt.ArrayLike] | None = None,
    out: BatchResult | None = None,
    **options: Unpack[Options],
) -> BatchResult: ...
def batch_ccd(
    kind: Kind,
    queries: npt.ArrayLike,
    min_distances: npt.ArrayLike | None = None,
    *,
    out: BatchResult | None = None,
    **options: Unpack[Options],
) -> BatchResult: ...
def vertex_face_ccd(
    p_t0: Point, a_t0: Point, b_t0: Point, c_t0: Point,
    p_t1: Point, a_t1: Point, b_t1: Point, c_t1: Point,
    **options: Unpack[Options],
) -> QueryResult: ...
def edge_edge_ccd(
    ea0_t0: Point, ea1_t0: Point, eb0_t0: Point, eb1_t0: Point,
    ea0_t1: Point, ea1_t1: Point, eb0_t1: Point, eb1_t1: Point,
    **options: Unpack[Options],
) -> QueryResult: ...
def vertex_edge_ccd(
    p_t0: Point, e0_t0: Point, e1_t0: Point, p_t1: Point, e0_t1: Point, e1_t1: Point,
    **options: Unpack[Options],
) -> QueryResult: ...
def vertex_vertex_ccd(p_t0: Point, q_t0: Point, p_t1: Point, q_t1: Point, **options: Unpack[Options]) -> QueryResult: ...
def query_ccd(kind: Kind, query: npt.ArrayLike, **options: Unpack[Options]) -> QueryResult: ...
def squared_distance(kind: Kind, query: npt.ArrayLike, t: float = 0.0) -> float: ...
def make_query(kind: Kind, points_t0: npt.ArrayLike, points_t1: npt.ArrayLike) -> npt.NDArray[np.float64]: ...
def unique_edges(faces: npt.ArrayLike) -> npt.NDArray[np.int32]: ...
def read_scene(path: str) -> dict[str, npt.NDArray | None]: ...
def default_options() -> dict[str, Union[str, float, int, bool]]: ...
def modes() -> list[str]: ...
def kinds() -> list[str]: ...
def available_isas() -> list[str]: ...
def resolve_isa(isa: str = "auto") -> str: ...
