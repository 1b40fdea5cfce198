"""The frame pipeline iterated from Python: arrays and plain dicts per frame."""
import numpy as np
import pytest

import horopter


def test_synthetic_frames_in_order_with_arrays_and_dicts():
    params = horopter.StereoParams(numDisparities=48)
    with horopter.Pipeline("synthetic", frames=4, size=(160, 120), params=params,
                           backend="scalar", in_flight=2) as pipeline:
        frames = list(pipeline)
        summary = pipeline.summary
    assert [f["index"] for f in frames] == [0, 1, 2, 3]
    for f in frames:
        assert f["left"].shape == (120, 160, 3) and f["left"].dtype == np.uint8
        assert f["disparity"].shape == (120, 160) and f["disparity"].dtype == np.int16
        assert f["mask"].shape == (120, 160) and f["mask"].dtype == np.uint8
        assert f["thresholds"].shape == (160,) and f["thresholds"].dtype == np.int16
        assert set(f["body"]) == {"frame", "time_s", "godfather", "head", "left_hand", "right_hand"}
        assert set(f["body"]["head"]) == {"tracked", "observed", "image", "rig"}
        assert f["truth"]["head"]["vergence"] > 0
        assert isinstance(f["truth"]["people"], list) and f["truth"]["people"]
        # Placeholders until detection, tracking and movement stages land.
        assert f["detections"] is None and f["tracking"] is None and f["movement"] is None
    assert summary["frames"] == 4


def test_pipeline_results_equal_the_matcher_on_the_same_frame():
    params = horopter.StereoParams(numDisparities=48)
    pipeline = horopter.Pipeline("synthetic", frames=2, size=(160, 120), params=params,
                                 backend="auto", threads=2)
    matcher = horopter.StereoMatcher(params, backend="scalar")
    for f in pipeline:
        np.testing.assert_array_equal(matcher.compute(f["left_grey"], f["right_grey"]),
                                      f["disparity"])
        mask, _ = matcher.compute_mask(f["thresholds"])
        np.testing.assert_array_equal(mask, f["mask"])


def test_zone_search_matches_only_where_the_zone_can_be():
    """zoneSearch=1 (without the guard below the range): each frame searches
    from below its smallest threshold up to the full range's top, exactly as a
    matcher over that range, with the full range's invalid marker."""
    with horopter.Pipeline("synthetic", frames=3, backend="auto", zoneSearch=1,
                           zoneMarginPx=4, zoneGuardStep=0) as pipeline:  # 640x480, the default rig
        frames = list(pipeline)
    assert len(frames) == 3
    for f in frames:
        lowest = -(-(int(f["thresholds"].min()) - 8) // 16)  # ceil((t - 8) / 16)
        bottom = min(max(lowest - 4, 0), 48)
        count = -(-(64 - bottom) // 16) * 16
        assert f["search_range"] == (64 - count, count)
        assert count < 64, "the default rig's zone needs less than the full range"
        # The run's stereo defaults match the left band (leftBand=16).
        matcher = horopter.StereoMatcher(minDisparity=64 - count, numDisparities=count,
                                         leftBand=16, backend="scalar")
        expected = matcher.compute(f["left_grey"], f["right_grey"])
        expected[expected == 16 * (64 - count - 1)] = -16
        np.testing.assert_array_equal(expected, f["disparity"])
    with pytest.raises(horopter.Error, match="zoneMarginPx"):
        horopter.Pipeline("synthetic", frames=1, zoneSearch=1, zoneMarginPx=999)
    with pytest.raises(TypeError, match="unknown Pipeline option 'zoneSerch'"):
        horopter.Pipeline("synthetic", frames=1, zoneSerch=1)
    with pytest.raises(TypeError, match="zoneSearch must be an int"):
        horopter.Pipeline("synthetic", frames=1, zoneSearch=1.5)


def test_tuning_options_are_pipeline_keywords():
    for table in horopter.tuning_options().values():
        for o in table:
            value = o["default"] if not o["integer"] else int(o["default"])
            horopter.Pipeline("synthetic", frames=1, size=(96, 72), numDisparities=16,
                              **{o["name"]: value}).close()


def test_stopping_early_and_errors():
    pipeline = horopter.Pipeline("synthetic", frames=50, size=(96, 72), numDisparities=16)
    first = next(pipeline)
    assert first["index"] == 0
    pipeline.close()  # stops capture; must not hang with frames still queued
    assert list(pipeline) == []
    with pytest.raises(horopter.Error, match="nosuch"):
        horopter.Pipeline("nosuch:thing", frames=1)
    with pytest.raises(ValueError, match="frames"):
        horopter.Pipeline("synthetic", frames=0)


def test_folder_source_and_its_errors(tmp_path, grey_pair):
    left, right = grey_pair
    for i in range(2):
        horopter.imwrite(str(tmp_path / f"left{i}.png"), left)
        horopter.imwrite(str(tmp_path / f"right{i}.png"), right)
    frames = list(horopter.Pipeline(f"dir:{tmp_path}", numDisparities=64, backend="scalar"))
    assert len(frames) == 2
    expected = horopter.StereoMatcher(numDisparities=64, leftBand=16,  # the run's band
                                      backend="scalar").compute(left, right)
    np.testing.assert_array_equal(frames[1]["disparity"], expected)


def test_synthetic_scene_truth():
    scene = horopter.SyntheticScene(width=160, height=120)
    frame = scene.render(0)
    assert frame["left"].shape == (120, 160, 3)
    truth = frame["truth"]
    assert truth["disparity"].dtype == np.int16 and truth["inside"].dtype == np.uint8
    assert scene.geometry.focal_px == pytest.approx(scene.focal_px)
    with pytest.raises(horopter.Error):
        scene.command_head(0.0, 0.0, 3.0)


def test_detection_tracking_and_movement_stages_fill_their_dicts():
    model = horopter.MovementModel.train(sequences=5)
    # 640x480: the face detector is tuned for it (a 16th of the width as smallest face).
    pipeline = horopter.Pipeline("synthetic", frames=120, detect="region", movement_model=model)
    frames = list(pipeline)
    assert len(frames) == 120
    for f in frames:
        assert f["detections"]["scope"] == "horopter-region"
        assert f["tracking"]["election"] in {"none", "candidate", "godfather"}
        assert sum(f["movement"]["posterior"].values()) == pytest.approx(1.0)
    # The main person walks into the zone and stays: faces are found inside it,
    # and after two seconds inside they are elected godfather.
    assert any(face["inside_zone"] for f in frames for face in f["detections"]["faces"])
    elected = [f for f in frames if f["tracking"]["election"] == "godfather"]
    assert elected and any(f["body"]["godfather"] for f in elected)
    assert any(f["tracking"]["head"]["tracked"] for f in elected)
    with pytest.raises(ValueError, match="detect"):
        horopter.Pipeline("synthetic", frames=1, detect="everywhere")
    with pytest.raises(ValueError, match="movement_model needs detect"):
        horopter.Pipeline("synthetic", frames=1, movement_model=model)
