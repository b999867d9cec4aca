"""lfcam.batch on a Dask cluster: a distributed.LocalCluster of 2 worker processes on loopback. Its
outputs are the single-machine batch's, byte for byte; a worker killed mid-batch loses nothing;
`lfcam batch --dask` hands over to the same code. Skipped, saying so, without python3-distributed."""
import json
import os
import signal
import subprocess
import threading
import time

import pytest

import lfcam
from batch_captures import STEPS, files_below, write_captures, without_times

distributed = pytest.importorskip("distributed", reason="python3-distributed is not installed (scripts/setup.sh)")

CAPTURES = 8


@pytest.fixture(scope="module")
def cluster():
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                                  dashboard_address=None) as local:
        with distributed.Client(local) as client:
            yield local, client


@pytest.fixture(scope="module")
def single_machine(tmp_path_factory):
    """The 8 captures and their outputs from the batch on this machine."""
    folder = tmp_path_factory.mktemp("batch")
    write_captures(folder / "in", CAPTURES)
    report = lfcam.batch.run(str(folder / "in"), folder / "local", STEPS, jobs=2)
    assert report["done"] == CAPTURES
    return folder, report, files_below(folder / "local")


def test_outputs_on_the_cluster_are_the_single_machine_outputs(cluster, single_machine):
    _, client = cluster
    folder, local_report, local_files = single_machine
    finished = []
    report = lfcam.batch.run(str(folder / "in"), folder / "dask", STEPS, client=client,
                             progress=lambda k, n: finished.append((k, n)))
    assert (report["done"], report["failed"]) == (CAPTURES, 0)
    assert finished[-1] == (CAPTURES, CAPTURES)
    assert without_times(report) == without_times(local_report)
    assert files_below(folder / "dask") == local_files
    # Run again: every capture is complete, so every task skips it.
    again = lfcam.batch.run(str(folder / "in"), folder / "dask", STEPS, client=client)
    assert again["skipped"] == CAPTURES


def test_a_worker_killed_mid_batch_loses_and_duplicates_nothing(cluster, single_machine):
    _, client = cluster
    folder, _, local_files = single_machine
    output = folder / "killed"
    outcome = {}

    def batch():
        try:
            outcome["report"] = lfcam.batch.run(str(folder / "in"), output, STEPS, client=client)
        except Exception as e:  # reported by the assertions below
            outcome["error"] = e

    runner = threading.Thread(target=batch)
    runner.start()
    pids = client.run(os.getpid)  # {worker address: its process}
    killed = None
    deadline = time.monotonic() + 120
    while killed is None and runner.is_alive() and time.monotonic() < deadline:
        markers = list(output.glob("*/.batch-done.json")) if output.exists() else []
        busy = [worker for worker, keys in client.processing().items() if keys and worker in pids]
        if markers and busy:  # one capture done, another in a worker's hands: kill that worker
            killed = busy[0]
            os.kill(pids[killed], signal.SIGKILL)
        time.sleep(0.02)
    runner.join(timeout=300)
    assert killed is not None, "the batch ended before a worker could be killed mid-capture"
    assert "error" not in outcome, outcome.get("error")
    report = outcome["report"]
    # Skipped: a capture whose worker died after its marker, before Dask heard of it, is found complete.
    assert (report["done"] + report["skipped"], report["failed"]) == (CAPTURES, 0)
    assert sorted(c["name"] for c in report["captures"]) == sorted(f"capture_{k:02d}" for k in range(CAPTURES))
    assert files_below(output) == local_files  # the redone capture removed the killed one's temporaries
    client.wait_for_workers(2, timeout=60)  # the nanny restarted it, for the tests after this one
    assert pids[killed] not in client.run(os.getpid).values()


def test_the_command_line_hands_over_to_the_cluster(cluster, single_machine):
    local, _ = cluster
    folder, _, local_files = single_machine
    spec = folder / "spec.json"
    spec.write_text(json.dumps({"inputs": [str(folder / "in")], "steps": STEPS, "dask": local.scheduler_address}))
    result = subprocess.run([os.environ["LFCAM_EXECUTABLE"], "batch", "--spec", str(spec), "-o", str(folder / "cli")],
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    assert f"batch: {CAPTURES} done, 0 skipped" in result.stdout
    assert files_below(folder / "cli") == local_files


def test_a_volume_step_on_the_cluster_shares_one_psf(cluster, tmp_path):
    """A microscope time series on the cluster: the PSF computed once, before the tasks, into the
    output folder; every worker only reads it; the volumes are the single machine's."""
    import numpy as np
    _, client = cluster
    series = tmp_path / "series"
    series.mkdir()
    for time_point in range(4):
        samples = np.full((7, 7, 1, 5, 6), 0.1, np.float32)
        samples[3, 3] = 0.6 + 0.1 * time_point
        lfcam.write(series / f"t{time_point}.lf.h5", lfcam.LightField(samples))
    settings = tmp_path / "microscope.json"
    settings.write_text(json.dumps({
        "calibrate": {"objective_magnification": 20, "objective_na": 0.5, "medium_index": 1.33,
                      "center_wavelength": 500, "ulens_pitch": 40, "ulens_focal_length": 800,
                      "pixel_size": 40 / 7, "num_slices": 3, "um_per_slice": 3, "supersample": 1},
        "deconvolve": {"max_iter": 2}}))
    steps = [f"volume:{settings}"]
    local = lfcam.batch.run(str(series), tmp_path / "local", steps, jobs=2)
    remote = lfcam.batch.run(str(series), tmp_path / "dask", steps, client=client)
    assert (remote["done"], remote["failed"]) == (4, 0)
    caches = sorted(p.name for p in (tmp_path / "dask").glob("lfcam-psf-*.h5"))
    assert len(caches) == 1
    written = (tmp_path / "dask" / caches[0]).stat().st_mtime_ns
    volumes = sorted((tmp_path / "dask").glob("*/volume.tif"))
    assert len(volumes) == 4
    assert all(v.stat().st_mtime_ns >= written for v in volumes)  # every volume after the one PSF
    for v in volumes:
        assert v.read_bytes() == (tmp_path / "local" / v.parent.name / "volume.tif").read_bytes()
    assert local["done"] == 4
    assert without_times(remote) == without_times(local)


def test_the_hand_over_takes_a_white_image_database(cluster, tmp_path):
    """`lfcam batch --whites DB --any-camera --dask`: each worker decodes its raw with the white the
    database chooses, as the single machine does."""
    local, _ = cluster
    capture = tmp_path / "capture"
    lfcam.simulate("chart", capture, size=128, samples=1, ground_truth=False)
    (capture / "white.json").write_text(json.dumps({"serial": "MICRO-1", "zoom_step": 300, "focus_step": 0}))
    (capture / "raw.json").write_text(json.dumps({"serial": "MICRO-2", "zoom_step": 280, "focus_step": 0}))
    lfcam_cli = os.environ["LFCAM_EXECUTABLE"]
    subprocess.run([lfcam_cli, "whites", "index", str(capture / "white.png"), "-o", str(tmp_path / "whites.json")],
                   check=True, capture_output=True)
    local_report = lfcam.batch.run([str(capture / "raw.png")], tmp_path / "local", "refocus:0",
                                   whites=tmp_path / "whites.json", any_camera=True)
    assert local_report["done"] == 1
    result = subprocess.run([lfcam_cli, "batch", str(capture / "raw.png"), "-o", str(tmp_path / "cli"), "--steps",
                             "refocus:0", "--whites", str(tmp_path / "whites.json"), "--any-camera", "--dask",
                             local.scheduler_address], capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    assert files_below(tmp_path / "cli") == files_below(tmp_path / "local")
