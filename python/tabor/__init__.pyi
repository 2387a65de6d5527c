# Type stubs of tabor's public Python API (the implementation is tabor/__init__.py over the
# compiled tabor._tabor). Results are dicts of NumPy arrays (``Result``) or plain dicts of
# numbers, strings, lists and arrays: no JSON text.
from os import PathLike
from typing import Any, Dict, List, Literal, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

ArrayLike = npt.ArrayLike
Array = npt.NDArray[np.float64]
Backend = Literal["auto", "cpu", "gpu"]
Precision = Literal["f32", "f64"]

__version__: str
LAMBDA_MIN: float
LAMBDA_MAX: float
LAMBDA_D: float
DMT_LIMIT_MAX: float
LIMIT_LAMBDA_MIN: float
LOAD_MAX: float
APPROACH_MAX: float
RADIUS_MAX: float
LIMIT_LAMBDA_MAX: float
STATUS_NAMES: Tuple[str, ...]
__all__: List[str]

class Result(Dict[str, npt.NDArray[Any]]):
    """Arrays by name, with the run's metadata; items are also attributes."""
    metadata: Dict[str, Any]
    def __init__(self, arrays: Dict[str, npt.NDArray[Any]], metadata: Dict[str, Any]) -> None: ...
    def __getattr__(self, name: str) -> npt.NDArray[Any]: ...

def solve(
    lam: ArrayLike,
    load: Optional[ArrayLike] = None,
    approach: Optional[ArrayLike] = None,
    radius: Optional[ArrayLike] = None,
    *,
    backend: Backend = "cpu",
    precision: Precision = "f32",
    check: int = 1000,
    adapter: Optional[str] = None,
    tip: Union[None, str, Dict[str, Any]] = None,
) -> Result: ...
def pulloff(
    lam: ArrayLike,
    stress_ratio: Optional[float] = None,
    range_ratio: Optional[float] = None,
    *,
    tip: Union[None, str, Dict[str, Any]] = None,
) -> Union[Result, Dict[str, float]]: ...
def hertz(load: Optional[ArrayLike] = None, A: Optional[ArrayLike] = None) -> Array: ...
def dmt(load: Optional[ArrayLike] = None, A: Optional[ArrayLike] = None) -> Array: ...
def jkr(load: Optional[ArrayLike] = None, A: Optional[ArrayLike] = None) -> Array: ...
def bradley() -> float: ...
def curve(lam: float, a_max: float = 4.0, points: int = 200) -> Result: ...

class AdhesionMap:
    lam: Array
    load_axis: Array
    pulloff: Array
    A: Array
    load: Array
    approach: Array
    m_minus_1: Array
    region: npt.NDArray[np.uint8]
    region_names: Tuple[str, ...]
    status: npt.NDArray[np.str_]
    region_counts: Dict[str, int]
    backend: str
    def __init__(self, inner: Any) -> None: ...
    def save(
        self,
        path: Union[str, "PathLike[str]"],
        quantity: Optional[str] = None,
        width_mm: float = 85.0,
        dpi: float = 300.0,
        *,
        npy: bool = False,
    ) -> None: ...
    def save_json(self, path: Union[str, "PathLike[str]"], full: bool = False) -> None: ...

def adhesion_map(
    lambda_min: float = 1e-3,
    lambda_max: float = 1e3,
    nx: int = 1024,
    ny: int = 1024,
    load_axis: Literal["log", "linear", "above-pulloff"] = "log",
    load_min: Optional[float] = None,
    load_max: Optional[float] = None,
    tolerance: float = 0.05,
    strength_ratio: Tuple[float, float] = (0.001, 0.01),
    *,
    backend: Backend = "auto",
    precision: Precision = "f32",
    check: int = 1000,
    adapter: Optional[str] = None,
    tip: Union[None, str, Dict[str, Any]] = None,
) -> AdhesionMap: ...
def presets() -> List[str]: ...

class Scene:
    report: Dict[str, Any]
    lam: float
    recommended_model: str
    load_n: Array
    contact_radius_m: Array
    approach_m: Array
    zone_radius_m: Array
    model: npt.NDArray[np.str_]
    warnings: List[List[str]]
    def __init__(self, scene: Optional[Dict[str, Any]] = None, *, _report: Optional[Dict[str, Any]] = None) -> None: ...
    @classmethod
    def from_file(cls, path: Union[str, "PathLike[str]"]) -> "Scene": ...
    @classmethod
    def preset(cls, name: str) -> "Scene": ...

def humidity(
    scene: Optional[Dict[str, Any]] = None,
    preset: Optional[str] = None,
    rh_min: float = 0.05,
    rh_max: float = 0.95,
    points: int = 19,
    contact_angle_deg: Optional[float] = None,
) -> Dict[str, Any]: ...
def infer_pulloff(
    force_n: float,
    radius_m: float,
    e_star_pa: float,
    z0_m: float = 0.3e-9,
    relative_humidity: Optional[float] = None,
    contact_angle_deg: Optional[float] = None,
) -> Dict[str, Any]: ...
def fit_pairs(loads_n: ArrayLike, radii_m: ArrayLike, radius_m: float, z0_m: float = 0.3e-9) -> Dict[str, Any]: ...
def fit_curves(
    height_m: ArrayLike,
    force_n: ArrayLike,
    segment: ArrayLike,
    curve: Optional[ArrayLike] = None,
    *,
    radius_m: Optional[float] = None,
    spring_n_m: float,
    poisson: Optional[float] = None,
    fit_segment: Literal["retract", "approach", "both"] = "retract",
    z0_m: Optional[float] = None,
    tilt: bool = False,
    tolerance: float = 0.05,
    relative_humidity: Optional[float] = None,
    contact_angle_deg: float = 0.0,
    surface_tension_n_m: Optional[float] = None,
    molar_volume_m3_mol: Optional[float] = None,
    temperature_k: Optional[float] = None,
    tip: Union[None, str, Dict[str, Any]] = None,
) -> List[Dict[str, Any]]: ...
def fit_curve(height_m: ArrayLike, force_n: ArrayLike, segment: ArrayLike, **options: Any) -> Dict[str, Any]: ...
def fit_afmformats(
    data: Any,
    radius_m: Optional[float] = None,
    spring_n_m: Optional[float] = None,
    *,
    poisson: Optional[float] = None,
    fit_segment: Literal["retract", "approach", "both"] = "retract",
    z0_m: Optional[float] = None,
    tilt: bool = False,
    tolerance: float = 0.05,
    relative_humidity: Optional[float] = None,
    contact_angle_deg: float = 0.0,
    surface_tension_n_m: Optional[float] = None,
    molar_volume_m3_mol: Optional[float] = None,
    temperature_k: Optional[float] = None,
    tip: Union[None, str, Dict[str, Any]] = None,
) -> List[Dict[str, Any]]: ...
def fit_fleet(
    maps: Union[str, PathLike[str], Sequence[Union[str, PathLike[str], Dict[str, Any]]],
                Dict[str, Union[str, PathLike[str], Dict[str, Any]]]],
    radius_m: Optional[float],
    spring_n_m: Optional[float] = None,
    *,
    client: Any = None,
    store: Union[None, str, PathLike[str]] = None,
    **options: Any,
) -> Any: ...  # an xarray.Dataset (xarray is an optional dependency)
def cycle(
    lam: float,
    drive: Literal["grips", "dead_load", "spring"] = "grips",
    stiffness: Optional[float] = None,
    max_load: float = 2.0,
    stress_ratio: Optional[float] = None,
    range_ratio: Optional[float] = None,
    tip: Union[None, str, Dict[str, Any]] = None,
) -> Result: ...
def profile(
    lam: float,
    load: Optional[float] = None,
    approach: Optional[float] = None,
    radius: Optional[float] = None,
    points: int = 400,
    stress_ratio: Optional[float] = None,
    range_ratio: Optional[float] = None,
    tip: Union[None, str, Dict[str, Any]] = None,
) -> Dict[str, Any]: ...
def rough(
    lam: float,
    sigma: float,
    min_separation: float,
    max_separation: Optional[float] = None,
    points: int = 400,
    stress_ratio: Optional[float] = None,
    range_ratio: Optional[float] = None,
) -> Dict[str, Any]: ...
def rough_ensemble(
    lam: float,
    heights: ArrayLike,
    separations: ArrayLike,
    min_separation: Optional[float] = None,
) -> Dict[str, Any]: ...
def rough_scene(
    scene: Union[Dict[str, Any], str, PathLike[str], None] = None,
    preset: Optional[str] = None,
    points: int = 400,
) -> Dict[str, Any]: ...
def rough_asperities(
    heights_m: ArrayLike,
    radii_m: ArrayLike,
    scene: Optional[Dict[str, Any]] = None,
    preset: Optional[str] = None,
    min_separation_m: Optional[float] = None,
    points: int = 400,
    summits: str = "tables",
    backend: str = "cpu",
) -> Dict[str, Any]: ...
def rough_topography(
    heights_m: ArrayLike,
    pixel_m: float,
    scene: Optional[Dict[str, Any]] = None,
    preset: Optional[str] = None,
    min_separation_m: Optional[float] = None,
    points: int = 400,
    summits: str = "tables",
    backend: str = "cpu",
) -> Dict[str, Any]: ...
def rough_pulloff(
    lambdas: Union[Sequence[float], npt.NDArray[np.float64]] = ...,
    sigma_min: float = 0.01,
    sigma_max: float = 10.0,
    points: int = 24,
    press_sigmas: float = 3.0,
) -> List[Dict[str, Any]]: ...
def rough_map(
    lambda_min: float = 1e-2,
    lambda_max: float = 1e3,
    nx: int = 256,
    sigma_min: float = 1e-2,
    sigma_max: float = 1e2,
    ny: int = 256,
    tolerance: float = 0.05,
    press_sigmas: float = 3.0,
    check: int = 64,
) -> Dict[str, Any]: ...

class DemLaw:
    """The force-overlap law of :func:`dem_law` (the compiled ``tabor._tabor.DemLaw``)."""
    @property
    def info(self) -> Dict[str, Any]: ...
    def eval(
        self, overlap: npt.NDArray[np.float64], history: npt.NDArray[np.uint8]
    ) -> Tuple[Array, Array]: ...
    def branches(self, history: npt.NDArray[np.uint8]) -> npt.NDArray[np.uint8]: ...
    def drive(
        self, overlap_min: float, overlap_max: float, points: int
    ) -> Dict[str, Dict[str, Array]]: ...
    def loop_energy(self, overlap_max: float) -> Optional[float]: ...

def dem_law(
    lam: Optional[float] = None,
    scene: Union[Dict[str, Any], str, PathLike[str], None] = None,
    overlap_max: Optional[float] = None,
    stress_ratio: Optional[float] = None,
    range_ratio: Optional[float] = None,
) -> DemLaw: ...
