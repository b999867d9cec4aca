"""progress= of the long calls: a callable gets the fraction done, rising to 1; True draws a tqdm bar;
a callback's error is reported without stopping the call; Ctrl-C still stops a call that reports."""
import os
import signal
import sys
import threading
import time

import numpy as np
import pytest

import lfcam


def reported(call, *args, **kwargs):
    """call(*args, **kwargs, progress=...), checking the fractions it reported."""
    fractions = []
    result = call(*args, **kwargs, progress=fractions.append)
    assert len(set(fractions)) > 2 and fractions == sorted(fractions), fractions
    assert fractions[0] >= 0 and fractions[-1] == 1, fractions
    return result


def test_long_calls_report_rising_fractions_that_end_at_one(tmp_path):
    capture = tmp_path / "capture"
    reported(lfcam.simulate, "people", capture, size=128, samples=1, seed=7)
    lf = reported(lfcam.decode, str(capture / "raw.png"), white=str(capture / "white.png"))
    reported(lfcam.write, tmp_path / "a.lf.h5", lf)
    back = reported(lfcam.read, tmp_path / "a.lf.h5")
    np.testing.assert_array_equal(back.samples, lf.samples)


def test_progress_true_draws_a_tqdm_bar_and_anything_else_raises(tmp_path, capsys):
    pytest.importorskip("tqdm", reason="Debian's python3-tqdm draws the bar of progress=True")
    lf = lfcam.LightField(np.ones((3, 3, 1, 8, 8), np.float32))
    lfcam.write(tmp_path / "a.lf.h5", lf, progress=True)
    assert "write: 100%" in capsys.readouterr().err
    with pytest.raises(lfcam.UsageError, match="read: progress must be a callable of the fraction done, True or None"):
        lfcam.read(tmp_path / "a.lf.h5", progress="yes")


def test_a_callbacks_error_is_reported_and_the_call_goes_on(tmp_path, monkeypatch):
    unraisable = []
    monkeypatch.setattr(sys, "unraisablehook", unraisable.append)
    lf = lfcam.LightField(np.ones((3, 3, 1, 8, 8), np.float32))
    lfcam.write(tmp_path / "a.lf.h5", lf, progress=lambda fraction: 1 / 0)
    np.testing.assert_array_equal(lfcam.read(tmp_path / "a.lf.h5").samples, lf.samples)
    assert unraisable and all(isinstance(u.exc_value, ZeroDivisionError) for u in unraisable)
    assert unraisable[0].object == "write(progress=...)"


def test_ctrl_c_stops_a_call_that_reports_progress(tmp_path):
    settings = dict(size=1024, samples=8, seed=7, white=False, ground_truth=False)
    start = time.perf_counter()
    lfcam.simulate("people", tmp_path / "timed", **settings)
    whole = time.perf_counter() - start
    fractions = []
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    timer = threading.Timer(0.2 * whole, os.kill, (os.getpid(), signal.SIGINT))
    try:
        timer.start()
        start = time.perf_counter()
        with pytest.raises(KeyboardInterrupt):
            lfcam.simulate("people", tmp_path / "stopped", **settings, progress=fractions.append)
        stopped_after = time.perf_counter() - start
    finally:
        timer.cancel()
        signal.signal(signal.SIGINT, previous)
    assert stopped_after < 0.75 * whole and fractions  # it did not run to the end, and it reported on the way
