"""--whites from Python: decode, choose_white and batch.run take a white-image database (made by
`lfcam whites index`) where they take white=, and choose the white of the raw's camera, zoom and focus."""
import json
import os
import subprocess

import numpy as np
import pytest

import lfcam

LFCAM = os.environ.get("LFCAM_EXECUTABLE", "")


def side_car(path, zoom):
    path.write_text(json.dumps({"serial": "MICRO-1", "zoom_step": zoom, "focus_step": 0}))


@pytest.mark.skipif(not LFCAM, reason="needs the lfcam executable (LFCAM_EXECUTABLE) to index the whites")
def test_decode_choose_white_and_batch_take_a_database(tmp_path):
    capture = tmp_path / "capture"
    lfcam.simulate("chart", capture, size=128, samples=1, ground_truth=False)
    side_car(capture / "white.json", 300)
    side_car(capture / "raw.json", 280)
    database = tmp_path / "whites.json"
    subprocess.run([LFCAM, "whites", "index", str(capture / "white.png"), "-o", str(database)], check=True,
                   capture_output=True)

    chosen = lfcam.choose_white(capture / "raw.png", database)
    assert chosen["white"] == str(capture / "white.png")
    assert "of 1 whites of camera MICRO-1" in chosen["reason"]
    lf = lfcam.decode(str(capture / "raw.png"), whites=str(database))
    by_hand = lfcam.decode(str(capture / "raw.png"), white=str(capture / "white.png"))
    np.testing.assert_array_equal(lf.samples, by_hand.samples)

    (capture / "raw.json").write_text(json.dumps({"serial": "OTHER", "zoom_step": 280, "focus_step": 0}))
    with pytest.raises(lfcam.UsageError, match="camera OTHER has no white in"):
        lfcam.decode(str(capture / "raw.png"), whites=str(database))
    assert lfcam.decode(str(capture / "raw.png"), whites=str(database), any_camera=True).samples.shape == \
        lf.samples.shape

    report = lfcam.batch.run([str(capture / "raw.png")], tmp_path / "out", "refocus:0", whites=database,
                             any_camera=True)
    assert report["done"] == 1 and (tmp_path / "out" / "raw" / "refocus_0.png").exists()
