# Type stub of the package lfcam (python/), so that editors complete and check its calls.
from os import PathLike
from typing import Callable, Dict, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

from . import batch as batch

_Path = Union[str, PathLike[str]]
_Array = npt.ArrayLike
_Progress = Union[bool, Callable[[float], object], None]  # a callable of the fraction done (0..1), or True: a tqdm bar

class Error(RuntimeError): ...
class UsageError(Error): ...

class Image:
    def __init__(self, array: _Array) -> None: ...
    @property
    def width(self) -> int: ...
    @property
    def height(self) -> int: ...
    @property
    def channels(self) -> int: ...
    @property
    def array(self) -> npt.NDArray[np.float32]: ...  # (channels, height, width), no copy
    def _repr_png_(self) -> bytes: ...  # 8-bit sRGB, for Jupyter

class LightField:
    def __init__(self, samples: _Array, weights: Optional[_Array] = None) -> None: ...
    @staticmethod
    def zeros(nu: int, nv: int, ns: int, nt: int, channels: int = 3) -> LightField: ...
    @property
    def nu(self) -> int: ...
    @property
    def nv(self) -> int: ...
    @property
    def ns(self) -> int: ...
    @property
    def nt(self) -> int: ...
    @property
    def channels(self) -> int: ...
    @property
    def samples(self) -> npt.NDArray[np.float32]: ...  # (nv, nu, channels, nt, ns), no copy
    @property
    def weights(self) -> Optional[npt.NDArray[np.float32]]: ...  # (nv, nu, nt, ns)
    def view(self, u: int, v: int) -> Image: ...
    @property
    def source(self) -> str: ...
    @property
    def optics(self) -> Optional[dict[str, Optional[float]]]: ...
    @property
    def disparity_range(self) -> Optional[tuple[float, float]]: ...
    def _repr_png_(self) -> bytes: ...  # the centre view, 8-bit sRGB, for Jupyter

class LensletGrid:
    pitch_x: float
    pitch_y: float
    rotation_rad: float
    origin: tuple[float, float]
    columns: int
    rows: int
    hexagonal: bool
    def write(self, path: _Path) -> None: ...

class DepthMap:
    disparity: Image
    confidence: Image
    disparity_min: float
    disparity_max: float
    labels: int

class AllInFocus:
    photo: Image
    slope: Image
    slopes: list[float]

class FocusedCapture:
    image: Image
    packing: str
    micro_image_diameter: float
    micro_images: tuple[int, int]
    micro_image_orientation: str
    lens_types: list[dict[str, tuple[float, float]]]
    calibration_path: Optional[str]
    def write_calibration(self, path: _Path) -> None: ...

class FocusedDepth:
    virtual_depth: Image
    confidence: Image

def read_focused(path: _Path, *, calibration: _Path = "", white: _Path = "", self_calibrate: bool = False) -> FocusedCapture: ...
def focused_depth(capture: FocusedCapture, *, pixels_per_lens: Optional[float] = None) -> FocusedDepth: ...
def focused_distance(capture: FocusedCapture, virtual_depth: _Array) -> Image: ...
def focused_photo(capture: FocusedCapture, *, pixels_per_lens: Optional[float] = None, virtual_depth: float,
                  aperture: float = 1.0, viewpoint: tuple[float, float] = (0.0, 0.0), patches: bool = False) -> Image: ...
def focused_total_focus(capture: FocusedCapture, *, pixels_per_lens: Optional[float] = None,
                        depth: Optional[_Array] = None) -> Image: ...
def read(path: _Path, *, lenslet_views: Optional[int] = None, progress: _Progress = None) -> LightField: ...
def write(path: _Path, light_field: LightField, *, progress: _Progress = None) -> None: ...
def read_image(path: _Path) -> Image: ...
def write_image(path: _Path, image: Image, *, bit_depth: Optional[str] = None) -> None: ...
def calibrate(white: _Path, *, metadata: Optional[_Path] = None, pinhole: bool = False, scene: bool = False,
              bayer: Optional[str] = None, black_level: Optional[float] = None) -> LensletGrid: ...
def decode(raw: str, *, white: str = "", dark: str = "", grid: str = "", bayer: Optional[str] = None,
           black_level: Optional[float] = None, views: int = 0, demosaic: str = "mhc",
           sampling: str = "subpixel", progress: _Progress = None, whites: str = "",
           any_camera: bool = False) -> LightField: ...
def choose_white(raw: _Path, whites: _Path, *, any_camera: bool = False) -> Dict[str, str]: ...
# The keywords of refocus and stack are the photograph request's fields (photo_fields(), the
# command line's flags): tests/python checks this list against that table.
def refocus(light_field: LightField, slope: Optional[float] = None, *, alpha: Optional[float] = None,
            focus_at: Optional[tuple[float, float]] = None,
            focus_plane: Optional[tuple[tuple[float, float], tuple[float, float], tuple[float, float]]] = None,
            tilt: Optional[float] = None, tilt_direction: Optional[float] = None,
            focus_range: Optional[tuple[float, float] | str] = None, depth: Optional[_Array | str] = None,
            aperture: Optional[float] = None, f_number: Optional[float] = None, aperture_shape: Optional[str] = None,
            aperture_centre: Optional[tuple[float, float]] = None, aperture_mask: Optional[_Array | str] = None,
            clamp: bool = False, beta: Optional[float] = None, method: str = "fast", supersampling: int = 0,
            upsample: int = 1) -> Image: ...
def stack(light_field: LightField, slopes: Optional[Sequence[float]] = None, *,
          alphas: Optional[Sequence[float]] = None, aperture: Optional[float] = None, f_number: Optional[float] = None,
          aperture_shape: Optional[str] = None, aperture_centre: Optional[tuple[float, float]] = None,
          aperture_mask: Optional[_Array | str] = None, clamp: bool = False, beta: Optional[float] = None,
          method: str = "fast", supersampling: int = 0) -> list[Image]: ...
def photo_fields() -> list[dict[str, str]]: ...
def observer(light_field: LightField, u: float, v: float, *, beta: float = 1.0, clamp: bool = False) -> Image: ...
def depth(light_field: LightField, *, options: Optional[_Path] = None, **knobs: float) -> DepthMap: ...
def edof(light_field: LightField, *, depth: Optional[_Array] = None, min: Optional[float] = None,
         max: Optional[float] = None, step: float = 0.0) -> AllInFocus: ...
def denoise(light_field: LightField, *, depth_range: Optional[tuple[float, float]] = None,
            bandwidth: Optional[float] = None) -> LightField: ...
def score(estimate: _Array, truth: _Array, *, mask: Optional[_Array] = None, border: int = 15) -> dict[str, float]: ...
# A light-field microscope volume (lfcam volume): float32 (z, y, x), voxels pitch / (M * supersample) um
# across, slice i at depth z_center + (i - (slices - 1) / 2) * um_per_slice um.
def volume(light_field: LightField, *, optics: Optional[_Path] = None, objective: Optional[str] = None,
           wavelength: Optional[float] = None, pixel_size: Optional[float] = None, pitch: Optional[float] = None,
           microlens_focal_length: Optional[float] = None, tube_lens: Optional[float] = None,
           slices: Optional[int] = None, um_per_slice: Optional[float] = None, z_center: Optional[float] = None,
           supersample: Optional[int] = None, iterations: Optional[int] = None, solver: str = "rl",
           background: Optional[float] = None, tolerance: Optional[float] = None, tv: Optional[float] = None,
           psf: Optional[_Path] = None, psf_energy: Optional[float] = None,
           progress: _Progress = None) -> npt.NDArray[np.float32]: ...
def simulate(scene: str, output: _Path, *, f_number: Optional[float] = None, image_f_number: Optional[float] = None,
             focus_mm: Optional[float] = None, size: Optional[int] = None, pixels_per_lens: Optional[float] = None,
             hexagonal: bool = False, samples: int = 16, seed: Optional[int] = None, exposure: Optional[float] = None,
             conventional: bool = False, noise: Optional[bool] = None, raw_format: str = "png",
             container: Optional[str] = None, white: bool = True, ground_truth: bool = True,
             progress: _Progress = None) -> None: ...
