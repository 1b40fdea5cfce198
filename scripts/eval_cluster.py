#!/usr/bin/env python3
"""Table III (horopter eval-interaction) with its trials spread over a Dask cluster.

Each trial is independent and seeded, so the cluster's result equals the
serial run's exactly: every worker runs horopter.interaction_trial for one
(scope, seed), and the client sums the outcomes in seed order with
horopter.interaction_summary, the code `horopter eval-interaction` sums its
own with. Only the "timing" entries (frames/s, stage times) differ.

  scripts/eval_cluster.py --trials 100 --seed 500000 --json          # a local cluster
  scripts/eval_cluster.py --scheduler tcp://10.0.0.5:8786 --trials 1000 --seed 500100

A real cluster: start `dask scheduler` on one machine and `dask worker
tcp://SCHEDULER:8786 --nthreads 1 --nworkers N` on each machine that has the
horopter Python module (`pip install ./bindings/python`, or PYTHONPATH set to a
build's bindings/python); then pass --scheduler. docs/evaluation.md says which
seeds to use.
"""
import argparse
import json
import os
import sys
import time


def _run_trial(seed, scope, frames, width, height, grace_frames, model_path):
    import horopter  # imported on the worker

    return horopter.interaction_trial(seed, scope=scope, frames=frames, width=width,
                                      height=height, grace_frames=grace_frames,
                                      model_path=model_path)


def _positive(text):
    value = int(text)
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be >= 1, got {text}")
    return value


def _size(text):
    try:
        width, height = (int(v) for v in text.split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"takes WxH, got '{text}'") from None
    return width, height


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter,
                                epilog="\n\n".join(__doc__.split("\n\n")[1:]))
    p.add_argument("--trials", type=_positive, default=20, help="trials (default 20)")
    p.add_argument("--seed", type=int, default=1, help="first trial's seed (default 1)")
    p.add_argument("--frames", type=_positive, default=300, help="frames per trial (default 300)")
    p.add_argument("--size", type=_size, default=(640, 480), help="WxH (default 640x480)")
    p.add_argument("--scope", choices=["region", "full", "both"], default="both",
                   help="detection scope (default both)")
    p.add_argument("--grace-frames", type=int, default=15,
                   help="frames after a movement where its decision counts (default 15)")
    p.add_argument("--model", default="", help="movement model file (default: trained in-process)")
    p.add_argument("--scheduler", default=None,
                   help="address of a running Dask scheduler (default: a local cluster)")
    p.add_argument("--workers", type=_positive, default=os.cpu_count() or 1,
                   help="local cluster: worker processes, one thread each (default: the cores)")
    p.add_argument("--json", action="store_true",
                   help="print the JSON of `horopter eval-interaction --json`")
    return p.parse_args(argv)


def evaluate(args, client, progress=sys.stderr):
    """The JSON object of `horopter eval-interaction --json` for these arguments."""
    import horopter
    from dask.distributed import as_completed

    seed_use = horopter.seed_use(args.seed, args.trials)
    width, height = args.size
    scopes = [s for s in ("full", "region") if args.scope in (s, "both")]
    futures = {}
    for scope in scopes:
        for seed in range(args.seed, args.seed + args.trials):
            # pure=False: a trial's key must not collide with another run's cached result.
            futures[(scope, seed)] = client.submit(_run_trial, seed, scope, args.frames, width,
                                                   height, args.grace_frames, args.model,
                                                   pure=False)
    where = {f.key: k for k, f in futures.items()}
    start, done = time.monotonic(), 0
    for future in as_completed(list(futures.values())):
        future.result()  # raises the worker's error here
        done += 1
        if progress:
            scope, seed = where[future.key]
            print(f"\r{done}/{len(futures)} trials done ({scope} seed {seed}), "
                  f"{time.monotonic() - start:.0f} s", end="", file=progress, flush=True)
    if progress:
        print(file=progress)
    out = {"seed_use": seed_use, "trials": args.trials, "seed_first": args.seed,
           "seed_last": args.seed + args.trials - 1, "frames": args.frames,
           "width": width, "height": height}
    for scope, key in (("full", "full"), ("region", "roi")):
        if scope in scopes:
            trials = [futures[(scope, s)].result()
                      for s in range(args.seed, args.seed + args.trials)]
            out[key] = json.loads(horopter.interaction_summary(trials, scope))
    return out


def _print_table(out):
    print(f"{out['trials']} trials (seeds {out['seed_first']}-{out['seed_last']}, "
          f"{out['seed_use']}), {out['frames']} frames each at {out['width']}x{out['height']}")
    for key, name in (("full", "full-image"), ("roi", "horopter-region")):
        if key not in out:
            continue
        s = out[key]

        def ci(k):
            return f"{s[k]:.1f} [{s[k + '_ci95'][0]:.1f},{s[k + '_ci95'][1]:.1f}]"

        print(f"{name:16} movements {s['movements']}  loss% {ci('tracker_loss')}  "
              f"class% {ci('classification_rate')}  real% {ci('real_classification_rate')}  "
              f"lost-all {s['trials_lost_all']}/{s['trials']}")


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    try:
        from dask.distributed import Client, LocalCluster
    except ImportError:
        sys.exit("eval_cluster: needs dask.distributed (Debian: python3-distributed; "
                 "PyPI: distributed)")
    import horopter

    try:
        horopter.seed_use(args.seed, args.trials)  # fails before any cluster starts
    except horopter.Error as e:
        sys.exit(f"eval_cluster: {e}")
    if args.scheduler:
        with Client(args.scheduler) as client:
            out = evaluate(args, client)
    else:
        with LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True,
                          dashboard_address=None) as cluster, Client(cluster) as client:
            out = evaluate(args, client)
    if args.json:
        print(json.dumps(out))
    else:
        _print_table(out)


if __name__ == "__main__":
    main()
