#!/usr/bin/env python3
"""Compare builds of horopter_bench by their ratio to the peer, run after run.

Runs each binary in turn, ROUNDS times (A B A B ...), each run the median of
--repetitions, and prints per run and binary the ratio of every row of ours to
the OpenCV row of the same size, range, block and thread count in the same
run. The machine's load moves wall times from run to run; a ratio within one
run, and its spread over alternating runs, is what can be compared.

Example:
  scripts/bench_ab.py --rounds 6 \\
    --filter '^(disparity/avx2|opencv_stereobm)/1280x720/d128/w15/t[12](/real_time)?$' \\
    old/horopter_bench build/bin/horopter_bench
"""
import argparse
import collections
import json
import statistics
import subprocess
import sys


def peer_of(name, rows):
    """opencv_stereobm/<size>/<d>/<w>/<tN>[/real_time] for ours' row."""
    parts = name.split("/")  # kind/backend/size/d/w/tN[/...]
    if len(parts) < 6:
        return None
    prefix = "/".join(["opencv_stereobm"] + parts[2:6])
    for candidate in rows:
        if candidate == prefix or candidate.startswith(prefix + "/"):
            return candidate
    return None


def run_once(binary, row_filter, repetitions, min_time):
    command = [binary, f"--benchmark_filter={row_filter}", f"--benchmark_min_time={min_time}",
               f"--benchmark_repetitions={repetitions}",
               "--benchmark_report_aggregates_only=true", "--benchmark_format=json"]
    try:
        done = subprocess.run(command, capture_output=True, text=True)
    except OSError as error:
        sys.exit(f"bench_ab: cannot run {binary}: {error.strerror}")
    if done.returncode != 0:
        sys.exit(f"bench_ab: {binary} exited with {done.returncode}: {done.stderr.strip()}")
    try:
        report = json.loads(done.stdout)
    except json.JSONDecodeError:
        said = (done.stdout + done.stderr).strip().splitlines()
        sys.exit(f"bench_ab: {binary} printed no JSON: {said[0] if said else 'nothing'}")
    # One repetition has no aggregates: its own row is the run's time.
    wanted = "median" if repetitions > 1 else None
    return {row["run_name"]: row["real_time"] for row in report["benchmarks"]
            if row.get("aggregate_name") == wanted}


def main():
    parser = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0],
        epilog="\n\n".join(__doc__.split("\n\n")[1:]),
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("binaries", nargs="+", help="horopter_bench executables to compare")
    parser.add_argument("--filter", required=True,
                        help="Google Benchmark row filter; include the opencv_stereobm rows")
    parser.add_argument("--rounds", type=int, default=3, help="runs of each binary (default 3)")
    parser.add_argument("--repetitions", type=int, default=3,
                        help="repetitions per run, their median taken (default 3)")
    parser.add_argument("--min-time", type=float, default=0.3,
                        help="seconds per repetition (default 0.3)")
    args = parser.parse_args()
    if args.rounds < 1 or args.repetitions < 1 or args.min_time <= 0:
        parser.error("--rounds and --repetitions must be at least 1, --min-time above 0")

    ratios = collections.defaultdict(list)
    for _ in range(args.rounds):
        for binary in args.binaries:
            rows = run_once(binary, args.filter, args.repetitions, args.min_time)
            for name, ours in sorted(rows.items()):
                if name.startswith("opencv"):
                    continue
                peer = peer_of(name, rows)
                if peer is None:
                    continue
                ratio = rows[peer] / ours
                ratios[(name, binary)].append(ratio)
                print(f"{binary}  {name}  {ours:.3f}  peer {rows[peer]:.3f}  ratio {ratio:.3f}",
                      flush=True)
    if not ratios:
        sys.exit("bench_ab: no row of ours with its opencv_stereobm row in the filter")
    print("\nratio to the peer: mean [min, max] over runs")
    for (name, binary), values in sorted(ratios.items()):
        print(f"{name}  {binary}  {statistics.mean(values):.3f} "
              f"[{min(values):.3f}, {max(values):.3f}]  n={len(values)}")


if __name__ == "__main__":
    main()
