"""Shared fixtures: the module under test, a synthetic stereo pair, the CLI.

ctest runs this suite with PYTHONPATH set to the build's module and
HOROPTER_CLI to the build's `horopter` tool; after `pip install
./bindings/python` it runs against the installed module (the CLI tests then
look for `horopter` on PATH and skip, saying so, without it).
"""
import os
import shutil

import numpy as np
import pytest

import horopter


@pytest.fixture(scope="session")
def scene_frame():
    """One frame of the built-in synthetic scene at 320x240 (BGR, rectified)."""
    scene = horopter.SyntheticScene(width=320, height=240, seed=3)
    frame = scene.render(5)
    frame["geometry"] = scene.geometry
    return frame


@pytest.fixture(scope="session")
def grey_pair(scene_frame):
    """A grey rectified pair (uint8, C-contiguous): the synthetic views' green channel."""
    left = np.ascontiguousarray(scene_frame["left"][:, :, 1])
    right = np.ascontiguousarray(scene_frame["right"][:, :, 1])
    return left, right


@pytest.fixture(scope="session")
def cli():
    path = os.environ.get("HOROPTER_CLI") or shutil.which("horopter")
    if not path or not os.path.exists(path):
        pytest.skip("the horopter tool is not built here (set HOROPTER_CLI)")
    return path


@pytest.fixture(scope="session")
def source_dir():
    here = os.path.dirname(os.path.abspath(__file__))
    return os.environ.get("HOROPTER_SOURCE_DIR") or os.path.normpath(os.path.join(here, "../../.."))
