"""One configuration, the same frames: `horopter run`, the module's Pipeline and
the C API's horopter_run all assemble the pipeline with the one builder
(engine/app/pipeline_builder.cpp), so their frames' digests (disparity, mask,
the godfather's tracked parts, frame by frame) are equal. Before the builder,
the module left out the tracker's largest disparity and the head control."""
import json
import os
import subprocess

import pytest

import horopter

# Long enough for the person to walk in and be elected (2 s inside the zone),
# so the tracker's and the head control's outputs are in the digest.
FRAMES, WIDTH, HEIGHT, SEED = 120, 320, 240, 7
# A folder of pairs has no rig: its zone comes from a fixation disparity, far
# enough (4 px) for the person walking in to be inside it and elected.
FIXATION_PX = 4


# Each configuration's digest, once per module: several tests compare the
# same runs (this file was the suite's longest test).
_cli_digests = {}
_c_digests = {}


def cli_digest(cli, tmp_path, backend, in_flight, detect="region", source="synthetic"):
    key = (backend, in_flight, detect, source)
    if key not in _cli_digests:
        _cli_digests[key] = _run_cli(cli, tmp_path, backend, in_flight, detect, source)
    return _cli_digests[key]


def _run_cli(cli, tmp_path, backend, in_flight, detect, source):
    fixation = ["--fixation-disparity", str(FIXATION_PX)] if source.startswith("dir:") else []
    out = subprocess.run(
        [cli, "run", "--source", source, *fixation, "--frames", str(FRAMES), "--size", f"{WIDTH}x{HEIGHT}",
         "--seed", str(SEED), "--detect", detect, "--backend", backend, "--in-flight",
         str(in_flight), "--no-movement", "--no-video", "--json", "-o", str(tmp_path / "out")],
        check=True, capture_output=True, text=True)
    summary = json.loads(out.stdout)
    assert summary["frames"] == FRAMES
    return summary["frames_digest"]


def python_digest(backend, in_flight, detect="region", source="synthetic", elected=None):
    fixation = FIXATION_PX if source.startswith("dir:") else None
    with horopter.Pipeline(source, frames=FRAMES, size=(WIDTH, HEIGHT), seed=SEED,
                           detect=None if detect == "off" else detect, backend=backend,
                           in_flight=in_flight, fixation_disparity=fixation) as run:
        frames = [(frame["index"], frame.get("body", {}).get("godfather", False)) for frame in run]
        assert [index for index, _ in frames] == list(range(FRAMES))
        if elected is not None:
            assert any(godfather for _, godfather in frames) == elected
        return run.digest


def c_digest(source, backend, in_flight, detect="region"):
    tool = os.environ.get("HOROPTER_C_RUN")
    if not tool or not os.path.exists(tool):
        pytest.skip("the C API's run tool is not built here (set HOROPTER_C_RUN)")
    key = (source, backend, in_flight, detect)
    if key not in _c_digests:
        _c_digests[key] = _run_c(tool, source, backend, in_flight, detect)
    return _c_digests[key]


def _run_c(tool, source, backend, in_flight, detect):
    out = subprocess.run([tool, source, str(FRAMES), detect, backend, str(in_flight),
                          str(FIXATION_PX)],
                         check=True, capture_output=True, text=True)
    return out.stdout.strip()


@pytest.fixture(scope="module")
def recorded(tmp_path_factory):
    """The synthetic scene's frames written as a folder of pairs: a source
    libhoropter itself reads (the scene is the simulator's)."""
    folder = tmp_path_factory.mktemp("pairs")
    scene = horopter.SyntheticScene(width=WIDTH, height=HEIGHT, seed=SEED)
    for i in range(FRAMES):
        frame = scene.render(i)
        horopter.imwrite(str(folder / f"left_{i:03d}.png"), frame["left"])
        horopter.imwrite(str(folder / f"right_{i:03d}.png"), frame["right"])
    return f"dir:{folder}"


def test_cli_and_python_give_the_same_frames_in_closed_loop(cli, tmp_path):
    digest = cli_digest(cli, tmp_path, "auto", 3)
    assert len(digest) == 16 and int(digest, 16) != 0
    assert python_digest("auto", 3, elected=True) == digest


def test_cli_python_and_c_give_the_same_frames_from_a_folder(cli, tmp_path, recorded):
    digest = cli_digest(cli, tmp_path, "auto", 3, source=recorded)
    assert python_digest("auto", 3, source=recorded, elected=True) == digest
    assert c_digest(recorded, "auto", 3) == digest


def test_the_digest_sees_the_configuration(cli, tmp_path):
    # The digest is not a constant: the front end alone gives another one.
    off = cli_digest(cli, tmp_path, "auto", 3, detect="off")
    assert off != cli_digest(cli, tmp_path, "auto", 3)
    assert python_digest("auto", 3, detect="off", elected=False) == off


def test_frames_do_not_depend_on_backend_or_frames_in_flight(cli, tmp_path, recorded):
    digest = cli_digest(cli, tmp_path, "auto", 3)
    assert cli_digest(cli, tmp_path, "scalar", 1) == digest
    from_folder = c_digest(recorded, "auto", 3)
    assert c_digest(recorded, "scalar", 2) == from_folder
