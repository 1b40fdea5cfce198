"""The movement classifier from Python: train, classify a labelled track, save and reload."""
import pytest

import horopter


@pytest.fixture(scope="module")
def model():
    return horopter.MovementModel.train(sequences=20)


@pytest.fixture(scope="module")
def sequence():
    return horopter.synthetic_sequence(seed=7)  # an evaluation seed, unseen in training


def test_classified_track_beats_chance(model, sequence):
    states = horopter.classify_track(sequence["samples"], model)
    assert len(states) == len(sequence["samples"]) == len(sequence["labels"])
    for s in states:
        assert set(s["posterior"]) == set(horopter.MOVEMENTS)
        assert sum(s["posterior"].values()) == pytest.approx(1.0)
        assert s["likeliest"] == max(s["posterior"], key=s["posterior"].get)
    scored = [(s["likeliest"], label) for s, label in zip(states, sequence["labels"])
              if s["features_valid"]]
    assert len(scored) > len(states) // 2
    accuracy = sum(a == b for a, b in scored) / len(scored)
    assert accuracy > 2 / len(horopter.MOVEMENTS), accuracy  # twice chance
    decisions = [s["decision"] for s in states if s["decision"]]
    assert decisions and set(decisions) <= set(horopter.MOVEMENTS)


def test_model_and_track_files_round_trip(model, sequence, tmp_path):
    path = tmp_path / "model.txt"
    model.save(str(path))
    again = horopter.MovementModel.load(str(path))
    assert again.serialize() == model.serialize()
    assert again.params == model.params
    samples = sequence["samples"][:90]
    track = tmp_path / "track.csv"
    horopter.write_body_track(str(track), samples)
    read = horopter.read_body_track(str(track))
    assert [s["frame"] for s in read] == [s["frame"] for s in samples]
    first = horopter.classify_track(samples, model)
    second = horopter.classify_track(read, again)
    assert [s["likeliest"] for s in first] == [s["likeliest"] for s in second]


def test_bad_model_file(tmp_path):
    bad = tmp_path / "bad.txt"
    bad.write_text("not a model\n")
    with pytest.raises(horopter.Error, match="bad.txt"):
        horopter.MovementModel.load(str(bad))
    with pytest.raises(KeyError):
        horopter.classify_track([{"frame": 0}], horopter.MovementModel.train(sequences=1))
