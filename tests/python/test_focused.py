"""lfcam's focused plenoptic (Raytrix) functions on a simulated multi-focus capture: the same
photographs as the commands, the calibration read beside it or found in it."""
import os
import shutil

import numpy as np
import pytest

import lfcam

SCENE = os.path.join(os.environ.get("LFCAM_TEST_DATA_DIR", os.path.join(os.path.dirname(__file__), "..", "data")),
                     "focused_multifocus_scene.json")


@pytest.fixture(scope="module")
def capture_folder(tmp_path_factory):
    folder = tmp_path_factory.mktemp("focused") / "capture"
    lfcam.simulate(SCENE, folder, samples=4, ground_truth=False)
    return folder


def test_a_capture_is_read_with_the_calibration_beside_it(capture_folder):
    capture = lfcam.read_focused(capture_folder / "raw.png")
    assert capture.packing == "hexagonal"
    assert capture.micro_image_diameter == pytest.approx(20, abs=0.01)
    assert capture.micro_image_orientation == "upright"
    assert len(capture.lens_types) == 3
    assert capture.calibration_path == str(capture_folder / "raw.xml")
    assert capture.image.array.shape == (1, 360, 480)


def test_depth_and_total_focus_agree_with_the_map_handed_back(capture_folder):
    capture = lfcam.read_focused(capture_folder / "raw.png")
    depth = lfcam.focused_depth(capture)
    v = depth.virtual_depth.array
    assert v.shape == (1, 84, 114)  # 5 pixels per 20 px lens, less half a lens each side
    # The background plane at 1 m lies at v ~ 3.4, the card at 0.8 m at ~ 5.1.
    assert 3.0 < np.median(v) < 4.0
    estimated = lfcam.focused_total_focus(capture).array
    given = lfcam.focused_total_focus(capture, depth=v).array
    np.testing.assert_array_equal(estimated, given)
    distance = lfcam.focused_distance(capture, v).array
    assert 900 < np.median(distance) < 1100  # most of the frame is the plane at 1 m
    moved = lfcam.focused_photo(capture, virtual_depth=3.4, aperture=0.3, viewpoint=(0.5, 0)).array
    assert moved.shape == given.shape and np.isfinite(moved).all()
    with pytest.raises(lfcam.UsageError):
        lfcam.focused_photo(capture, virtual_depth=3.4, aperture=0.8, viewpoint=(0.5, 0))


def test_an_uncalibrated_capture_is_calibrated_from_its_white_and_written(capture_folder, tmp_path):
    bare = tmp_path / "bare.png"
    shutil.copy(capture_folder / "raw.png", bare)
    with pytest.raises(lfcam.Error, match="no focused plenoptic calibration"):
        lfcam.read_focused(bare)
    found = lfcam.read_focused(bare, white=capture_folder / "white.png", self_calibrate=True)
    assert found.calibration_path is None
    assert found.micro_image_diameter == pytest.approx(20, abs=0.05)
    assert len(found.lens_types) == 3
    found.write_calibration(tmp_path / "bare.xml")
    assert lfcam.read_focused(bare).calibration_path == str(tmp_path / "bare.xml")
