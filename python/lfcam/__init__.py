"""lfcam: light-field photography with a hand-held plenoptic camera (Ng et al. 2005).

The same C++ library as the `lfcam` command, with its names and defaults:

    import lfcam
    lf = lfcam.read("../shared/data/hci-antinous")        # a LightField
    photo = lfcam.refocus(lf, 0.5, aperture=2)            # an Image
    pixels = photo.array                                  # numpy, (channels, height, width), no copy

A focused plenoptic (Raytrix) capture: lfcam.read_focused, then focused_depth, focused_photo and
focused_total_focus (`lfcam depth`, `refocus` and `edof` of it).

lfcam.simulate writes a simulated capture as `lfcam simulate` does; lfcam.batch.run applies steps to
many captures, on this machine or on a Dask cluster (`lfcam batch`, docs/batch.md).

Errors raise lfcam.UsageError (a wrong argument) or lfcam.Error (a file or input that fails),
with the command line's one-line messages.
"""
from ._lfcam import (AllInFocus, DepthMap, Error, FocusedCapture, FocusedDepth, Image, LensletGrid, LightField, UsageError,
                     calibrate, choose_white, decode, denoise, depth, edof, focused_depth, focused_distance, focused_photo,
                     focused_total_focus, observer, photo_fields, read, read_focused, read_image, refocus, score, simulate,
                     stack, volume, write, write_image)


def __getattr__(name):
    # lfcam.batch on first use, not at import: `python3 -m lfcam.batch` then runs it once, as __main__.
    if name == "batch":
        import importlib
        return importlib.import_module(".batch", __name__)
    raise AttributeError(f"module 'lfcam' has no attribute '{name}'")


__all__ = ["AllInFocus", "DepthMap", "Error", "FocusedCapture", "FocusedDepth", "Image", "LensletGrid", "LightField",
           "UsageError", "batch", "calibrate", "choose_white", "decode", "denoise", "depth", "edof", "focused_depth",
           "focused_distance", "focused_photo", "focused_total_focus", "observer", "photo_fields", "read", "read_focused",
           "read_image", "refocus", "score", "simulate", "stack", "volume", "write", "write_image"]
