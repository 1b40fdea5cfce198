"""Each kernel from Python, chained, equals the front end; every backend equals scalar."""
import numpy as np
import pytest

import horopter

AVAILABLE = [b["name"] for b in horopter.backends() if b["available"]]


def chain(left, right, params, median, backend):
    f_left, texture = horopter.prefilter_xsobel(left, params.preFilterCap, backend)
    f_right, _ = horopter.prefilter_xsobel(right, params.preFilterCap, backend)
    disparity, winner = horopter.match_blocks(f_left, f_right, texture, params, backend)
    horopter.left_right_check(disparity, winner, params, backend)
    horopter.filter_speckles(disparity, params, backend)
    return horopter.median_filter(disparity, median, params.invalidDisparity, backend)


@pytest.mark.parametrize("backend", AVAILABLE)
def test_kernel_chain_equals_the_front_end(grey_pair, backend):
    left, right = grey_pair
    params = horopter.StereoParams(numDisparities=48, blockSize=9, minDisparity=-2)
    median = horopter.MedianParams(kernelSize=5)
    matcher = horopter.StereoMatcher(params, median, backend=backend, threads=2)
    expected = matcher.compute(left, right)
    np.testing.assert_array_equal(chain(left, right, params, median, backend), expected)
    assert (expected != params.invalidDisparity).mean() > 0.5


@pytest.mark.parametrize("backend", AVAILABLE)
def test_every_backend_equals_scalar(grey_pair, scene_frame, backend):
    left, right = grey_pair
    params = horopter.StereoParams(numDisparities=64)
    reference = horopter.StereoMatcher(params, backend="scalar")
    other = horopter.StereoMatcher(params, backend=backend)
    np.testing.assert_array_equal(other.compute(left, right), reference.compute(left, right))
    thresholds = np.full(left.shape[1], 20 * 16, np.int16)
    ref_mask, ref_seg = reference.compute_mask(thresholds, scene_frame["left"])
    mask, seg = other.compute_mask(thresholds, scene_frame["left"])
    np.testing.assert_array_equal(mask, ref_mask)
    np.testing.assert_array_equal(seg, ref_seg)


def test_mask_kernel_equals_the_rule(grey_pair, scene_frame):
    left, right = grey_pair
    params = horopter.StereoParams(numDisparities=64)
    matcher = horopter.StereoMatcher(params, backend="scalar")
    disparity = matcher.compute(left, right)
    thresholds = np.linspace(10 * 16, 30 * 16, left.shape[1]).astype(np.int16)
    mask, segmented = horopter.horopter_mask(disparity, thresholds, params.invalidDisparity,
                                             scene_frame["left"])
    inside = (disparity != params.invalidDisparity) & (disparity >= thresholds[None, :])
    np.testing.assert_array_equal(mask, np.where(inside, 255, 0).astype(np.uint8))
    np.testing.assert_array_equal(segmented, np.where(inside[:, :, None], scene_frame["left"], 0))
    m2, s2 = matcher.compute_mask(thresholds, scene_frame["left"])
    np.testing.assert_array_equal(m2, mask)
    np.testing.assert_array_equal(s2, segmented)
    _, none = matcher.compute_mask(thresholds)
    assert none is None


def test_a_failed_compute_leaves_no_result_behind(grey_pair):
    left, right = grey_pair
    matcher = horopter.StereoMatcher(horopter.StereoParams(numDisparities=64), backend="scalar")
    matcher.compute(left, right)
    thresholds = np.full(left.shape[1], 20 * 16, np.int16)
    matcher.compute_mask(thresholds)
    with pytest.raises(horopter.Error):
        matcher.compute(left, right[:, :-8])
    # The mask of the frame before must not pass for this frame's.
    with pytest.raises(horopter.Error, match="last call failed"):
        matcher.compute_mask(thresholds)
    matcher.compute(left, right)
    mask, _ = matcher.compute_mask(thresholds)
    assert mask.shape == left.shape


def test_backends_and_devices():
    names = [b["name"] for b in horopter.backends()]
    assert "scalar" in names and "scalar" in AVAILABLE
    assert horopter.find_backend("scalar") == "scalar"
    assert horopter.find_backend("auto") in AVAILABLE
    with pytest.raises(horopter.Error):
        horopter.find_backend("no-such-backend")
    devices = horopter.devices()
    assert set(devices) == {"cpu", "opencl", "backends"}
    assert devices["cpu"]["hardware_threads"] >= 1
    assert isinstance(devices["opencl"]["devices"], list)
