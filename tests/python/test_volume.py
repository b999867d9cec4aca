"""lfcam.volume: a light-field microscope frame (a light field of N x N views) -> a float32 (z, y, x)
volume, with `lfcam volume`'s settings and its one-line messages for wrong ones."""
import os
import subprocess

import numpy as np
import pytest

import lfcam

LFCAM = os.environ.get("LFCAM_EXECUTABLE", "")

# A small microscope: 40 um lenslets over 40/7 um pixels, 7 x 7 views; 3 slices 3 um apart.
SMALL = dict(objective="20x/0.5/water", wavelength=500, pitch=40, microlens_focal_length=800, pixel_size=40 / 7,
             slices=3, um_per_slice=3, supersample=1, iterations=2)


def frame(nt=6, ns=5):
    """A frame of nt x ns lenslets of 7 x 7 pixels, as a light field of 7 x 7 views."""
    samples = np.zeros((7, 7, 1, nt, ns), np.float32)
    samples[:, :, :, nt // 2, ns // 2] = 1  # one lit lenslet
    return lfcam.LightField(samples)


def test_volume_is_float32_slices_of_the_lenslet_grid():
    lf = frame()
    fractions = []
    volume = lfcam.volume(lf, **SMALL, progress=fractions.append)
    assert volume.shape == (3, lf.nt * 1, lf.ns * 1)
    assert volume.dtype == np.float32
    assert np.isfinite(volume).all() and volume.max() > 0
    assert fractions and fractions[-1] == 1
    dark = lfcam.volume(lfcam.LightField(np.zeros((7, 7, 1, 6, 5), np.float32)), **SMALL)
    assert dark.shape == (3, 6, 5) and np.isfinite(dark).all()


def test_a_hexagonal_frame_uses_its_rows_in_pairs():
    # 5 rows of lenslets: the hexagonal array's period is two rows, the last one is left out.
    volume = lfcam.volume(frame(nt=5, ns=6), **SMALL, microlens_array="hexagonal")
    assert volume.shape == (3, 4, 6)
    assert np.isfinite(volume).all() and volume.max() > 0


def test_the_psf_cache_is_written_and_read_back(tmp_path):
    lf = frame()
    cache = tmp_path / "psf.h5"
    first = lfcam.volume(lf, **SMALL, psf=cache)
    assert cache.is_file()
    np.testing.assert_array_equal(lfcam.volume(lf, **SMALL, psf=str(cache)), first)


MESSAGES = [
    (dict(slices=None), "--slices: how many z-slices (or num_slices in --optics)"),
    (dict(slices=0), "slices 0 outside [1, 1000]"),
    (dict(objective="60/1.2/water"), "--objective: expected MAGx/NA/MEDIUM as 60x/1.2/water, got '60/1.2/water'"),
    (dict(microlens_array="round"), "--microlens-array: expected square or hexagonal, got 'round'"),
]


@pytest.mark.parametrize("change,message", MESSAGES)
def test_wrong_settings_raise_the_commands_message(change, message):
    with pytest.raises(lfcam.UsageError) as raised:
        lfcam.volume(frame(), **{**SMALL, **change})
    assert str(raised.value) == message


@pytest.mark.parametrize("change,message", MESSAGES)
def test_the_command_line_gives_the_same_message(tmp_path, change, message):
    if not LFCAM:
        pytest.skip("LFCAM_EXECUTABLE is not set (ctest sets it)")
    settings = {**SMALL, **change}
    flags = []
    for name, value in settings.items():
        if value is not None:
            flags += ["--" + name.replace("_", "-"), str(value)]
    run = subprocess.run([LFCAM, "volume", str(tmp_path / "frame.lf.h5"), *flags, "-o", str(tmp_path / "v.tif")],
                         capture_output=True, text=True)
    assert run.returncode != 0
    assert run.stderr.strip() == "lfcam: " + message


def test_the_microscope_is_needed_and_the_solver_named():
    with pytest.raises(lfcam.UsageError, match="--optics or --objective: the microscope is needed"):
        lfcam.volume(frame(), slices=3)
    with pytest.raises(lfcam.UsageError, match="--solver: expected rl or backprojection, got 'cg'"):
        lfcam.volume(frame(), **SMALL, solver="cg")
