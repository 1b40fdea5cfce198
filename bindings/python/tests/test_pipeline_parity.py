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


def cli_digest(cli, tmp_path, backend, in_flight, detect="region"):
    out = subprocess.run(
        [cli, "run", "--frames", str(FRAMES), "--size", f"{WIDTH}x{HEIGHT}", "--seed", str(SEED),
         "--detect", detect, "--backend", backend, "--in-flight", str(in_flight),
         "--no-movement", "--no-video", "--json", "-o", str(tmp_path / "out")],
        check=True, capture_output=True, text=True)
    summary = json.loads(out.stdout)
    assert summary["frames"] == FRAMES
    return summary["frames_digest"]


def python_digest(backend, in_flight, detect="region"):
    with horopter.Pipeline(frames=FRAMES, size=(WIDTH, HEIGHT), seed=SEED,
                           detect=None if detect == "off" else detect, backend=backend,
                           in_flight=in_flight) as run:
        frames = [(frame["index"], frame.get("body", {}).get("godfather", False)) for frame in run]
        assert [index for index, _ in frames] == list(range(FRAMES))
        assert any(godfather for _, godfather in frames) == (detect != "off")
        return run.digest


def c_digest(backend, in_flight, detect="region"):
    tool = os.environ.get("HOROPTER_C_RUN")
    if not tool or not os.path.exists(tool):
        pytest.skip("the C API's run tool is not built here (set HOROPTER_C_RUN)")
    out = subprocess.run([tool, str(FRAMES), str(WIDTH), str(HEIGHT), str(SEED), detect, backend,
                          str(in_flight)], check=True, capture_output=True, text=True)
    return out.stdout.strip()


def test_cli_python_and_c_give_the_same_frames(cli, tmp_path):
    digest = cli_digest(cli, tmp_path, "auto", 3)
    assert len(digest) == 16 and int(digest, 16) != 0
    assert python_digest("auto", 3) == digest
    assert c_digest("auto", 3) == digest


def test_the_digest_sees_the_configuration(cli, tmp_path):
    # The digest is not a constant: the front end alone gives another one.
    assert cli_digest(cli, tmp_path, "auto", 3, detect="off") != cli_digest(cli, tmp_path,
                                                                            "auto", 3)
    assert python_digest("auto", 3, detect="off") == cli_digest(cli, tmp_path, "auto", 3,
                                                                detect="off")


def test_frames_do_not_depend_on_backend_or_frames_in_flight(cli, tmp_path):
    digest = cli_digest(cli, tmp_path, "auto", 3)
    assert cli_digest(cli, tmp_path, "scalar", 1) == digest
    assert c_digest("scalar", 2) == digest
