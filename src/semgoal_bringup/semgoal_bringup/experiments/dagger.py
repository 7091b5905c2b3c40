"""`./semgoal train dagger`: fine-tune an exported actor by DAgger (:mod:`semgoal_policy.dagger`).

Each iteration the actor drives sub-goal episodes and whole tasks through the planner's executive (the in-process
episodes of :mod:`~semgoal_bringup.experiments.episodes`, as evaluation runs them). The scripted expert labels every
state, and the actor is fitted to all the labels so far. The run's folder keeps a progress row per iteration
(``progress.csv``), each iteration's export (``iterations/K``, git-ignored as snapshots are) and the last one in
``export/``. The aggregate is saved after each iteration (``aggregate.npz``, never committed), so ``--resume`` carries
on from the last finished iteration. The seed rule: runs/README.md.
"""

from __future__ import annotations

import argparse
import csv
import json
import shlex
import sys
import time
from dataclasses import asdict
from pathlib import Path

import numpy as np
import torch
from tqdm import tqdm

from semgoal_bringup.experiments.episodes import HierarchicalAgent
from semgoal_bringup.experiments.training import make_env
from semgoal_core.arguments import count, natural
from semgoal_core.provenance import provenance
from semgoal_core.tasks import ALL_TASKS
from semgoal_core.vocabulary import SCENES
from semgoal_policy import actor as actor_io
from semgoal_policy.dagger import ITERATION_SEED_STRIDE, Aggregate, DaggerConfig, Recorder, collect_subgoals, fit, label
from semgoal_policy.trainer import RUNS_DIR

TRAINED_BLOCKS = 6
"""Tasks with more blocks than this (Tower-7, Clean-8) are left out of the task episodes: the issue's trained range."""
PROGRESS_FIELDS = ("iteration", "states", "subgoal_success", "task_success", "loss", "wall_s")


def dagger_tasks(scene: str) -> list[str]:
    """The scene's tasks with at most :data:`TRAINED_BLOCKS` blocks."""
    return [name for name, task in ALL_TASKS.items() if task.scene == scene and len(task.blocks) <= TRAINED_BLOCKS]


def run(scene: str, model_dir: Path, run_dir: Path, config: DaggerConfig, envs: int, resume: bool,
        command: str) -> list[dict]:
    """The iterations not yet done in ``run_dir``; returns every progress row."""
    actor, meta = actor_io.load(model_dir, scene)
    derived = actor_io.derived_features(meta)
    progress, aggregate_path = run_dir / "progress.csv", run_dir / "aggregate.npz"
    rows = _read_rows(progress) if resume else []
    if rows:
        actor, _ = actor_io.load(run_dir / "iterations" / str(rows[-1]["iteration"]), scene)
    elif progress.exists():
        raise FileExistsError(f"{run_dir} holds a run; --resume carries it on, or choose another --run-dir")
    data = Aggregate()
    if rows:
        saved = np.load(aggregate_path)
        data.add(saved["obs"], saved["goal"], saved["label"])
    run_dir.mkdir(parents=True, exist_ok=True)
    settings = {"scene": scene, "base": meta.get("command", str(model_dir)), **asdict(config), "command": command}
    (run_dir / "config.json").write_text(json.dumps(settings, indent=2) + "\n")
    torch.manual_seed(config.seed)
    rng = np.random.default_rng([config.seed, len(rows)])
    subgoal_envs = [make_env("hierarchical", scene, derived) for _ in range(envs)]
    agent = HierarchicalAgent(scene, model_dir)
    recorder = Recorder(actor)
    agent.controller.actor = recorder  # the executive's episodes ask the actor being fitted
    tasks, start = dagger_tasks(scene), time.monotonic() - (float(rows[-1]["wall_s"]) if rows else 0.0)
    for iteration in range(len(rows) + 1, config.iterations + 1):
        offset = ITERATION_SEED_STRIDE * (iteration - 1)
        states, subgoal_success = collect_subgoals(subgoal_envs, actor, config.subgoal_episodes,
                                                   config.subgoal_seed + offset)
        data.add(*states.arrays())
        recorder.obs.clear()
        recorder.goal.clear()
        wins = 0
        episodes = [(task, config.task_seed + offset + j) for task in tasks for j in range(config.task_episodes)]
        for task, seed in tqdm(episodes, desc=f"dagger {iteration}: tasks", leave=False):
            wins += agent.run(task, seed).success
        if recorder.obs:
            obs, goal = np.stack(recorder.obs), np.stack(recorder.goal)
            data.add(obs, goal, label(scene, obs, goal))
        loss = fit(actor, data, config, rng)
        actor_io.export(actor, run_dir / "iterations" / str(iteration), scene,
                        {"agent": "hierarchical", "dagger_iteration": iteration}, derived=derived)
        np.savez(aggregate_path, **dict(zip(("obs", "goal", "label"), data.arrays(), strict=True)))
        row = {"iteration": iteration, "states": len(data), "subgoal_success": round(subgoal_success, 4),
               "task_success": round(wins / max(len(episodes), 1), 4), "loss": round(loss, 5),
               "wall_s": round(time.monotonic() - start, 1)}
        _append_row(progress, row)
        rows.append(row)
        print(json.dumps(row), flush=True)
    last = rows[-1] if rows else {"states": 0, "wall_s": 0.0}  # every labelled state is an env step the actor drove
    info = {"agent": "hierarchical", "seed": config.seed, "env_steps": last["states"], "wall_s": last["wall_s"],
            "kinds": meta.get("kinds"), "command": command, "provenance": provenance(command, config.seed),
            "base": {key: meta[key] for key in ("command", "seed", "env_steps", "final_eval", "config") if key in meta},
            "dagger": {**asdict(config), "progress": rows}}
    actor_io.export(actor, run_dir / "export", scene, info, derived=derived)
    return rows


def _read_rows(path: Path) -> list[dict]:
    if not path.exists():
        return []
    with path.open() as f:
        return [{key: (int if key in ("iteration", "states") else float)(value) for key, value in row.items()}
                for row in csv.DictReader(f)]


def _append_row(path: Path, row: dict) -> None:
    new = not path.exists()
    with path.open("a", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=PROGRESS_FIELDS)
        if new:
            writer.writeheader()
        writer.writerow(row)


def main(argv: list[str]) -> int:
    """`./semgoal train dagger --scene tabletop --seed 1 [--resume]`: DAgger on the shipped actor (or --model-dir)."""
    defaults = DaggerConfig()
    parser = argparse.ArgumentParser(prog="semgoal train dagger", description=main.__doc__)
    parser.add_argument("--scene", default="tabletop", choices=list(SCENES))
    parser.add_argument("--model-dir", type=Path, help="the actor to start from (default: the shipped one)")
    parser.add_argument("--seed", type=natural, default=defaults.seed)
    parser.add_argument("--iterations", type=count, default=defaults.iterations)
    parser.add_argument("--subgoal-episodes", type=count, default=defaults.subgoal_episodes)
    parser.add_argument("--task-episodes", type=natural, default=defaults.task_episodes, help="per task and iteration")
    parser.add_argument("--epochs", type=count, default=defaults.epochs)
    parser.add_argument("--lr", type=float, default=defaults.lr, help="Adam's rate for the fit")
    parser.add_argument("--envs", type=count, default=8, help="sub-goal envs stepped side by side")
    parser.add_argument("--run-dir", type=Path, help="default runs/SCENE-dagger/seedS")
    parser.add_argument("--resume", action="store_true", help="carry on from the last finished iteration")
    args = parser.parse_args(argv)
    if not args.lr > 0:
        parser.error(f"--lr must be above 0, got {args.lr}")
    torch.set_num_threads(1)
    config = DaggerConfig(iterations=args.iterations, subgoal_episodes=args.subgoal_episodes,
                          task_episodes=args.task_episodes, epochs=args.epochs, lr=args.lr, seed=args.seed)
    model_dir = args.model_dir or actor_io.models_dir() / args.scene
    run_dir = args.run_dir or RUNS_DIR / f"{args.scene}-dagger" / f"seed{args.seed}"
    try:
        run(args.scene, model_dir, run_dir, config, args.envs, args.resume, shlex.join(["./semgoal", "train", "dagger",
                                                                                        *argv]))
    except (FileExistsError, actor_io.LayoutMismatchError, ValueError) as error:
        print(f"semgoal train dagger: {error}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
