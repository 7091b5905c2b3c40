"""`./semgoal sweep --recipe R --seeds 81-90 [--executor local|dask|dask:ADDRESS] [--workers N] [train settings]`:
train one run per seed, each a job on the executor (:mod:`semgoal_bringup.experiments.executors`).

A job runs `./semgoal train --recipe R --seed S --resume ...` as a process of its own and, when that process dies
(killed, out of memory), runs it again; when the job's worker dies instead (a Dask worker killed or its machine
lost), the training process dies with it and the scheduler runs the job again on another worker. Either way
``--resume`` continues from the run's last checkpoint, so a seed is resumed, never restarted. The seed rule is
written before the runs (runs/README.md)."""

from __future__ import annotations

import argparse
import ctypes
import json
import os
import signal
import subprocess
import sys
from pathlib import Path

from semgoal_bringup.experiments.executors import check_executor, run_jobs
from semgoal_core.arguments import count
from semgoal_policy.recipes import RecipeError, load_recipe

ATTEMPTS = 3
"""Times a seed's training process is started before the sweep reports it failed."""


def parse_seeds(text: str) -> list[int]:
    """``81-90`` (both ends), ``81,85,90`` or a mix; ValueError for anything else."""
    seeds: list[int] = []
    for part in filter(None, (p.strip() for p in text.split(","))):
        low, _, high = part.partition("-")
        if not low.isdigit() or (high and not high.isdigit()) or (high and int(high) < int(low)):
            raise ValueError(f"seeds {text!r}: give e.g. 81-90 or 81,85,90")
        seeds += range(int(low), int(high or low) + 1)
    if not seeds or len(set(seeds)) != len(seeds):
        raise ValueError(f"seeds {text!r}: give each seed once, e.g. 81-90")
    return seeds


PR_SET_PDEATHSIG = 1


def _die_with_parent() -> None:
    """In the training process before it starts: SIGKILL it when the job's process dies (Linux's
    PR_SET_PDEATHSIG), so a job run again never trains beside an orphan of its earlier run."""
    ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGKILL)


def train_seed(recipe: str, seed: int, settings: list[str], runs_dir: str | None) -> dict:
    """One seed's run to its end, resumed from its checkpoint after a death: the train command's JSON line,
    with the attempts it took."""
    command = [str(Path(os.environ["SEMGOAL_ROOT"]) / "semgoal"), "train", "--recipe", recipe, "--seed", str(seed),
               "--resume", *settings]
    if runs_dir:
        run_dir = Path(runs_dir) / f"seed{seed}"
        command += ["--run-dir", str(run_dir), "--export-dir", str(run_dir / "export")]
    for attempt in range(1, ATTEMPTS + 1):
        done = subprocess.run(command, stdout=subprocess.PIPE, text=True, preexec_fn=_die_with_parent)
        if done.returncode == 0:
            return {"seed": seed, "attempts": attempt, **json.loads(done.stdout.strip().splitlines()[-1])}
        print(f"[sweep] seed {seed}: training exited with {done.returncode} (attempt {attempt} of {ATTEMPTS}); "
              "resuming from its checkpoint", file=sys.stderr, flush=True)
    return {"seed": seed, "attempts": ATTEMPTS, "failed": f"training exited with {done.returncode} {ATTEMPTS} times"}


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="semgoal sweep", description=__doc__.split("\n\n")[0],
                                     epilog="Other arguments go to every `./semgoal train` (e.g. --steps 300000).")
    parser.add_argument("--recipe", required=True, help="a shipped recipe (./semgoal train --help lists them)")
    parser.add_argument("--seeds", required=True, type=parse_seeds, help="e.g. 81-90 or 81,85,90")
    parser.add_argument("--executor", default="local", type=check_executor, help="local, dask or dask:ADDRESS")
    parser.add_argument("--workers", type=count, default=2, help="seeds trained at once (local and a Dask LocalCluster)")
    parser.add_argument("--runs-dir", help="the runs' folders: DIR/seedS (default: each recipe run's own under runs/)")
    args, settings = parser.parse_known_args(argv)
    try:
        load_recipe(args.recipe)  # refused here, not once per seed and attempt
    except RecipeError as error:
        parser.error(str(error))
    jobs = [(args.recipe, seed, settings, args.runs_dir) for seed in args.seeds]
    results = run_jobs(train_seed, jobs, args.executor, args.workers, what="seed")
    for result in results:
        print(json.dumps(result))
    return 1 if any("failed" in result for result in results) else 0
