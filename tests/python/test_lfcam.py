"""The Python package lfcam (python/): zero-copy views, round trips, errors, and results identical
to the command line's. Run by CTest (label python) with PYTHONPATH=build/python; tests on
../shared/data skip, saying so, when it is absent."""
import os
import signal
import subprocess
import threading
import time

import numpy as np
import pytest

import lfcam

DATA = os.environ.get("LFCAM_SHARED_DATA_DIR", "")
ANTINOUS = os.path.join(DATA, "hci-antinous")
LFCAM = os.environ.get("LFCAM_EXECUTABLE", "")


def needs_antinous():
    if not os.path.isdir(ANTINOUS):
        pytest.skip(f"real data absent: {ANTINOUS} (see ../shared/data/SOURCES.md)")


def sloped_light_field(disparity=1, views=5, size=48, seed=3):
    """A textured plane of integer disparity: view (u, v) is the centre view shifted by -(u, v) d."""
    texture = np.random.default_rng(seed).random((size + 2 * views * abs(disparity), ) * 2, dtype=np.float32)
    samples = np.zeros((views, views, 1, size, size), np.float32)
    centre, margin = (views - 1) // 2, views * abs(disparity)
    for v in range(views):
        for u in range(views):
            dy, dx = (v - centre) * disparity, (u - centre) * disparity
            samples[v, u, 0] = texture[margin + dy:margin + dy + size, margin + dx:margin + dx + size]
    return lfcam.LightField(samples)


def test_samples_are_a_view_not_a_copy():
    lf = lfcam.LightField.zeros(3, 2, 8, 6, channels=3)
    assert lf.samples.shape == (2, 3, 3, 6, 8)
    lf.samples[1, 2, 0, 4, 5] = 7.5  # view (u=2, v=1), red, row 4, column 5
    assert lf.view(2, 1).array[0, 4, 5] == 7.5
    assert np.asarray(lf)[1, 2, 0, 4, 5] == 7.5
    samples = lf.samples
    del lf  # the array keeps the light field alive
    assert samples[1, 2, 0, 4, 5] == 7.5


def test_image_array_is_a_view_and_round_trips(tmp_path):
    pixels = np.random.default_rng(1).random((3, 20, 30), dtype=np.float32)
    image = lfcam.Image(pixels)
    image.array[2, 19, 29] = 0.25
    assert np.asarray(image)[2, 19, 29] == 0.25
    lfcam.write_image(tmp_path / "a.exr", image, bit_depth="float")
    back = lfcam.read_image(tmp_path / "a.exr")
    assert (back.width, back.height, back.channels) == (30, 20, 3)
    np.testing.assert_array_equal(back.array, image.array)


def test_light_field_round_trips_through_lf_h5(tmp_path):
    lf = sloped_light_field()
    lfcam.write(tmp_path / "a.lf.h5", lf)
    back = lfcam.read(tmp_path / "a.lf.h5")
    np.testing.assert_array_equal(back.samples, lf.samples)


def test_refocus_at_the_planes_disparity_is_its_texture():
    lf = sloped_light_field(disparity=1)
    photo = lfcam.refocus(lf, 1.0).array[0]
    centre = lf.view(2, 2).array[0]
    inner = (slice(6, -6), slice(6, -6))  # away from the borders, where fewer views contribute
    np.testing.assert_allclose(photo[inner], centre[inner], atol=1e-5)
    blurred = lfcam.refocus(lf, -1.0).array[0]
    assert np.abs(blurred[inner] - centre[inner]).mean() > 0.05


def test_upsample_renders_on_a_finer_grid_and_repeats_pixels_on_the_microlens_plane():
    lf = sloped_light_field(disparity=1)
    fine = lfcam.refocus(lf, 0.5, upsample=2).array
    assert fine.shape[1:] == (2 * lf.samples.shape[3], 2 * lf.samples.shape[4])
    plain = lfcam.refocus(lf, 0.0).array
    repeated = np.repeat(np.repeat(plain, 2, axis=1), 2, axis=2)
    np.testing.assert_allclose(lfcam.refocus(lf, 0.0, upsample=2).array, repeated, atol=1e-5)
    with pytest.raises(lfcam.UsageError, match="upsample: expected 1 to 4, got 5"):
        lfcam.refocus(lf, 0.5, upsample=5)


def test_focus_plane_through_three_points_of_a_fronto_parallel_plane_is_its_refocus():
    lf = sloped_light_field(disparity=1)
    tilted = lfcam.refocus(lf, focus_plane=((12, 12), (36, 14), (20, 36))).array[0]
    inner = (slice(6, -6), slice(6, -6))
    np.testing.assert_allclose(tilted[inner], lfcam.refocus(lf, 1.0).array[0][inner], atol=1e-2)
    with pytest.raises(lfcam.UsageError, match="one line"):
        lfcam.refocus(lf, focus_plane=((5, 5), (10, 10), (20, 20)))


def test_focus_range_over_a_plane_is_its_refocus_and_bad_ranges_raise():
    lf = sloped_light_field(disparity=1)
    flat = np.ones((48, 48), np.float32)
    inner = (slice(6, -6), slice(6, -6))
    spread = lfcam.refocus(lf, focus_range=(1.5, 0.5), depth=flat).array[0]
    np.testing.assert_allclose(spread[inner], lfcam.refocus(lf, 1.0).array[0][inner], atol=1e-5)
    # The plane lies beyond a range nearer than it: rendered at the range's far end, as a lens focused there.
    beyond = lfcam.refocus(lf, focus_range=(2.0, 1.5), depth=flat).array[0]
    np.testing.assert_allclose(beyond[inner], lfcam.refocus(lf, 1.5).array[0][inner], atol=1e-5)
    for bad in ({"focus_range": (0.5, 1.5)}, {"depth": flat},
                {"focus_range": (1.5, 0.5), "depth": np.ones((10, 10), np.float32)}):
        with pytest.raises(lfcam.UsageError):
            lfcam.refocus(lf, **bad)


def test_depth_finds_the_disparity_and_takes_the_commands_options():
    lf = sloped_light_field(disparity=1)
    result = lfcam.depth(lf, min=-2.0, max=2.0, median_radius=2)
    disparity = result.disparity.array[0][8:-8, 8:-8]
    assert abs(np.median(disparity) - 1.0) < 0.05
    with pytest.raises(lfcam.UsageError, match="unknown option 'no_such_knob'"):
        lfcam.depth(lf, no_such_knob=1)
    with pytest.raises(lfcam.UsageError, match="median_radius"):
        lfcam.depth(lf, median_radius=-4)


def test_denoise_keeps_a_plane_in_its_passband_and_removes_noise():
    lf = sloped_light_field(disparity=1, views=7, size=64)
    clean = lf.samples.copy()
    noise = np.random.default_rng(1).normal(0, 0.05, clean.shape).astype(np.float32)
    lf.samples[...] += noise
    out = lfcam.denoise(lf, depth_range=(0.8, 1.2)).samples
    inner = (Ellipsis, slice(10, -10), slice(10, -10))
    assert np.sqrt(((out - clean)[inner] ** 2).mean()) < 0.5 * np.sqrt((noise[inner] ** 2).mean())
    with pytest.raises(lfcam.UsageError, match="A <= B"):
        lfcam.denoise(lf, depth_range=(1, 0))


def test_score_of_the_truth_is_perfect():
    truth = np.linspace(-1, 1, 64 * 64, dtype=np.float32).reshape(64, 64)
    scores = lfcam.score(truth, truth, border=4)
    assert scores["badpix_0.07"] == 0 and scores["mse_x100"] == 0 and scores["pixels"] == 56 * 56
    with pytest.raises(lfcam.UsageError):
        lfcam.score(truth, truth[:32], border=4)


def test_score_at_more_thresholds():
    truth = np.zeros((64, 64), np.float32)
    estimate = truth.copy()
    estimate[:, 32:] = 0.05  # bad at 0.035 and 0.04 on half the pixels, not at 0.07
    scores = lfcam.score(estimate, truth, border=0, badpix=[0.035, 0.04])
    assert scores["badpix_0.035"] == 50 and scores["badpix_0.04"] == 50 and scores["badpix_0.07"] == 0
    with pytest.raises(lfcam.UsageError, match="threshold must be positive"):
        lfcam.score(estimate, truth, badpix=[0])


def test_bad_arrays_and_arguments_raise_one_line_errors():
    with pytest.raises(lfcam.UsageError, match="expected an array of 5 dimensions, got 3"):
        lfcam.LightField(np.zeros((2, 3, 4), np.float32))
    with pytest.raises(lfcam.UsageError, match="expected a numeric array"):
        lfcam.Image(np.array([["a", "b"], ["c", "d"]]))
    lf = sloped_light_field()
    with pytest.raises(lfcam.UsageError, match="give the focus: slope, alpha"):
        lfcam.refocus(lf)
    with pytest.raises(lfcam.UsageError, match="no optics metadata"):
        lfcam.refocus(lf, alpha=1.1)
    with pytest.raises(lfcam.UsageError, match="method: expected fast, quadrature or fourier, got 'wavelet'"):
        lfcam.refocus(lf, 0.0, method="wavelet")
    with pytest.raises(lfcam.UsageError, match="unknown keyword 'aperture_radius'"):
        lfcam.refocus(lf, 0.0, aperture_radius=1)
    with pytest.raises(lfcam.UsageError, match="clamp: expected true or false, got 'maybe'"):
        lfcam.refocus(lf, 0.0, clamp="maybe")
    with pytest.raises(lfcam.Error) as failed:
        lfcam.read("/no/such/light/field.lf.h5")
    assert "\n" not in str(failed.value) and "/no/such/light/field.lf.h5" in str(failed.value)
    assert not isinstance(failed.value, lfcam.UsageError)


def test_light_fields_with_non_finite_samples_or_impossible_shapes_are_refused_as_files_are(tmp_path):
    lf = lfcam.LightField.zeros(3, 3, 8, 8, channels=1)
    lf.samples[1, 2, 0, 3, 4] = np.inf  # through the view, unchecked: what a file could hold
    lfcam.write(tmp_path / "inf.lf.h5", lf)
    with pytest.raises(lfcam.Error) as read:
        lfcam.read(tmp_path / "inf.lf.h5")
    with pytest.raises(lfcam.UsageError) as given:
        lfcam.LightField(lf.samples)
    assert str(given.value) == str(read.value).replace(str(tmp_path / "inf.lf.h5"), "LightField")
    assert str(given.value) == f"LightField: sample {5 * 64 + 3 * 8 + 4} is infinite; only finite values are accepted"
    with pytest.raises(lfcam.UsageError, match="^LightField: sample 0 is NaN; only finite values are accepted$"):
        lfcam.LightField(np.full((3, 3, 1, 8, 8), np.nan, np.float32))
    with pytest.raises(lfcam.UsageError, match="^LightField: weight 0 is NaN"):
        lfcam.LightField(np.ones((3, 3, 1, 8, 8), np.float32), weights=np.full((3, 3, 8, 8), np.nan, np.float32))
    with pytest.raises(lfcam.UsageError, match=r"^samples: shape \(3, 3, 1, 0, 8\) has an empty or absurd dimension$"):
        lfcam.LightField(np.zeros((3, 3, 1, 0, 8), np.float32))
    with pytest.raises(lfcam.UsageError, match=r"^Image: shape \(0, 4\) has an empty or absurd dimension$"):
        lfcam.Image(np.zeros((0, 4), np.float32))
    with pytest.raises(lfcam.UsageError, match="every size must be at least 1"):
        lfcam.LightField.zeros(-1, 3, 8, 8)
    with pytest.raises(lfcam.Error, match="^LightField.zeros: needs more than 16 EiB of memory for its samples"):
        lfcam.LightField.zeros(10**5, 10**5, 10**5, 10**5)


def png_header(data):
    """(width, height, bit depth, colour type) of PNG bytes."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and data[12:16] == b"IHDR"
    return int.from_bytes(data[16:20], "big"), int.from_bytes(data[20:24], "big"), data[24], data[25]


def test_images_and_light_fields_show_themselves_in_jupyter_as_srgb_png(tmp_path):
    image = lfcam.Image(np.full((3, 20, 30), 0.5, np.float32))
    png = image._repr_png_()
    assert png_header(png) == (30, 20, 8, 2)  # 8-bit RGB
    (tmp_path / "image.png").write_bytes(png)
    # An 8-bit PNG holds sRGB codes: read back as such, it is the linear value to 8 bits (0.5 is code 188).
    np.testing.assert_allclose(lfcam.read_image(tmp_path / "image.png").array, image.array, atol=0.005)

    for views in (5, 4):  # the centre view, or the view left of and above the centre
        lf = sloped_light_field(views=views)
        png = lf._repr_png_()
        assert png_header(png) == (48, 48, 8, 0)  # 8-bit grey: one channel
        (tmp_path / "lf.png").write_bytes(png)
        centre = lf.view((views - 1) // 2, (views - 1) // 2).array
        np.testing.assert_allclose(lfcam.read_image(tmp_path / "lf.png").array, centre, atol=0.01)


def test_threads_overlap_calls_with_the_same_results():
    lf = sloped_light_field(size=96)
    alone = lfcam.refocus(lf, 0.5).array.copy()
    results = [None] * 4

    def run(k):
        results[k] = lfcam.refocus(lf, 0.5).array.copy()

    threads = [threading.Thread(target=run, args=(k, )) for k in range(4)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    for result in results:
        np.testing.assert_array_equal(result, alone)


def test_refocus_is_the_commands_photograph(tmp_path):
    needs_antinous()
    out = tmp_path / "cli.exr"
    subprocess.run([LFCAM, "refocus", ANTINOUS, "--slope", "0.5", "--aperture", "2", "--bit-depth", "float", "-o",
                    str(out)], check=True, capture_output=True)
    lf = lfcam.read(ANTINOUS)
    photo = lfcam.refocus(lf, 0.5, aperture=2)
    np.testing.assert_array_equal(photo.array, lfcam.read_image(out).array)
    stack = lfcam.stack(lf, alphas=[0.98, 1.0, 1.02])
    assert len(stack) == 3
    np.testing.assert_array_equal(stack[1].array, lfcam.refocus(lf, 0.0).array)


def test_ctrl_c_stops_a_long_call_soon():
    lf = sloped_light_field(size=192, views=9)
    start = time.perf_counter()
    lfcam.stack(lf, [0.1] * 16)
    per_photo = (time.perf_counter() - start) / 16
    count = max(8, int(3.0 / per_photo))  # about 3 s of work, measured in this run
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    timer = threading.Timer(0.2, os.kill, (os.getpid(), signal.SIGINT))
    try:
        timer.start()
        start = time.perf_counter()
        with pytest.raises(KeyboardInterrupt):
            lfcam.stack(lf, [0.1] * count)
        stopped_after = time.perf_counter() - start
    finally:
        timer.cancel()
        signal.signal(signal.SIGINT, previous)
    assert stopped_after < 0.75 * count * per_photo  # it did not run to the end (a loaded machine may be slow to stop)
    np.testing.assert_array_equal(lfcam.refocus(lf, 0.1).array, lfcam.stack(lf, [0.1])[0].array)  # usable again


REFUSALS = os.path.join(os.path.dirname(__file__), "..", "photo_request", "refusals.json")


def test_the_table_of_refusals_is_refused_with_the_command_lines_line():
    import json
    lf = lfcam.LightField(np.random.default_rng(0).random((5, 5, 1, 40, 40), np.float32))
    with open(REFUSALS) as table:
        cases = json.load(table)["cases"]
    for case in cases:
        keywords = {name.replace("-", "_"): text for name, text in case["fields"].items()}
        with pytest.raises(lfcam.UsageError) as refused:
            lfcam.refocus(lf, **keywords)
        assert case["message"] in str(refused.value), (keywords, str(refused.value))
        assert "\n" not in str(refused.value)
    # The refusals the command line gives for files (tests/cli/render_commands_test.cpp), for arrays.
    with pytest.raises(lfcam.UsageError) as refused:
        lfcam.refocus(lf, 1, aperture_mask=np.ones((32, 64), np.float32))
    assert str(refused.value) == ("aperture-mask: the mask is 64x32 pixels, the lens 5x5 views: "
                                  "it must have the lens's proportions")
    with pytest.raises(lfcam.UsageError) as refused:
        lfcam.refocus(lf, focus_range=(1, 0), depth=np.zeros((10, 10), np.float32))
    assert str(refused.value) == "depth: focus spread: the disparity map is 10x10x1, the views 40x40 (one channel needed)"


def test_every_combination_renders_from_python_values():
    lf = sloped_light_field(disparity=1)
    flat = np.ones((48, 48), np.float32)
    for keywords in ({"slope": 0.5, "tilt": 1.0, "aperture": 1.5, "aperture_centre": (0.5, 0)},
                     {"focus_plane": ((12, 12), (36, 14), (20, 36)), "f_number": 2},
                     {"slope": 0.5, "tilt": 1, "upsample": 2},
                     {"focus_range": (1.5, 0.5), "depth": flat, "aperture": 1},
                     {"focus_range": "1.5:0.5", "depth": flat, "method": "quadrature"},
                     {"slope": 0.2, "aperture": 0, "aperture_centre": [3, 0], "clamp": True}):
        photo = lfcam.refocus(lf, **keywords).array
        scale = keywords.get("upsample", 1)
        assert photo.shape == (1, 48 * scale, 48 * scale), keywords
        assert np.isfinite(photo).all() and photo.max() > 0, keywords


def test_the_stub_lists_the_photograph_requests_fields():
    import ast
    with open(os.path.join(os.path.dirname(lfcam.__file__), "__init__.pyi")) as stub:
        tree = ast.parse(stub.read())
    signatures = {node.name: node for node in tree.body if isinstance(node, ast.FunctionDef)}
    fields = [field["name"] for field in lfcam.photo_fields()]
    refocus = signatures["refocus"].args
    assert [a.arg for a in refocus.args[1:] + refocus.kwonlyargs] == fields
    stack = signatures["stack"].args
    focus = {field["name"] for field in lfcam.photo_fields() if field["group"] == "focus"}
    assert [a.arg for a in stack.kwonlyargs[1:]] == [f for f in fields if f not in focus and f != "upsample"]
    assert all(field["name"] in lfcam.refocus.__doc__ for field in lfcam.photo_fields())
