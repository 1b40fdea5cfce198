"""examples/python/segment.py runs: a stereo pair in, the mask and the segmented image out."""
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
