"""numpy in and out: views without copies, and clear errors where a copy would be needed."""
import numpy as np
import pytest

import horopter


def test_strided_view_gives_the_result_of_its_copy(grey_pair):
    left, right = grey_pair
    params = horopter.StereoParams(numDisparities=32, blockSize=7)
    # A window into a larger array: rows are strided, pixels within a row contiguous.
    big_left = np.zeros((300, 400), np.uint8)
    big_right = np.zeros((300, 400), np.uint8)
    big_left[20:260, 30:350] = left
    big_right[20:260, 30:350] = right
    view_left, view_right = big_left[20:260, 30:350], big_right[20:260, 30:350]
    assert not view_left.flags["C_CONTIGUOUS"]
    a = horopter.StereoMatcher(params, backend="scalar").compute(view_left, view_right)
    b = horopter.StereoMatcher(params, backend="scalar").compute(left.copy(), right.copy())
    assert a.dtype == np.int16 and a.shape == left.shape
    np.testing.assert_array_equal(a, b)


def test_in_place_kernels_write_the_callers_memory(grey_pair):
    """left_right_check works in place on a strided view: the caller's buffer changes
    inside the view and nowhere else, so no copy was made."""
    left, right = grey_pair
    params = horopter.StereoParams(numDisparities=32, blockSize=7, disp12MaxDiff=0)
    f_left, texture = horopter.prefilter_xsobel(left)
    f_right, _ = horopter.prefilter_xsobel(right)
    disparity, winner = horopter.match_blocks(f_left, f_right, texture, params)
    expected = disparity.copy()
    horopter.left_right_check(expected, winner, params)
    assert (expected != disparity).any(), "the check should invalidate some pixels"

    canvas = np.full((disparity.shape[0] + 4, disparity.shape[1] + 6), 1234, np.int16)
    canvas[2:-2, 3:-3] = disparity
    horopter.left_right_check(canvas[2:-2, 3:-3], winner, params)
    np.testing.assert_array_equal(canvas[2:-2, 3:-3], expected)
    assert (canvas[:2] == 1234).all() and (canvas[-2:] == 1234).all()
    assert (canvas[:, :3] == 1234).all() and (canvas[:, -3:] == 1234).all()


def test_wrong_dtype_is_a_type_error(grey_pair):
    left, right = grey_pair
    matcher = horopter.StereoMatcher(numDisparities=32)
    with pytest.raises(TypeError, match="dtype float32.*astype"):
        matcher.compute(left.astype(np.float32), right)
    with pytest.raises(TypeError, match="numpy array, got list"):
        matcher.compute(left.tolist(), right)
    with pytest.raises(TypeError, match="int16"):
        horopter.horopter_mask(np.zeros((4, 4), np.int16), np.zeros(4, np.int32))


def test_wrong_shape_is_a_value_error(grey_pair):
    left, right = grey_pair
    matcher = horopter.StereoMatcher(numDisparities=32)
    with pytest.raises(ValueError, match=r"shape \(240, 320, 4\)"):
        matcher.compute(np.zeros(left.shape + (4,), np.uint8), right)
    with pytest.raises(ValueError, match=r"shape \(240, 320, 3\), expected uint8 \(H, W\)"):
        matcher.compute(np.zeros(left.shape + (3,), np.uint8), right)
    with pytest.raises(ValueError, match="one dimension"):
        horopter.horopter_mask(np.zeros((4, 4), np.int16), np.zeros((4, 1), np.int16))


def test_layouts_that_need_a_copy_are_refused_and_say_so(grey_pair):
    left, right = grey_pair
    matcher = horopter.StereoMatcher(numDisparities=32)
    with pytest.raises(ValueError, match="contiguous.*would need a copy.*ascontiguousarray"):
        matcher.compute(np.asfortranarray(left), right)
    with pytest.raises(ValueError, match="would need a copy"):
        matcher.compute(left[:, ::2], right[:, ::2])
    with pytest.raises(ValueError, match="reversed or overlapping rows"):
        matcher.compute(left[::-1], right)
    odd = np.zeros(2 * 16 * 40 + 1, np.uint8)[1:].view(np.int16).reshape(16, 40)
    with pytest.raises(ValueError, match="aligned"):
        horopter.median_filter(odd)


def test_read_only_output_is_refused(grey_pair):
    left, right = grey_pair
    params = horopter.StereoParams(numDisparities=32, textureThreshold=0)
    disparity, _ = horopter.match_blocks(left, right, None, params)
    disparity.flags.writeable = False
    with pytest.raises(ValueError, match="read-only"):
        horopter.filter_speckles(disparity)


def test_bad_parameters_raise_horopter_error(grey_pair):
    left, right = grey_pair
    with pytest.raises(horopter.Error, match="blockSize"):
        horopter.StereoMatcher(blockSize=8)
    assert issubclass(horopter.Error, ValueError)
    with pytest.raises(TypeError, match="unknown stereo parameter 'blocksize'"):
        horopter.StereoParams(blocksize=9)
    with pytest.raises(horopter.Error, match="same size|size"):
        horopter.StereoMatcher(numDisparities=32).compute(left, right[:, :200])


def test_stereo_options_come_from_the_librarys_table():
    options = {o["name"]: o for o in horopter.stereo_options()}
    assert options["numDisparities"]["flag"] == "--num-disparities"
    assert options["numDisparities"]["min"] == 16 and options["numDisparities"]["max"] == 1024
    assert options["numDisparities"]["default"] == horopter.StereoParams().numDisparities
    # Every option is a keyword, and out of its range an error naming it.
    for name, o in options.items():
        assert getattr(horopter.StereoParams(**{name: o["default"]}), name) == o["default"]
        with pytest.raises(horopter.Error, match=name):
            horopter.StereoParams(**{name: o["max"] + 1})
    with pytest.raises(TypeError, match="must be an int"):
        horopter.StereoParams(numDisparities=True)


def test_tuning_options_come_from_the_librarys_tables():
    tables = horopter.tuning_options()
    assert set(tables) == {"detector", "election", "tracker", "head_control", "zone_search"}
    flags = set()
    for table in tables.values():
        for o in table:
            assert o["flag"].startswith("--") and o["flag"] not in flags
            flags.add(o["flag"])
            assert o["min"] <= o["default"] <= o["max"]
            assert o["help"]
    election = {o["name"]: o for o in tables["election"]}
    assert election["electS"]["flag"] == "--elect-s" and election["electS"]["unit"] == "s"
    assert election["electS"]["default"] == 2.0
