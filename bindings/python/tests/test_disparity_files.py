"""Signed, sub-pixel disparities round-trip through files: the 16-bit offset
PNG (d16 + 32768, 0 = invalid) and Middlebury's PFM (float px, inf = invalid),
written by the module and by the CLI."""
import subprocess

import numpy as np
import pytest

import horopter

INVALID = -33 * 16
VALUES = np.array([[-40, INVALID, 0, 5, 300], [32767, -1, -512, -32767, 17]], dtype=np.int16)


def test_disparity16_png_round_trips_negative_and_subpixel(tmp_path):
    path = str(tmp_path / "d16.png")
    horopter.write_disparity16(path, VALUES, INVALID)
    raw = horopter.imread(path)
    assert raw.dtype == np.uint16
    expected = np.where(VALUES == INVALID, 0, VALUES.astype(np.int32) + 32768)
    np.testing.assert_array_equal(raw, expected)
    back = horopter.read_disparity16(path, INVALID)
    assert back.dtype == np.int16
    np.testing.assert_array_equal(back, VALUES)
    # Another marker for invalid on reading.
    other = horopter.read_disparity16(path, -16)
    np.testing.assert_array_equal(other == -16, VALUES == INVALID)


def test_pfm_round_trips_float_and_int16_with_inf_as_invalid(tmp_path):
    path = str(tmp_path / "d.pfm")
    horopter.write_pfm(path, VALUES, invalid=INVALID)
    with open(path, "rb") as f:
        assert f.read(12) == b"Pf\n5 2\n-1.0\n"
    px = horopter.read_pfm(path)
    assert px.dtype == np.float32 and px.shape == VALUES.shape
    assert np.isposinf(px[VALUES == INVALID]).all()
    np.testing.assert_array_equal(px[VALUES != INVALID], VALUES[VALUES != INVALID] / 16.0)
    # Bottom row first, little-endian, as Middlebury's files.
    data = np.fromfile(path, dtype="<f4", offset=12).reshape(2, 5)[::-1]
    np.testing.assert_array_equal(data, px)

    floats = np.array([[-1.25, np.inf, 3.0625], [0.0, 1e-3, -200.5]], dtype=np.float32)
    horopter.write_pfm(path, floats)
    np.testing.assert_array_equal(horopter.read_pfm(path), floats)
    horopter.write_pfm(path, floats.astype(np.float64))
    np.testing.assert_array_equal(horopter.read_pfm(path), floats)
    with pytest.raises(horopter.Error, match="invalid"):
        horopter.write_pfm(path, VALUES)


def test_imwrite_refuses_int16_instead_of_cutting_it(tmp_path):
    with pytest.raises(horopter.Error, match="write_disparity16"):
        horopter.imwrite(str(tmp_path / "d.png"), VALUES)
    # uint16 still writes 16 bits.
    wide = np.array([[0, 65535, 300]], dtype=np.uint16)
    horopter.imwrite(str(tmp_path / "w.png"), wide)
    np.testing.assert_array_equal(horopter.imread(str(tmp_path / "w.png")), wide)


def test_read_errors_name_the_file(tmp_path):
    missing = str(tmp_path / "missing.pfm")
    with pytest.raises(horopter.Error, match="missing.pfm"):
        horopter.read_pfm(missing)
    with pytest.raises(horopter.Error, match="missing.png"):
        horopter.read_disparity16(str(tmp_path / "missing.png"), -16)


def test_cli_writes_signed_disparities_that_read_back(grey_pair, cli, tmp_path):
    # A pair shifted so that the true disparities are negative: the right view
    # is the left moved 8 px to the right.
    left, _ = grey_pair
    right = np.zeros_like(left)
    right[:, 8:] = left[:, :-8]
    horopter.imwrite(str(tmp_path / "left.png"), left)
    horopter.imwrite(str(tmp_path / "right.png"), right)
    out = tmp_path / "out"
    subprocess.run([cli, "disparity", str(tmp_path / "left.png"), str(tmp_path / "right.png"),
                    "-o", str(out), "--min-disparity", "-32", "--num-disparities", "64",
                    "--fixation-disparity", "9", "--backend", "scalar"],
                   check=True, capture_output=True)
    params = horopter.StereoParams(minDisparity=-32, numDisparities=64)
    disparity = horopter.StereoMatcher(params, backend="scalar").compute(left, right)
    negative = (disparity != params.invalidDisparity) & (disparity < 0)
    assert negative.mean() > 0.3
    back16 = horopter.read_disparity16(str(out / "disparity16.png"), params.invalidDisparity)
    np.testing.assert_array_equal(back16, disparity)
    px = horopter.read_pfm(str(out / "disparity.pfm"))
    valid = disparity != params.invalidDisparity
    assert np.isinf(px[~valid]).all()
    np.testing.assert_array_equal(px[valid], disparity[valid] / 16.0)
