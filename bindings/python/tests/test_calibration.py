"""Calibration files from Python: a file written by `horopter calibrate` on
opencv-doc's chessboard views, read, rectified with, saved and read again."""
import glob
import math
import os
import subprocess

import numpy as np
import pytest

import horopter

VIEWS = "/usr/share/doc/opencv-doc/examples/data"


@pytest.fixture(scope="module")
def calib_file(cli, tmp_path_factory):
    if not glob.glob(os.path.join(VIEWS, "left0*.jpg")):
        pytest.skip(f"opencv-doc's chessboard views are not in {VIEWS} (apt-get install opencv-doc)")
    path = tmp_path_factory.mktemp("calib") / "calib.yml"
    subprocess.run([cli, "calibrate", "--left", f"{VIEWS}/left*.jpg", "--right",
                    f"{VIEWS}/right*.jpg", "--board", "9x6", "--square", "0.025", "-o",
                    str(path)], check=True, capture_output=True)
    return path


def test_load_rectify_save(calib_file, tmp_path):
    calib = horopter.load_calibration(str(calib_file))
    assert calib.image_size == (640, 480)
    assert calib.K1.shape == (3, 3) and calib.P2.shape == (3, 4)
    assert 0 < calib.rms < 2
    g = horopter.rectified_geometry(calib)
    assert g.focal_px == pytest.approx(calib.P1[0, 0])
    assert g.baseline == pytest.approx(-calib.P2[0, 3] / calib.P2[0, 0])
    assert g.baseline > 0

    left = horopter.imread(os.path.join(VIEWS, "left01.jpg"))
    right = horopter.imread(os.path.join(VIEWS, "right01.jpg"))
    rectifier = horopter.StereoRectifier(calib)
    rl, rr = rectifier.rectify(left, right)
    assert rl.shape == left.shape and rr.shape == right.shape
    assert not np.array_equal(rl, left)  # remapped
    rl2, _ = rectifier.rectify(left, right)
    np.testing.assert_array_equal(rl, rl2)  # the buffers of the first call were not reused

    saved = tmp_path / "again.yml"
    horopter.save_calibration(calib, str(saved))
    again = horopter.load_calibration(str(saved))
    np.testing.assert_allclose(again.P2, calib.P2)
    assert math.isclose(horopter.rectified_geometry(again).baseline, g.baseline)


def test_bad_files_say_what_is_wrong(tmp_path):
    with pytest.raises(horopter.Error, match="no_such.yml"):
        horopter.load_calibration(str(tmp_path / "no_such.yml"))
    bad = tmp_path / "bad.yml"
    bad.write_text("%YAML:1.0\n---\nimage_size: [1, 2]\n")
    with pytest.raises(horopter.Error):
        horopter.load_calibration(str(bad))


def _views(side):
    paths = sorted(glob.glob(os.path.join(VIEWS, f"{side}[0-9][0-9].jpg")))
    if not paths:
        pytest.skip(f"opencv-doc's chessboard views are not in {VIEWS} (apt-get install opencv-doc)")
    return [horopter.imread(p, grey=True) for p in paths]


def test_find_board_corners():
    image = _views("left")[0]
    corners = horopter.find_board_corners(image, (9, 6))
    assert corners.shape == (54, 2) and corners.dtype == np.float32
    h, w = image.shape
    assert (corners[:, 0] >= 0).all() and (corners[:, 0] < w).all()
    assert (corners[:, 1] >= 0).all() and (corners[:, 1] < h).all()
    # A board that is not there: no corners, not an error.
    assert horopter.find_board_corners(np.zeros((120, 160), np.uint8), (9, 6)) is None
    with pytest.raises(horopter.Error, match="inner_corners"):
        horopter.find_board_corners(image, (1, 6))


def test_calibrate_from_images_matches_the_cli(calib_file):
    lefts, rights = _views("left"), _views("right")
    calib = horopter.calibrate(lefts, rights, square_size=0.025, inner_corners=(9, 6))
    assert calib.image_size == (640, 480)
    assert 0 < calib.rms < 2
    assert len(calib.views) + len(calib.skipped) == len(lefts)
    # The same views through `horopter calibrate` give the same baseline.
    cli = horopter.load_calibration(str(calib_file))
    assert horopter.rectified_geometry(calib).baseline == pytest.approx(
        horopter.rectified_geometry(cli).baseline, rel=1e-6)


def test_calibrate_says_what_is_wrong():
    lefts, rights = _views("left"), _views("right")
    with pytest.raises(horopter.Error, match="in pairs"):
        horopter.calibrate(lefts, rights[:-1], square_size=0.025)
    with pytest.raises(horopter.Error):
        horopter.calibrate(lefts[:2], rights[:2], square_size=0.025)  # too few views
    with pytest.raises(horopter.Error):
        horopter.calibrate(lefts, rights, square_size=-1.0)
