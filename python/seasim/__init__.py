"""seasim: physically based light in water and air, from Python.

The same C++ core as the ``seasim`` command line (a thin nanobind binding, never a second
implementation)::

    import seasim
    scene = seasim.Scene.load("scenes/flat_sea.toml", overrides={"camera.width": 64, "camera.height": 36})
    renderer = seasim.Renderer(scene)          # device="" picks as --device does
    frame = renderer.render()                  # frame.rgb: float32 (H, W, 3), linear sensor RGB
    renderer.update({"sun.zenith_deg": 60})    # the next render reruns only the passes that read the sun
    seasim.compare(frame, renderer.render())   # the CLI's metrics

docs/python/README.md has the examples.
"""

from __future__ import annotations

import os
import sys
from dataclasses import dataclass
from typing import Callable, Optional, Tuple, Union

import numpy as np

from . import _cpu_runtime, _paths

_paths.point_core_at_package()  # before the core first reads its data or loads a module
_cpu_runtime.register()  # before the core loads oneTBB and the OpenCL loader first looks for platforms

from ._seasim import DeviceInfo, Frame, Renderer, Scene, data_dir, device, devices, version  # noqa: E402
from . import _seasim  # noqa: E402
from .errors import DeviceError, RenderError, SceneError  # noqa: E402

__all__ = [
    "DeviceInfo", "Frame", "Renderer", "Scene", "ReferenceResult", "DeviceError", "RenderError", "SceneError",
    "compare", "data_dir", "device", "devices", "display", "read_image", "reference", "run_job", "scenes_dir", "version",
]

PathLike = Union[str, "os.PathLike[str]"]
ImageLike = Union[np.ndarray, Frame, "ReferenceResult", PathLike]


def scenes_dir() -> Optional[str]:
    """The example scenes a wheel carries (``scenes_dir() + '/flat_sea.toml'``); None in a build tree."""
    d = _paths.scenes_dir()
    return None if d is None else str(d)


def read_image(path: PathLike) -> np.ndarray:
    """An image file (EXR, PNG, ... or .npy) as float32 (H, W, C), read as ``seasim compare`` reads it."""
    return _seasim._read_image(path)


def _as_image(image: ImageLike) -> np.ndarray:
    if isinstance(image, (Frame, ReferenceResult)):
        return image.rgb
    if isinstance(image, (str, os.PathLike)):
        return read_image(image)
    array = np.ascontiguousarray(image, dtype=np.float32)
    if array.ndim == 2:
        array = array[:, :, None]
    if array.ndim != 3:
        raise ValueError(f"an image is (height, width) or (height, width, channels), not shape {array.shape}")
    return array


def compare(test: ImageLike, reference: ImageLike, exposure_ev: float = 0.0) -> dict:
    """The error of ``test`` against ``reference``, with the metrics of ``seasim compare``.

    Either may be an array (H, W, C), a Frame, a ReferenceResult or an image path. Returns rmse_8bit and max_abs_8bit
    (8-bit display levels after the PNG's tone map at ``exposure_ev``), rel_l2 (linear) and
    hue_sat_distance, and nonfinite (NaN/Inf met). Raises seasim.RenderError for different sizes.
    """
    return _seasim._compare(_as_image(test), _as_image(reference), exposure_ev)


def display(image: ImageLike, exposure_ev: Optional[float] = None) -> np.ndarray:
    """Display sRGB in [0, 1], float32 (H, W, C): the tone map of the PNGs and of compare's 8-bit metrics.

    ``exposure_ev`` defaults to the frame's scene setting (camera.exposure_ev) for a Frame, else 0.
    """
    if exposure_ev is None:
        exposure_ev = image.report["settings"]["exposure_ev"] if isinstance(image, Frame) else 0.0
    return _seasim._display(_as_image(image), exposure_ev)


@dataclass
class ReferenceResult:
    """A brute-force reference image (seasim.reference)."""

    rgb: np.ndarray  #: linear sensor RGB, float32 (H, W, 3)
    method: str  #: "path tracer", "ray-march" or "quadrature"
    steps: int  #: paths per pixel, or ray-march / quadrature steps
    ms: float  #: time taken
    std_error: Optional[np.ndarray] = None  #: path tracer: per-pixel standard error
    #: path tracer under water: the part of rgb from paths whose camera ray reached a surface unscattered
    #: (the fast model's ``frame.layers["direct"]``; rgb - direct is backscatter + forward + lamps)
    direct: Optional[np.ndarray] = None
    direct_std_error: Optional[np.ndarray] = None  #: its per-pixel standard error
    info: Optional[dict] = None  #: path tracer: seed, max_bounces, mean_std_error, image_mean_std_error, effective_samples, blocks, device


def reference(scene: Scene, steps: int = 0, seed: Optional[int] = None, all_orders: bool = False,
              max_bounces: int = 0, device: str = "", sun_single_quadrature: bool = False, subpixels: int = 4,
              progress: Optional[Callable[[int, int], None]] = None) -> ReferenceResult:
    """The scene's brute-force reference, as ``seasim reference`` computes it.

    Under water (and with ``all_orders`` the sea seen from above) the spectral path tracer on the
    device, ``steps`` paths per pixel (0: quality.reference_spp), ``seed`` (default 1); spotlights
    in air the shafts ray marcher; else the sea's quadrature (``steps`` 0: quality.reference_steps).
    ``sun_single_quadrature`` (under water with underwater.multiple_scattering = false): the sun beam's
    single scattering, the froxel pass's term, by deterministic quadrature over each pixel's area,
    ``subpixels``² rays per pixel and ``steps`` points per ray (``--sun-single-quadrature``).
    ``progress(done, total)`` is called as the path tracer's samples finish.
    """
    r = _seasim._reference(scene, steps, -1 if seed is None else seed, all_orders, max_bounces, device,
                           subpixels if sun_single_quadrature else 0, progress)
    info = {k: r[k] for k in ("seed", "max_bounces", "mean_std_error", "image_mean_std_error", "effective_samples", "blocks", "device") if k in r} or None
    return ReferenceResult(rgb=r["rgb"], method=r["method"], steps=r["steps"], ms=r["ms"],
                           std_error=r.get("std_error"), direct=r.get("direct"),
                           direct_std_error=r.get("direct_std_error"), info=info)


def _progress_bar() -> Callable[[int, int, str, str], None]:
    """tqdm when it is installed, else one line per item on stderr."""
    try:
        from tqdm.auto import tqdm
    except ImportError:
        def line(handled: int, total: int, item: str, outcome: str) -> None:
            print(f"[{handled}/{total}] {item}: {outcome}", file=sys.stderr, flush=True)
        return line
    bar = None

    def update(handled: int, total: int, item: str, outcome: str) -> None:
        nonlocal bar
        if bar is None:
            bar = tqdm(total=total, unit="render")
        bar.set_postfix_str(f"{item}: {outcome}", refresh=False)
        bar.update(1)
        if handled == total:
            bar.close()
    return update


def run_job(path: PathLike, shard: Union[None, str, Tuple[int, int]] = None, resume: bool = False,
            device: str = "", output_dir: Optional[PathLike] = None,
            progress: Union[bool, Callable[[int, int, str, str], None]] = True) -> dict:
    """Runs a job file as ``seasim run`` does: shards, resume, atomic outputs, a manifest.

    ``shard`` is "i/N" or (i, N). ``progress``: True draws a tqdm bar when tqdm is installed (else a
    line per item on stderr), False is silent, or a callable(handled, total, item, outcome).
    Returns rendered, skipped, other_shards, failed ([{name, error}]), output_dir and manifest.
    A failed item does not stop the job; it is listed in ``failed``.
    """
    index, count = 0, 1
    if shard is not None:
        try:
            index, count = (int(p) for p in shard.split("/")) if isinstance(shard, str) else shard
        except (TypeError, ValueError):
            raise ValueError(f"shard is 'i/N' or (i, N), e.g. '0/4'; got {shard!r}") from None
    if progress is True:
        on_item = _progress_bar()
    elif progress is False:
        on_item = lambda *args: None  # noqa: E731
    else:
        on_item = progress
    out = "" if output_dir is None else os.fspath(output_dir)
    return _seasim._run_job(path, index, count, resume, device, out, on_item)
