"""The zone's geometry from Python against its definitions."""
import math

import numpy as np
import pytest

import horopter


def test_threshold_table_is_the_circle_disparity_rounded_up():
    g = horopter.RectifiedGeometry(focal_px=500.0, cx=159.5, baseline=0.12, cy=119.5)
    fixation = horopter.fixation_at_distance(0.12, 1.5)
    np.testing.assert_allclose(fixation, [0.0, 0.0, 1.5])
    circle = horopter.vieth_mueller_circle(0.12, fixation)
    table = horopter.horopter_thresholds(g, circle, 320)
    assert table.dtype == np.int16 and table.shape == (320,)
    for u in (0, 100, 160, 319):
        t = (u - g.cx) / g.focal_px
        z = (g.baseline * t + 2 * circle.centre_z) / (t * t + 1)
        assert table[u] == math.ceil(16 * g.focal_px * g.baseline / z)
    # The same table from a FixationPoint in the left camera frame.
    left_frame = horopter.to_left_camera_frame(g, fixation)
    np.testing.assert_array_equal(horopter.horopter_thresholds(g, 320, left_frame), table)


def test_circle_depth_and_points():
    baseline = 0.1
    fixation = horopter.fixation_from_vergence(baseline, 0.1)
    assert fixation[2] == pytest.approx(baseline / 2 / math.tan(0.05))
    circle = horopter.vieth_mueller_circle(baseline, fixation)
    assert circle.radius ** 2 == pytest.approx((baseline / 2) ** 2 + circle.centre_z ** 2)
    assert horopter.inside_zone(circle, np.array([0.0, 0.0, fixation[2] * 0.9]))
    assert not horopter.inside_zone(circle, np.array([0.0, 0.0, fixation[2] * 1.1]))
    assert horopter.vergence_angle_at(baseline, fixation) == pytest.approx(0.1)
    g = horopter.RectifiedGeometry(focal_px=400.0, cx=200.0, baseline=baseline, cy=100.0)
    assert horopter.depth_from_disparity(g, 20.0) == pytest.approx(400 * baseline / 20)
    p = horopter.point_from_pixel(g, 200.0, 100.0, 20.0)
    np.testing.assert_allclose(p, [-baseline / 2, 0.0, 2.0])
    extent = horopter.zone_extent(baseline, circle)
    assert extent["far_on_axis"] == pytest.approx(fixation[2])
    with pytest.raises(horopter.Error):
        horopter.fixation_at_distance(baseline, -1.0)
