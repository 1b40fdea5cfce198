"""Table III spread over a Dask cluster equals the serial run (issue 20).

Trials are independent and seeded, so scripts/eval_cluster.py on a local
cluster must give the same figures, intervals and per-trial outcomes as
`horopter eval-interaction --json`; only the "timing" entries may differ.
"""
import json
import os
import subprocess
import sys

import pytest

import horopter

SCRIPT = os.path.join(os.path.dirname(__file__), "..", "..", "..", "scripts", "eval_cluster.py")
SMALL = ["--trials", "2", "--seed", "21", "--frames", "150", "--size", "320x240"]


def without_timing(value):
    if isinstance(value, dict):
        return {k: without_timing(v) for k, v in value.items() if k != "timing"}
    if isinstance(value, list):
        return [without_timing(v) for v in value]
    return value


@pytest.fixture(scope="module")
def serial(cli):
    out = subprocess.run([cli, "eval-interaction", *SMALL, "--json"], check=True,
                         capture_output=True, text=True).stdout
    return json.loads(out)


def test_serial_json_has_per_trial_outcomes_and_intervals(serial):
    assert serial["seed_use"] == "tuning"
    for key in ("full", "roi"):
        scope = serial[key]
        assert [t["seed"] for t in scope["per_trial"]] == [21, 22]
        assert scope["movements"] == sum(t["movements"] for t in scope["per_trial"])
        assert scope["lost"] == sum(t["lost"] for t in scope["per_trial"])
        low, high = scope["tracker_loss_ci95"]
        assert low <= scope["tracker_loss"] <= high
        assert scope["trials_lost_all"] == sum(t["lost_all"] for t in scope["per_trial"])
        assert len(scope["worst_trials"]) == 2


def test_one_trial_from_python_equals_the_cli(serial):
    trial = json.loads(horopter.interaction_trial(22, scope="region", frames=150, width=320,
                                                  height=240))
    assert without_timing(trial) == without_timing(serial["roi"]["per_trial"][1])


def test_local_cluster_equals_the_serial_run(serial):
    pytest.importorskip("dask.distributed", reason="needs python3-distributed (scripts/setup.sh)")
    run = subprocess.run([sys.executable, SCRIPT, *SMALL, "--workers", "2", "--json"],
                         capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr
    cluster = json.loads(run.stdout)
    assert without_timing(cluster) == without_timing(serial)


def test_summary_refuses_broken_or_mixed_trials(serial):
    trial = json.dumps(serial["roi"]["per_trial"][0])
    with pytest.raises(horopter.Error, match="not valid JSON"):
        horopter.interaction_summary([trial[:-3]], "region")
    with pytest.raises(horopter.Error, match="another scope"):
        horopter.interaction_summary([trial], "full")
    broken = dict(serial["roi"]["per_trial"][0])
    del broken["lost"]
    with pytest.raises(horopter.Error, match='missing "lost"'):
        horopter.interaction_summary([json.dumps(broken)], "region")


def test_seed_ranges_are_enforced():
    assert horopter.seed_use(0, 100) == "tuning"
    assert horopter.seed_use(500000, 100) == "evaluation"
    with pytest.raises(horopter.Error, match="tuning range"):
        horopter.seed_use(499990, 20)
    with pytest.raises(horopter.Error, match="trained and tuned the movement model"):
        horopter.seed_use(1000000, 1)


def test_ledger_blocks_are_disjoint_evaluation_seeds():
    """docs/evaluation.md's ledger: every block lies in the evaluation range, none overlaps."""
    import re

    path = os.path.join(os.path.dirname(__file__), "..", "..", "..", "docs", "evaluation.md")
    ledger = open(path, encoding="utf-8").read().split("## Ledger of evaluation blocks")[1]
    blocks = []
    for row in re.findall(r"^\| ([\d ]+) - ([\d ]+) \|", ledger, flags=re.M):
        first, last = (int(v.replace(" ", "")) for v in row)
        assert first <= last
        assert horopter.seed_use(first, last - first + 1) == "evaluation"
        blocks.append((first, last))
    assert blocks, "the ledger lists no block"
    blocks.sort()
    for (_, last), (first, _) in zip(blocks, blocks[1:]):
        assert last < first, f"ledger blocks overlap at {first}"
