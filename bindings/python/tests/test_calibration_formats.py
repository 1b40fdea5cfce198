"""Calibrations from elsewhere, from Python: an OpenCV FileStorage file (as
cv2.FileStorage writes it, text made here: cv2 is not needed), ROS
camera_info pairs (as ROS's camera_calibration writes them), and the way
back to ROS with write_ros_camera_info."""
import glob
import os
import subprocess

import numpy as np
import pytest

import horopter

K1 = [[520.5, 0, 318.25], [0, 521.75, 242.5], [0, 0, 1]]
K2 = [[515.125, 0, 325.5], [0, 516.0, 236.75], [0, 0, 1]]
D1 = [-0.28, 0.09, 0.0012, -0.0007, -0.011]
D2 = [-0.265, 0.081, -0.0009, 0.0004, -0.008]


def _rodrigues(v):
    """The rotation by |v| radians about v."""
    v = np.asarray(v, dtype=np.float64)
    angle = np.linalg.norm(v)
    k = v / angle
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + np.sin(angle) * kx + (1 - np.cos(angle)) * kx @ kx


R = _rodrigues([0.011, -0.019, 0.006])  # about 1.3 degrees
T = [-0.1203, 0.0021, -0.0017]


def _opencv_matrix(name, rows):
    """One field as cv2.FileStorage writes a float64 array."""
    rows = np.atleast_2d(np.asarray(rows, dtype=np.float64))
    data = ", ".join(repr(float(v)) for v in rows.flat)
    return (f"{name}: !!opencv-matrix\n   rows: {rows.shape[0]}\n   cols: {rows.shape[1]}\n"
            f"   dt: d\n   data: [ {data} ]\n")


def _opencv_file(path, with_size=True):
    text = "%YAML:1.0\n---\n"
    if with_size:
        text += "image_width: 640\nimage_height: 480\n"
    text += _opencv_matrix("K1", K1) + _opencv_matrix("D1", [D1]) + _opencv_matrix("K2", K2)
    text += _opencv_matrix("D2", [D2]) + _opencv_matrix("R", R)
    text += _opencv_matrix("T", np.reshape(T, (3, 1)))
    path.write_text(text)
    return path


def _ros_matrix(name, m):
    """A matrix as camera_calibration's format_mat lays it out."""
    m = np.asarray(m, dtype=np.float64)
    rows = [", ".join(repr(float(v)) for v in row) for row in m]
    return (f"{name}:\n  rows: {m.shape[0]}\n  cols: {m.shape[1]}\n"
            f"  data: [{(',' + chr(10) + '        ').join(rows)}]\n")


def _ros_file(path, name, k, d, r, p, model="plumb_bob", size=(640, 480)):
    path.write_text(f"image_width: {size[0]}\nimage_height: {size[1]}\ncamera_name: {name}\n"
                    + _ros_matrix("camera_matrix", k) + f"distortion_model: {model}\n"
                    + _ros_matrix("distortion_coefficients", np.reshape(d, (1, -1)))
                    + _ros_matrix("rectification_matrix", r)
                    + _ros_matrix("projection_matrix", p))
    return path


@pytest.fixture
def opencv_calib(tmp_path):
    return horopter.load_calibration(str(_opencv_file(tmp_path / "stereo.yml")))


def test_opencv_file_is_rectified_as_horopter_does(opencv_calib):
    c = opencv_calib
    assert c.format == "opencv"
    assert c.image_size == (640, 480)
    assert c.inner_corners is None and c.square_size is None
    np.testing.assert_array_equal(c.K1, K1)
    np.testing.assert_array_equal(c.D2, [D2])
    np.testing.assert_array_equal(c.T.ravel(), T)
    # stereoRectify's rectified pair: the baseline is |T|, rows aligned.
    g = horopter.rectified_geometry(c)
    assert g.baseline == pytest.approx(np.linalg.norm(T), rel=1e-12)
    assert abs(c.P2[1, 3]) < 1e-9
    np.testing.assert_allclose(c.R2.T @ c.R1, c.R, atol=1e-6)


def test_opencv_file_without_image_size_needs_one(tmp_path):
    path = _opencv_file(tmp_path / "stereo.yml", with_size=False)
    with pytest.raises(horopter.Error, match="image_size="):
        horopter.load_calibration(str(path))
    c = horopter.load_calibration(str(path), image_size=(640, 480), alpha=1.0)
    assert c.image_size == (640, 480) and c.alpha == 1.0
    with pytest.raises(horopter.Error, match="width, height"):
        horopter.load_calibration(str(path), image_size=(640,))


def test_ros_round_trip(opencv_calib, tmp_path):
    left, right = tmp_path / "left.yaml", tmp_path / "right.yaml"
    horopter.write_ros_camera_info(opencv_calib, str(left), str(right), camera_name="head")
    text = right.read_text()
    assert "camera_name: head/right\n" in text and "distortion_model: plumb_bob\n" in text
    back = horopter.load_calibration(str(tmp_path))  # the folder
    assert back.format == "ros camera_info"
    for name in ("K1", "D1", "K2", "D2", "R1", "R2", "P1", "P2"):
        np.testing.assert_array_equal(getattr(back, name), getattr(opencv_calib, name), name)
    # The extrinsics come back from the rectification: R = R2^T R1, T = R2^T t.
    np.testing.assert_allclose(back.R, opencv_calib.R, atol=1e-12)
    np.testing.assert_allclose(back.T, opencv_calib.T, atol=1e-12)
    np.testing.assert_allclose(back.Q, opencv_calib.Q, rtol=1e-12, atol=1e-12)
    # Horopter's file from it, and back.
    horopter.save_calibration(back, str(tmp_path / "calib.yml"))
    again = horopter.load_calibration(str(tmp_path / "calib.yml"))
    assert again.format == "ros camera_info"
    np.testing.assert_array_equal(again.P2, back.P2)


def test_ros_pair_as_camera_calibration_writes_it(opencv_calib, tmp_path):
    c = opencv_calib
    _ros_file(tmp_path / "cam_left.yaml", "narrow_stereo/left", np.round(c.K1, 5),
              np.round(c.D1, 6), np.round(c.R1, 8), np.round(c.P1, 5))
    _ros_file(tmp_path / "cam_right.yaml", "narrow_stereo/right", np.round(c.K2, 5),
              np.round(c.D2, 6), np.round(c.R2, 8), np.round(c.P2, 5))
    back = horopter.load_calibration(str(tmp_path / "cam_left.yaml"))
    # Rounded as ROS rounds: R within 1e-7, T within 1e-6 (of a 0.12 baseline).
    np.testing.assert_allclose(back.R, c.R, atol=1e-7)
    np.testing.assert_allclose(back.T, c.T, atol=1e-6)
    # The right file first, or given explicitly, is the same pair.
    again = horopter.load_calibration(str(tmp_path / "cam_right.yaml"))
    np.testing.assert_array_equal(again.K1, back.K1)
    (tmp_path / "cam_right.yaml").rename(tmp_path / "other.yaml")
    with pytest.raises(horopter.Error, match="right="):
        horopter.load_calibration(str(tmp_path / "cam_left.yaml"))
    given = horopter.load_calibration(str(tmp_path / "cam_left.yaml"),
                                      right=str(tmp_path / "other.yaml"))
    np.testing.assert_array_equal(given.P2, back.P2)


def test_bad_ros_files_name_the_field(opencv_calib, tmp_path):
    c = opencv_calib
    _ros_file(tmp_path / "right.yaml", "r", c.K2, c.D2, c.R2, c.P2)
    _ros_file(tmp_path / "left.yaml", "l", c.K1, c.D1[:, :4], c.R1, c.P1, model="equidistant")
    with pytest.raises(horopter.Error, match="equidistant.*fisheye"):
        horopter.load_calibration(str(tmp_path))
    _ros_file(tmp_path / "left.yaml", "l", c.K1, c.D1, c.R1, c.P1)
    text = (tmp_path / "left.yaml").read_text()
    (tmp_path / "left.yaml").write_text(text.replace("rectification_matrix", "rectification"))
    with pytest.raises(horopter.Error, match="'rectification_matrix' is missing"):
        horopter.load_calibration(str(tmp_path))
    # Two single-camera calibrations: no baseline.
    _ros_file(tmp_path / "left.yaml", "l", c.K1, c.D1, c.R1, c.P1)
    _ros_file(tmp_path / "right.yaml", "r", c.K2, c.D2, c.R2, c.P1)
    with pytest.raises(horopter.Error, match="no baseline"):
        horopter.load_calibration(str(tmp_path))


VIEWS = "/usr/share/doc/opencv-doc/examples/data"


def test_cli_ros_out_matches_python(cli, tmp_path):
    """`horopter calibrate --ros-out` and write_ros_camera_info write the same files."""
    if not glob.glob(os.path.join(VIEWS, "left0*.jpg")):
        pytest.skip(f"opencv-doc's chessboard views are not in {VIEWS} (apt-get install opencv-doc)")
    subprocess.run([cli, "calibrate", "--left", f"{VIEWS}/left*.jpg", "--right",
                    f"{VIEWS}/right*.jpg", "--board", "9x6", "--square", "0.025", "-o",
                    str(tmp_path / "calib.yml"), "--ros-out", str(tmp_path / "cli_ros"),
                    "--camera-name", "head"], check=True, capture_output=True)
    calib = horopter.load_calibration(str(tmp_path / "calib.yml"))
    assert calib.inner_corners == (9, 6) and calib.square_size == 0.025
    horopter.write_ros_camera_info(calib, str(tmp_path / "left.yaml"),
                                   str(tmp_path / "right.yaml"), camera_name="head")
    for side in ("left", "right"):
        assert (tmp_path / f"{side}.yaml").read_text() == \
            (tmp_path / "cli_ros" / f"{side}.yaml").read_text()
    ros = horopter.load_calibration(str(tmp_path / "cli_ros"))
    np.testing.assert_allclose(ros.T, calib.T, rtol=0, atol=1e-12)
    assert horopter.rectified_geometry(ros).baseline == pytest.approx(
        horopter.rectified_geometry(calib).baseline, rel=1e-12)
