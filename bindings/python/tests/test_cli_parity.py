"""The module equals the C++ `horopter disparity` tool on the same files, bit for bit."""
import os
import subprocess

import numpy as np
import pytest

import horopter


@pytest.mark.parametrize("backend", ["scalar", "auto"])
def test_disparity_mask_and_segmented_equal_the_cli(grey_pair, cli, tmp_path, backend):
    left, right = grey_pair
    horopter.imwrite(str(tmp_path / "left.png"), left)
    horopter.imwrite(str(tmp_path / "right.png"), right)
    out = tmp_path / "out"
    subprocess.run([cli, "disparity", str(tmp_path / "left.png"), str(tmp_path / "right.png"),
                    "-o", str(out), "--backend", backend, "--num-disparities", "64",
                    "--block-size", "11", "--threads", "2", "--fixation-disparity", "9"],
                   check=True, capture_output=True)

    # The same computation through the module: the CLI reads the grey files as
    # colour (three equal channels) and converts back to grey, exactly.
    colour = np.repeat(left[:, :, None], 3, axis=2)
    params = horopter.StereoParams(numDisparities=64, blockSize=11)
    matcher = horopter.StereoMatcher(params, backend=backend)
    disparity = matcher.compute(left, right)
    width = left.shape[1]
    geometry = horopter.RectifiedGeometry(focal_px=width, cx=(width - 1) / 2, baseline=1.0)
    fixation = horopter.fixation_from_disparity(geometry, geometry.cx, 9.0)
    thresholds = horopter.horopter_thresholds(geometry, width, fixation)
    mask, segmented = matcher.compute_mask(thresholds, colour)

    # disparity.png holds the valid positive disparities, 0 elsewhere (16-bit).
    cli_disparity = horopter.imread(str(out / "disparity.png"))
    assert cli_disparity.dtype == np.uint16
    expected = np.where((disparity != params.invalidDisparity) & (disparity > 0), disparity, 0)
    np.testing.assert_array_equal(cli_disparity, expected.astype(np.uint16))
    np.testing.assert_array_equal(horopter.imread(str(out / "mask.png")), mask)
    np.testing.assert_array_equal(horopter.imread(str(out / "segmented.png")), segmented)
    assert 0 < (mask > 0).mean() < 1
