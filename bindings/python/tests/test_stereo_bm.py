"""StereoMatcher shaped like cv2.StereoBM: constructor, constants, getters and
setters that take effect, matcher.params written through, one set of defaults."""
import os

import numpy as np
import pytest

import horopter

# Every cv::StereoBM parameter, with a valid value other than its default.
OTHER_VALUES = {
    "MinDisparity": -4,
    "NumDisparities": 32,
    "BlockSize": 15,
    "PreFilterSize": 21,
    "PreFilterCap": 15,
    "TextureThreshold": 3,
    "UniquenessRatio": 5,
    "Disp12MaxDiff": 2,
    "SpeckleWindowSize": 50,
    "SpeckleRange": 16,
}


def test_stereo_bm_create_has_opencv_defaults():
    m = horopter.StereoBM_create()
    assert m.getNumDisparities() == 64  # OpenCV: 0 means 64
    assert m.getBlockSize() == 21
    assert m.getMinDisparity() == 0
    assert m.getPreFilterType() == horopter.STEREO_BM_PREFILTER_XSOBEL
    assert m.getPreFilterSize() == 9
    assert m.getPreFilterCap() == 31
    assert m.getTextureThreshold() == 10
    assert m.getUniquenessRatio() == 15
    assert m.getDisp12MaxDiff() == -1
    assert m.getSpeckleWindowSize() == 0
    assert m.getSpeckleRange() == 0
    assert m.median.kernelSize == 0
    m2 = horopter.StereoBM_create(32, 15)
    assert (m2.getNumDisparities(), m2.getBlockSize()) == (32, 15)
    p = horopter.stereo_bm_defaults(16)
    assert (p.numDisparities, p.blockSize, p.disp12MaxDiff) == (16, 21, -1)


def test_constants_and_enum_take_opencv_ints():
    assert horopter.STEREO_BM_PREFILTER_NORMALIZED_RESPONSE == 0
    assert horopter.STEREO_BM_PREFILTER_XSOBEL == 1
    assert int(horopter.PreFilterType.NORMALIZED_RESPONSE) == 0
    assert int(horopter.PreFilterType.XSOBEL) == 1
    p = horopter.StereoParams(preFilterType=0)
    assert p.preFilterType == horopter.PreFilterType.NORMALIZED_RESPONSE
    p.preFilterType = 1
    assert p.preFilterType == horopter.PreFilterType.XSOBEL
    p.preFilterType = "normalized"
    assert p.preFilterType == horopter.PreFilterType.NORMALIZED_RESPONSE
    with pytest.raises(horopter.Error, match="preFilterType"):
        horopter.StereoParams(preFilterType=7)
    with pytest.raises(TypeError, match="preFilterType"):
        horopter.StereoParams(preFilterType=1.0)


def test_positional_num_disparities_and_block_size():
    m = horopter.StereoMatcher(64, 9)
    assert (m.getNumDisparities(), m.getBlockSize()) == (64, 9)
    m = horopter.StereoMatcher(32)
    assert (m.getNumDisparities(), m.getBlockSize()) == (32, horopter.StereoParams().blockSize)
    with pytest.raises(TypeError, match="both"):
        horopter.StereoMatcher(32, numDisparities=48)
    with pytest.raises(TypeError, match="positional"):
        horopter.StereoMatcher(32, 9, 3)
    # The older form still works.
    params = horopter.StereoParams(numDisparities=48)
    m = horopter.StereoMatcher(params, horopter.MedianParams(kernelSize=3), backend="scalar")
    assert m.getNumDisparities() == 48 and m.median.kernelSize == 3
    m = horopter.StereoMatcher(None, None, "scalar", 1)
    assert (m.getNumDisparities(), m.backend, m.threads) == (64, "scalar", 1)


@pytest.mark.parametrize("name", sorted(OTHER_VALUES))
def test_each_setter_takes_effect_and_has_docs(name):
    m = horopter.StereoBM_create(64, 9)
    getter, setter = getattr(m, "get" + name), getattr(m, "set" + name)
    assert getter.__doc__ and setter.__doc__
    setter(OTHER_VALUES[name])
    assert getter() == OTHER_VALUES[name]
    field = name[0].lower() + name[1:]
    assert getattr(m.params, field) == OTHER_VALUES[name]


def test_setters_change_the_next_compute(grey_pair):
    left, right = grey_pair
    m = horopter.StereoBM_create(64, 9)
    before = m.compute(left, right)
    m.setPreFilterType(horopter.STEREO_BM_PREFILTER_NORMALIZED_RESPONSE)
    after = m.compute(left, right)
    expected = horopter.StereoMatcher(
        horopter.stereo_bm_defaults(64, 9), horopter.MedianParams(kernelSize=0),
        preFilterType="normalized").compute(left, right)
    assert not np.array_equal(before, after)
    assert np.array_equal(after, expected)


def test_bad_setter_raises_naming_the_parameter_and_keeps_settings():
    m = horopter.StereoBM_create(64, 9)
    with pytest.raises(horopter.Error, match="numDisparities"):
        m.setNumDisparities(30)  # not a multiple of 16
    assert m.getNumDisparities() == 64
    with pytest.raises(horopter.Error, match="blockSize"):
        m.setBlockSize(8)
    assert m.getBlockSize() == 9
    with pytest.raises(horopter.Error, match="preFilterSize"):
        m.setPreFilterSize(300)
    with pytest.raises(horopter.Error, match="preFilterSize"):
        m.setPreFilterSize(6)
    assert m.getPreFilterSize() == 9
    with pytest.raises(TypeError, match="int"):
        m.setPreFilterCap("31")


def test_params_attribute_writes_through_or_raises(grey_pair):
    left, right = grey_pair
    m = horopter.StereoMatcher(numDisparities=64, backend="scalar", threads=1)
    m.params.numDisparities = 32
    assert m.getNumDisparities() == 32
    assert m.params.numDisparities == 32
    expected = horopter.StereoMatcher(numDisparities=32, backend="scalar").compute(left, right)
    assert np.array_equal(m.compute(left, right), expected)
    with pytest.raises(horopter.Error, match="numDisparities"):
        m.params.numDisparities = 33
    assert m.params.numDisparities == 32
    with pytest.raises(AttributeError):
        m.params.noSuchParameter = 1
    detached = m.params.copy()
    detached.numDisparities = 48
    assert m.getNumDisparities() == 32
    m.params = detached
    assert m.getNumDisparities() == 48
    assert m.params.invalidDisparity == -16


def test_one_set_of_defaults():
    """Python takes the library's defaults (FrontendDefaults): the auto backend
    and one thread per hardware thread, as the C API and the CLI."""
    m = horopter.StereoMatcher()
    assert m.backend == horopter.StereoMatcher(backend="auto").backend
    assert m.threads == min(os.cpu_count() or 1, 256)
    assert horopter.StereoBM_create().threads == m.threads
    assert horopter.StereoMatcher(threads=1).threads == 1


def test_new_names_have_docstrings():
    for obj in (horopter.StereoBM_create, horopter.stereo_bm_defaults,
                horopter.StereoMatcherParams, horopter.StereoMatcherParams.copy,
                horopter.StereoMatcherParams.numDisparities, horopter.StereoParams.preFilterSize,
                horopter.StereoParams.preFilterType, horopter.StereoMatcher.params,
                horopter.StereoMatcher.getPreFilterType, horopter.StereoMatcher.setPreFilterType):
        assert obj.__doc__ and len(obj.__doc__) > 10, obj
    assert "STEREO_BM_PREFILTER_XSOBEL" in horopter.__doc__
