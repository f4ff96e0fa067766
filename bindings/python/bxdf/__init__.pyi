# Type stubs for the bxdf package (the compiled bxdf._bxdf plus bxdf/__init__.py).
import os
from typing import Any, Callable, Literal, Mapping, Sequence, SupportsFloat, TypedDict, Union, overload

import numpy as np
import numpy.typing as npt

__version__: str

ArrayLike = npt.ArrayLike
F32 = npt.NDArray[np.float32]
I32 = npt.NDArray[np.int32]
RGBLike = Union[SupportsFloat, Sequence[SupportsFloat], npt.NDArray[Any]]
ParamValue = Union[float, int, bool, str, RGBLike, Sequence[dict[str, Any]]]

class _When(TypedDict):
    param: str
    values: list[str]

class ParamSpecDict(TypedDict, total=False):
    name: str
    kind: Literal["float", "rgb", "enum", "bool", "string", "list"]
    default: Any
    min: float | None
    max: float | None
    min_exclusive: bool
    max_exclusive: bool
    unit: str
    doc: str
    choices: list[str]  # enum only
    fields: list[ParamSpecDict]  # list only
    when: _When  # conditional parameters only

def models() -> dict[str, list[ParamSpecDict]]: ...
def model_doc(name: str) -> str: ...
def make(name: str, **params: ParamValue) -> Model: ...

class PresetDict(TypedDict):
    model: str
    doc: str
    params: dict[str, Any]

def presets() -> dict[str, PresetDict]: ...
def make_preset(name: str) -> Model: ...
def save_material(model: Model, path: str | os.PathLike[str], name: str = "") -> None: ...
def load_material(path: str | os.PathLike[str]) -> Model: ...
def load_measured(path: str | os.PathLike[str], **params: ParamValue) -> Model: ...

class FitReport(TypedDict):
    model: str
    error: float
    baseline_error: float
    sum_squares: float
    samples: int
    iterations: int
    total_iterations: int
    starts: int
    start_errors: list[float]
    seconds: float

# Present when the build found Ceres (core/fit).
def fit(
    measured: Model | str | os.PathLike[str],
    model: str = "lafortune",
    lobes: int = 2,
    *,
    max_iterations: int = 200,
    max_starts: int = 0,
    merl_stride: int = 4,
) -> tuple[Model, FitReport]: ...
def fit_models() -> list[str]: ...
def fit_error(measured: Model | str | os.PathLike[str], model: Model, merl_stride: int = 4) -> float: ...

class Model:
    @property
    def name(self) -> str: ...
    @property
    def params(self) -> dict[str, Any]: ...
    @property
    def flags(self) -> set[str]: ...
    @property
    def doc(self) -> str: ...
    def f(self, wo: ArrayLike, wi: ArrayLike) -> F32: ...
    def pdf(self, wo: ArrayLike, wi: ArrayLike) -> F32: ...
    @property
    def sample_f_is_exact(self) -> bool: ...
    def sample_f(self, wo: ArrayLike, u: ArrayLike, exact: bool = False) -> tuple[F32, F32, F32]: ...
    def rho(self, wo: ArrayLike, n_samples: int, seed: int = 0) -> F32: ...
    def rho_hh(self, n_samples: int, seed: int = 0) -> F32: ...
    def __eq__(self, other: object) -> bool: ...
    def __hash__(self) -> int: ...
    def __getstate__(self) -> tuple[str, dict[str, Any]]: ...
    def __setstate__(self, state: tuple[str, dict[str, Any]]) -> None: ...

def fresnel_dielectric(cos_i: ArrayLike, eta_i: float, eta_t: float) -> F32 | float: ...
def fresnel_conductor(cos_i: ArrayLike, eta: RGBLike, k: RGBLike) -> F32: ...
def eta_from_f0(f0: ArrayLike) -> F32 | float: ...
def k_from_f0(f0: ArrayLike) -> F32 | float: ...

def bake_lobe_polar(
    model: Model,
    wo: ArrayLike | None = None,
    resolution: int = 256,
    parameterization: Literal["equal_area", "lat_long"] = "equal_area",
    *,
    theta_o: float | None = None,
    phi_o: float = 0.0,
    hemisphere: Literal["upper", "lower"] = "upper",
) -> F32: ...
def bake_slice_half_diff(
    model: Model, phi_d: float = 90.0, resolution: int = 256, *, phi_h: float = 0.0
) -> F32: ...
def bake_albedo_curve(
    model: Model, n_theta: int = 90, n_samples: int = 4096, *, phi_o: float = 0.0, seed: int = 0
) -> tuple[F32, F32]: ...
def lobe_mesh(
    model: Model,
    wo: ArrayLike | None = None,
    resolution: int = 32,
    *,
    theta_o: float | None = None,
    phi_o: float = 0.0,
    hemisphere: Literal["upper", "lower"] = "upper",
) -> tuple[F32, I32]: ...

class RenderStats(TypedDict, total=False):
    seconds: float
    samples_per_pixel: int
    camera_samples: int
    rays: int
    shadow_rays: int
    rejected_samples: int
    cancelled: bool
    warnings: list[str]
    convert_seconds: float  # render() only
    bvh_seconds: float  # render() only
    bvh_build: str  # "quick" or "medium"

class RenderSettingsDict(TypedDict, total=False):
    samples: int
    max_bounces: int
    pixel_filter: Literal["box", "gaussian", "pixel_center", "BOX", "GAUSSIAN", "PIXEL_CENTER"]
    filter_width: float
    threads: int
    seed: int
    tile_size: int
    samples_per_pass: int
    russian_roulette_depth: int
    transparent_background: bool
    region: tuple[int, int, int, int] | None  # x_min, y_min (rows from the top), x_max, y_max

# on_progress(done_tiles, total_tiles, partial_image_or_None) -> False to cancel
ProgressCallback = Callable[[int, int, F32 | None], bool | None]

@overload
def render(
    scene: Mapping[str, Any],
    settings: RenderSettingsDict | None = None,
    on_progress: ProgressCallback | None = None,
    *,
    bottom_up: bool = False,
    return_stats: Literal[False] = False,
) -> F32: ...
@overload
def render(
    scene: Mapping[str, Any],
    settings: RenderSettingsDict | None = None,
    on_progress: ProgressCallback | None = None,
    *,
    bottom_up: bool = False,
    return_stats: Literal[True],
) -> tuple[F32, RenderStats]: ...
@overload
def render_scene_file(
    path: str | os.PathLike[str],
    settings: RenderSettingsDict | None = None,
    on_progress: ProgressCallback | None = None,
    *,
    bottom_up: bool = False,
    return_stats: Literal[False] = False,
) -> F32: ...
@overload
def render_scene_file(
    path: str | os.PathLike[str],
    settings: RenderSettingsDict | None = None,
    on_progress: ProgressCallback | None = None,
    *,
    bottom_up: bool = False,
    return_stats: Literal[True],
) -> tuple[F32, RenderStats]: ...
