"""The Python examples run: segment.py (a stereo pair in, the mask and the
segmented image out) and live_mask.py (a source of pairs in, a mask per frame)."""
import os
import subprocess
import sys

import numpy as np

import horopter


def test_segment_example(scene_frame, grey_pair, source_dir, tmp_path):
    script = os.path.join(source_dir, "examples", "python", "segment.py")
    horopter.imwrite(str(tmp_path / "left.png"), scene_frame["left"])
    horopter.imwrite(str(tmp_path / "right.png"), scene_frame["right"])
    out = tmp_path / "out"
    result = subprocess.run([sys.executable, script, str(tmp_path / "left.png"),
                             str(tmp_path / "right.png"), "-o", str(out),
                             "--num-disparities", "64", "--fixation-disparity", "9"],
                            check=True, capture_output=True, text=True, env=os.environ.copy())
    assert "inside the zone" in result.stdout
    mask = horopter.imread(str(out / "mask.png"))
    segmented = horopter.imread(str(out / "segmented.png"))
    assert mask.shape == scene_frame["left"].shape[:2]
    assert segmented.shape == scene_frame["left"].shape
    assert set(np.unique(mask)) <= {0, 255} and 0 < (mask > 0).mean() < 1
    # Outside the mask the segmented image is black, inside it is the left image.
    assert (segmented[mask == 0] == 0).all()
    np.testing.assert_array_equal(segmented[mask > 0], scene_frame["left"][mask > 0])


def test_live_mask_example_on_recorded_frames(source_dir, tmp_path):
    """examples/python/live_mask.py on a recorded folder of pairs (the synthetic
    scene's frames, as a camera rig would have recorded them): one line and one
    mask per frame, each mask the pipeline's own for the same configuration."""
    script = os.path.join(source_dir, "examples", "python", "live_mask.py")
    frames = 4
    recorded = tmp_path / "recorded"
    recorded.mkdir()
    scene = horopter.SyntheticScene(width=320, height=240, seed=11)
    for i in range(frames):
        frame = scene.render(i)
        horopter.imwrite(str(recorded / f"left_{i:03d}.png"), frame["left"])
        horopter.imwrite(str(recorded / f"right_{i:03d}.png"), frame["right"])
    out = tmp_path / "masks"
    source = f"dir:{recorded}"
    result = subprocess.run([sys.executable, script, source, "-o", str(out),
                             "--fixation-disparity", "9", "--num-disparities", "64"],
                            check=True, capture_output=True, text=True, env=os.environ.copy())
    lines = [line for line in result.stdout.splitlines() if line.startswith("frame ")]
    assert [line.split(":")[0] for line in lines] == [f"frame {i}" for i in range(frames)]
    assert f"{frames} frames, " in result.stdout
    expected = horopter.Pipeline(source, fixation_disparity=9, numDisparities=64)
    for frame in expected:
        mask = horopter.imread(str(out / f"mask_{frame['index']:06d}.png"), grey=True)
        np.testing.assert_array_equal(mask, frame["mask"])
        assert 0 < (mask > 0).mean() < 1
        assert f"frame {frame['index']}: {100.0 * (mask > 0).mean():.1f}% inside" in result.stdout


def test_live_mask_example_says_what_is_wrong(source_dir, tmp_path):
    script = os.path.join(source_dir, "examples", "python", "live_mask.py")
    result = subprocess.run([sys.executable, script, f"dir:{tmp_path / 'none'}"],
                            capture_output=True, text=True, env=os.environ.copy())
    assert result.returncode != 0
    assert "live_mask.py: " in result.stderr and "does not exist" in result.stderr
