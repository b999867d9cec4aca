"""lfcam.batch on one machine against `lfcam batch`, the batch's bad requests (Python and command line,
an unreachable Dask scheduler among them), and lfcam.simulate against `lfcam simulate`."""
import json
import os
import socket
import subprocess
import time

import numpy as np
import pytest

import lfcam
from batch_captures import STEPS, files_below, write_captures, without_times

LFCAM = os.environ.get("LFCAM_EXECUTABLE", "")


def lfcam_command(*arguments, env=None):
    return subprocess.run([LFCAM, *map(str, arguments)], capture_output=True, text=True,
                          env=None if env is None else {**os.environ, **env})


def one_error_line(result, code):
    assert result.returncode == code, result.stderr
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("lfcam: "), result.stderr
    return lines[0]


def test_python_batch_is_the_commands_batch(tmp_path):
    inputs = tmp_path / "in"
    write_captures(inputs, 3)
    (inputs / "broken.lf.h5").write_bytes(b"not a light field")
    cli = lfcam_command("batch", inputs, "-o", tmp_path / "cli", "--steps", ",".join(STEPS), "--jobs", 2)
    assert cli.returncode == 1 and "lfcam: batch: failed: " in cli.stderr and "broken.lf.h5" in cli.stderr

    finished = []
    with pytest.raises(lfcam.batch.BatchError, match="1 of 4 captures failed") as failed:
        lfcam.batch.run(str(inputs), tmp_path / "py", STEPS, jobs=2, progress=lambda k, n: finished.append((k, n)))
    assert finished[-1] == (4, 4) and finished == sorted(finished)
    report = failed.value.report
    assert (report["done"], report["skipped"], report["failed"]) == (3, 0, 1)
    broken = [c for c in report["captures"] if c["status"] == "failed"]
    assert len(broken) == 1 and "broken.lf.h5" in broken[0]["error"] and "\n" not in broken[0]["error"]
    assert report == json.loads((tmp_path / "py" / "batch-report.json").read_text())
    cli_report = json.loads((tmp_path / "cli" / "batch-report.json").read_text())
    assert without_times(report) == without_times(cli_report)
    assert files_below(tmp_path / "py") == files_below(tmp_path / "cli")

    # A rerun skips the complete captures and redoes one whose marker is gone (half-done).
    os.remove(tmp_path / "py" / "capture_01" / ".batch-done.json")
    (inputs / "broken.lf.h5").unlink()
    again = lfcam.batch.run([str(inputs / "*.lf.h5")], tmp_path / "py", ",".join(STEPS),
                            report=tmp_path / "again.json")
    assert (again["done"], again["skipped"], again["failed"]) == (1, 2, 0)
    assert [c["name"] for c in again["captures"] if c["status"] == "done"] == ["capture_01"]
    assert files_below(tmp_path / "py") == files_below(tmp_path / "cli")


def test_bad_batch_requests_are_one_line_errors(tmp_path):
    write_captures(tmp_path / "in", 1)
    capture = str(tmp_path / "in" / "capture_00.lf.h5")
    with pytest.raises(lfcam.UsageError, match="unknown step 'blur'"):
        lfcam.batch.run(capture, tmp_path / "out", ["refocus:0.5", "blur"])
    with pytest.raises(lfcam.UsageError, match="no file matches this pattern"):
        lfcam.batch.run(str(tmp_path / "in" / "*.lfp"), tmp_path / "out", "edof")
    with pytest.raises(lfcam.UsageError, match="expected stack:FROM:TO:N"):
        lfcam.batch.run(capture, tmp_path / "out", "stack:1:2")
    assert not (tmp_path / "out").exists()  # checked before any work

    spec = tmp_path / "spec.json"
    spec.write_text(json.dumps({"inputs": [capture], "output": str(tmp_path / "out"), "steps": ["edof", "sharpen"]}))
    assert "unknown step 'sharpen'" in one_error_line(lfcam_command("batch", "--spec", spec), 2)
    spec.write_text(json.dumps({"inputs": [capture], "output": str(tmp_path / "out"), "steps": "edof", "colour": 1}))
    assert "unknown key 'colour'" in one_error_line(lfcam_command("batch", "--spec", spec), 2)
    line = one_error_line(lfcam_command("batch", tmp_path / "in" / "*.png", "-o", tmp_path / "out", "--steps", "edof"), 2)
    assert "*.png: no file matches this pattern" in line
    assert "unknown step" in one_error_line(
        lfcam_command("batch", capture, "-o", tmp_path / "out", "--steps", "blur", "--dask", "tcp://127.0.0.1:1"), 2)
    assert not (tmp_path / "out").exists()


def unused_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def test_an_unreachable_scheduler_is_one_line_within_seconds(tmp_path):
    pytest.importorskip("distributed", reason="python3-distributed is not installed")
    write_captures(tmp_path / "in", 1)
    address = f"tcp://127.0.0.1:{unused_port()}"
    start = time.monotonic()
    with pytest.raises(lfcam.Error, match=f"cannot reach the Dask scheduler at {address}"):
        lfcam.batch.run(str(tmp_path / "in"), tmp_path / "out", "edof", client=address)
    assert time.monotonic() - start < lfcam.batch.CONNECT_TIMEOUT + 5

    start = time.monotonic()
    result = lfcam_command("batch", tmp_path / "in", "-o", tmp_path / "out", "--steps", "edof", "--dask", address)
    assert "cannot reach the Dask scheduler" in one_error_line(result, 1)
    assert time.monotonic() - start < lfcam.batch.CONNECT_TIMEOUT + 15  # python3 and Dask start too
    assert "unknown address scheme" in one_error_line(
        lfcam_command("batch", tmp_path / "in", "-o", tmp_path / "out", "--steps", "edof", "--dask", "bogus://x"), 2)
    no_python = lfcam_command("batch", tmp_path / "in", "-o", tmp_path / "out", "--steps", "edof", "--dask", address,
                              env={"LFCAM_PYTHON": "/no/such/python3"})
    assert "cannot run /no/such/python3" in one_error_line(no_python, 1)
    assert not (tmp_path / "out").exists()


def test_wrong_arrays_for_a_light_field_name_the_problem():
    with pytest.raises(lfcam.UsageError, match="expected an array of 5 dimensions, got 4"):
        lfcam.LightField(np.zeros((2, 2, 3, 4), np.float32))
    with pytest.raises(lfcam.UsageError, match="expected a numeric array, got dtype complex64"):
        lfcam.LightField(np.zeros((2, 2, 1, 4, 4), np.complex64))


def test_simulate_writes_the_commands_capture(tmp_path):
    settings = dict(size=64, samples=1, seed=7, f_number=4.0)
    cli = lfcam_command("simulate", "people", "-o", tmp_path / "cli", "--size", 64, "--samples", 1, "--seed", 7,
                        "--f-number", 4, "--no-ground-truth")
    assert cli.returncode == 0, cli.stderr
    lfcam.simulate("people", tmp_path / "py", ground_truth=False, **settings)
    assert sorted(os.listdir(tmp_path / "py")) == sorted(os.listdir(tmp_path / "cli"))
    for name in os.listdir(tmp_path / "cli"):
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    raw = lfcam.read_image(tmp_path / "py" / "raw.png")
    assert (raw.width, raw.height) == (64, 64) and raw.array.std() > 0
    with pytest.raises(lfcam.UsageError, match="samples 0 is outside"):
        lfcam.simulate("people", tmp_path / "bad", samples=0)
    with pytest.raises(lfcam.UsageError, match="size"):
        lfcam.simulate("people", tmp_path / "bad", size=4)
    with pytest.raises(lfcam.Error, match="no-such-scene"):
        lfcam.simulate("no-such-scene.json", tmp_path / "bad")
    assert not (tmp_path / "bad").exists()


def test_a_string_of_steps_splits_where_a_step_starts_not_inside_a_photographs_fields():
    from lfcam import _lfcam
    assert _lfcam._split_batch_steps("edof,photo:p?focus-plane=1,2:3,4:5,6&f-number=2,refocus:0.5,page") == [
        "edof", "photo:p?focus-plane=1,2:3,4:5,6&f-number=2", "refocus:0.5", "page"]
