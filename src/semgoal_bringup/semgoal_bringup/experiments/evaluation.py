"""`./semgoal eval`: task completion of the agents on the paper's eight tasks: Table 1, side by side.

    ./semgoal eval --tasks all --episodes 50 --seeds 3 --agents hierarchical,flat-semantic,flat-continuous \\
        --via-ros --json --out results/

Every agent meets the same starts (episode ``i`` of a task uses the task sampler's seed ``--seed + i``),
the same step budget and the same success test, the executive's: the task's goal literals hold with the
world at rest over ``SETTLE_STEPS`` control steps (:mod:`semgoal_core.settling`). In-process rows also
report the first-step rule (the literals held at some step) on the same episodes, and the median
control steps to success at rest. ``--seeds N`` averages
up to N training seeds of each agent where exported actors exist (the shipped one, plus
``models/seeds/<name>/seedK``); the table says how many each row has. ``--via-ros`` also runs the
hierarchical agent through the real node graph in lockstep (:mod:`semgoal_bringup.experiments.graph_eval`).
Writes ``table1.md``, ``table1.csv`` and ``table1.png`` under ``--out``; the last line printed is the
JSON ``{task: {agent: rate, "settled_steps": {agent: median steps}, "first_step_rule": {agent: rate},
"linger_holds": {agent: rate}, "fell_off": {agent: rate}}}`` (the last three where observed).
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import os
import shlex
import statistics
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from semgoal_bringup.experiments.executors import check_executor, run_jobs
from semgoal_bringup.graph import TRUTH, Sight, add_sight_arguments, sight_of
from semgoal_core.arguments import count, names, natural
from semgoal_core.provenance import describe, provenance
from semgoal_core.settling import REST_SPEED, SETTLE_STEPS
from semgoal_core.tasks import TABLETOP_TASKS, TASK_STEP_BUDGET, TASKS, get_task
from semgoal_policy.expert_actor import EXPERT

if TYPE_CHECKING:
    from semgoal_bringup.experiments.episodes import Outcome

PAPER_TABLE1 = {
    "flat-semantic": {"MC-2": 10, "MA-2": 80, "Swap-2": 0, "MC-3": 5, "MA-3": 10, "DC-2": 30, "DC-3": 0, "DC-4": 0},
    "flat-continuous": {"MC-2": 5, "MA-2": 10, "Swap-2": 0, "MC-3": 0, "MA-3": 0, "DC-2": 0, "DC-3": 0, "DC-4": 0},
    "hierarchical": {"MC-2": 95, "MA-2": 100, "Swap-2": 92, "MC-3": 95, "MA-3": 96, "DC-2": 94, "DC-3": 91, "DC-4": 90},
}
"""Task completion (%) in the paper's Table 1: 2M training steps, 50 episodes, mean of three seeds."""
PAPER_NAMES = {"flat-semantic": "Flat Semantic", "flat-continuous": "Flat Continuous",
               "hierarchical": "Hierarchical Semantic"}
AGENT_NAMES = ("hierarchical", "flat-semantic", "flat-continuous")
DEFAULT_SEED = 3_000_000
"""First task seed: above the sub-goal evaluation seeds (1e6, 2e6); training never draws task seeds."""
VIA_ROS = "hierarchical (via ROS)"


@dataclass
class Tally:
    """One training seed's episodes of one task."""

    wins: int = 0
    episodes: int = 0
    steps: int = 0
    first_step_wins: int | None = 0
    """Episodes whose goal literals held at some step, at rest or not (None: not observed, via ROS)."""
    settled_steps: list[int] = field(default_factory=list)
    """Control steps to success at rest, one per successful episode."""
    lingered: int = 0
    """Successes checked again after ``--linger`` control steps of the idle arm..."""
    linger_holds: int = 0
    """...and of those, the ones whose goal still held at rest."""
    fell_off: int | None = 0
    """Episodes that ended with a block off the table (None: not observed, via ROS)."""
    ends: dict[int, tuple[bool, int]] = field(default_factory=dict)
    """Per task seed: how its episode ended (success at rest, control steps), to compare the graph's episodes
    with the same starts in process."""
    why: dict[int, str] = field(default_factory=dict)
    """Per task seed missed: why, in words (:attr:`Outcome.why`; ``--misses`` prints them)."""

    def add(self, other: Tally) -> None:
        """Count ``other``'s episodes too (the same seed and task, other episodes: another job's chunk)."""
        self.wins, self.episodes, self.steps = self.wins + other.wins, self.episodes + other.episodes, self.steps + other.steps
        self.lingered, self.linger_holds = self.lingered + other.lingered, self.linger_holds + other.linger_holds
        self.fell_off = None if None in (self.fell_off, other.fell_off) else self.fell_off + other.fell_off
        self.first_step_wins = (None if self.first_step_wins is None or other.first_step_wins is None
                                else self.first_step_wins + other.first_step_wins)
        self.settled_steps += other.settled_steps
        self.ends.update(other.ends)
        self.why.update(other.why)


@dataclass
class Row:
    """One agent's results, kept per training seed; the pooled figures of a task sum its seeds' tallies."""

    agent: str
    per_seed: dict[str, dict[str, Tally]] = field(default_factory=dict)
    """Per training seed (``shipped``, ``seed21``, ...): per task, the tally of its episodes."""
    seed_steps: dict[str, set[int]] = field(default_factory=dict)
    """Per training seed: the training env steps of its actors (one per scene)."""
    wall_s: float = 0.0

    @property
    def env_steps(self) -> set[int]:
        """Training env steps of the actors evaluated."""
        return set().union(*self.seed_steps.values())

    def add(self, seed_label: str, outcome: Outcome, first_step_observed: bool = True) -> None:
        """Count one episode; ``first_step_observed``: whether ``outcome.first_held`` was watched (not via ROS)."""
        tally = self.per_seed.setdefault(seed_label, {}).setdefault(outcome.task, Tally())
        tally.wins += int(outcome.success)
        tally.episodes += 1
        tally.steps += outcome.steps
        tally.ends[outcome.seed] = (outcome.success, outcome.steps)
        if outcome.success:
            tally.settled_steps.append(outcome.steps)
        else:
            tally.why[outcome.seed] = outcome.why
        if not first_step_observed or tally.first_step_wins is None:
            tally.first_step_wins = tally.fell_off = None
        else:
            tally.first_step_wins += int(outcome.first_step_success)
            tally.fell_off += int(outcome.fell_off)
        if outcome.linger_holds is not None:
            tally.lingered += 1
            tally.linger_holds += int(outcome.linger_holds)

    def tallies(self, task: str) -> list[Tally]:
        return [by_task[task] for by_task in self.per_seed.values() if task in by_task]

    def training_seeds(self, task: str) -> int:
        """How many training seeds' actors were evaluated on ``task``."""
        return len(self.tallies(task))

    def wins(self, task: str) -> int:
        return sum(t.wins for t in self.tallies(task))

    def episodes(self, task: str) -> int:
        return sum(t.episodes for t in self.tallies(task))

    def mean_steps(self, task: str) -> float:
        return sum(t.steps for t in self.tallies(task)) / self.episodes(task)

    def rate(self, task: str) -> float:
        return self.wins(task) / self.episodes(task)

    def first_step_rate(self, task: str) -> float | None:
        """The rate under the first-step rule (literals held at some step), where it was observed."""
        counts = [t.first_step_wins for t in self.tallies(task)]
        return None if None in counts else sum(counts) / self.episodes(task)

    def linger_rate(self, task: str) -> float | None:
        """Of the successes checked after ``--linger`` steps, the share whose goal still held at rest."""
        lingered = sum(t.lingered for t in self.tallies(task))
        return sum(t.linger_holds for t in self.tallies(task)) / lingered if lingered else None

    def fell_off_rate(self, task: str) -> float | None:
        """The share of episodes that ended with a block off the table, where it was observed."""
        counts = [t.fell_off for t in self.tallies(task)]
        return None if None in counts else sum(counts) / self.episodes(task)

    def median_settled_steps(self, task: str) -> float | None:
        steps = [s for t in self.tallies(task) for s in t.settled_steps]
        return statistics.median(steps) if steps else None

    def interval(self, task: str) -> tuple[float, float]:
        """95 % Wilson score interval of the rate: unlike the normal approximation it stays wide at 0 and
        1 (10 of 10 episodes still admit a rate near 72 %)."""
        return wilson_interval(self.wins(task), self.episodes(task))


def unlike_in_process(in_process: Row, via_ros: Row, label: str, task: str) -> list[str]:
    """The graph's episodes of ``task`` that did not end as the same start did in process (success at rest and
    control steps), each said in words; the graph runs ``label``'s actors (the shipped ones or the expert). Where a
    scene's pool stands in for its shipped actor in process (``pool.json`` without it), the pool's first actor is the
    shipped one (the pool's rule), so its episodes are the ones compared."""
    by_label = in_process.per_seed
    same_actor = label if task in by_label.get(label, {}) else next(
        (name for name, tasks in by_label.items() if task in tasks), label)
    ran = by_label.get(same_actor, {}).get(task, Tally()).ends
    unlike = []
    for seed, (success, steps) in sorted(via_ros.per_seed[label][task].ends.items()):
        if seed not in ran:
            unlike.append(f"{task} from seed {seed}: not run in process")
        elif ran[seed] != (success, steps):
            unlike.append(f"{task} from seed {seed}: via ROS {_ending(success, steps)}, in process {_ending(*ran[seed])}")
    return unlike


def missed_starts(row: Row, label: str, task: str) -> list[str]:
    """The starts of ``task`` that ``label``'s actors missed in ``row``, each said in words (to trace them)."""
    ends = row.per_seed.get(label, {}).get(task, Tally()).ends
    return [f"{task} from seed {seed}: {_ending(False, steps)}" for seed, (success, steps) in sorted(ends.items())
            if not success]


def missed_in_process(rows: list[Row], tasks: list[str]) -> list[str]:
    """Each start an agent missed in process, with why (a block off the table: which, over which edge, when and during
    which steps), per agent, task and training seed: to trace misses without a one-off script."""
    return [f"missed: {row.agent} {label} {task} from seed {seed}: {why}"
            for row in rows for label, by_task in row.per_seed.items() for task in tasks
            for seed, why in sorted(by_task.get(task, Tally()).why.items())]


def print_missed(row: Row, tasks: list[str], label: str) -> None:
    """Say which starts the graph missed (where the graph sees by the camera, in process is no reference)."""
    missed = [line for task in tasks for line in missed_starts(row, label, task)]
    print(f"via ROS: {len(missed)} start(s) missed" + (":" if missed else ""), file=sys.stderr)
    for line in missed:
        print(f"    {line}", file=sys.stderr)


def _ending(success: bool, steps: int) -> str:
    return f"{'succeeded' if success else 'failed'} after {steps} steps"


def wilson_interval(wins: int, n: int, z: float = 1.96) -> tuple[float, float]:
    p = wins / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    return max(0.0, centre - half), min(1.0, centre + half)


def parse_tasks(text: str) -> list[str]:
    """``all`` (the paper's eight), ``tabletop`` (its tasks) or task names, comma-separated."""
    if text.strip().lower() == "all":
        return list(TASKS)
    if text.strip().lower() == "tabletop":
        return list(TABLETOP_TASKS)
    return [get_task(name).name for name in text.split(",") if name.strip()]


POOL_FILE = "pool.json"
"""``models/seeds/<name>/pool.json``: ``{"actors": ["seed25", ...], "with_shipped": false, "why": "..."}``
names the training seeds a row pools, when a rule chose them (otherwise: the shipped actor, then every
``seed*`` folder)."""


def actor_dirs(agent: str, scene: str, seeds: int, models_dir: Path) -> list[Path]:
    """Exported actors of ``agent`` for ``scene`` to pool: those ``pool.json`` names, or else the shipped
    one first, then the extra training seeds."""
    from semgoal_policy.agents import get_agent

    if models_dir == Path(EXPERT):
        if agent != "hierarchical":
            raise FileNotFoundError(f"the scripted expert stands in for the hierarchical agent's actor only, not {agent}")
        return [models_dir]
    name = get_agent(agent).model_name(scene)
    extra_dir = models_dir / "seeds" / name
    pool_file = extra_dir / POOL_FILE
    if pool_file.exists():
        pool = json.loads(pool_file.read_text())
        dirs = [models_dir / name] * bool(pool.get("with_shipped", True)) + [extra_dir / d for d in pool["actors"]]
        missing = [str(d) for d in dirs if not (d / "actor.json").exists()]
        if missing:
            raise FileNotFoundError(f"{pool_file} names actors that are not exported: {', '.join(missing)}")
    else:
        extra = sorted(extra_dir.glob("seed*")) if extra_dir.is_dir() else []
        dirs = [d for d in [models_dir / name, *extra] if (d / "actor.json").exists()]
    return dirs[:seeds]


def evaluate_task(agent: str, task_name: str, episodes: range, seed: int, seeds: int, models_dir: Path,
                  linger: int = 0, sleep: bool = True) -> Row:
    """In-process episodes (their indices: episode i starts from task seed ``seed + i``) of one agent on one task,
    for every available training seed (one job); ``linger``: control steps after a success before the goal is
    checked again (the hierarchical agent); ``sleep``: its worlds' blocks at rest sleep (False: awake)."""
    import torch

    from semgoal_bringup.experiments.episodes import make_agent

    torch.set_num_threads(1)
    row = Row(agent)
    started = time.perf_counter()
    scene = get_task(task_name).scene
    dirs = actor_dirs(agent, scene, seeds, models_dir)
    if not dirs:
        raise FileNotFoundError(f"no exported {agent} actor for {scene} under {models_dir}: "
                                f"train one with ./semgoal train --scene {scene} --agent {agent}")
    for directory in dirs:
        label = "shipped" if directory.parent == models_dir else directory.name
        expert = directory == models_dir
        row.seed_steps[label] = {0 if expert else json.loads((directory / "actor.json").read_text())["env_steps"]}
        runner = make_agent(agent, scene, directory, sleep=sleep)
        for i in episodes:
            row.add(label, runner.run(task_name, seed + i, linger=linger) if agent == "hierarchical"
                    else runner.run(task_name, seed + i))
    row.wall_s = time.perf_counter() - started
    return row


def merge(rows: list[Row]) -> list[Row]:
    """One row per agent from per-job rows (tasks, chunks of episodes), in first-seen order."""
    merged: dict[str, Row] = {}
    for part in rows:
        row = merged.setdefault(part.agent, Row(part.agent))
        for label, results in part.per_seed.items():
            for task, tally in results.items():
                row.per_seed.setdefault(label, {}).setdefault(task, Tally()).add(tally)
            row.seed_steps.setdefault(label, set()).update(part.seed_steps[label])
        row.wall_s += part.wall_s
    return list(merged.values())


def evaluate_in_process(agents: list[str], tasks: list[str], episodes: int, seed: int, seeds: int, models_dir: Path,
                        jobs: int, executor: str = "local", chunk: int = 0, linger: int = 0,
                        sleep: bool = True) -> list[Row]:
    """Every (agent, task, chunk of ``chunk`` episodes; 0: all) as a job on ``executor`` with ``jobs`` workers.
    Each job is seeded by its episodes' indices: the rows do not depend on the executor, the workers or the chunks."""
    size = chunk or episodes
    work = [(agent, task, range(first, min(first + size, episodes)), seed, seeds, models_dir, linger, sleep)
            for agent in agents for task in tasks for first in range(0, episodes, size)]
    return merge(run_jobs(evaluate_task, work, executor, jobs, what="eval job"))


def evaluate_via_ros(task_names: list[str], episodes: int, seed: int, record: Path | None = None,
                     sight: Sight = TRUTH, models: str = "", composed: bool = False) -> Row:
    from tqdm import tqdm

    from semgoal_bringup.experiments.graph_eval import run_via_ros
    from semgoal_policy import actor as actor_io

    row = Row(VIA_ROS)
    started = time.perf_counter()
    outcomes = run_via_ros(task_names, episodes, seed, models, record=record, sight=sight, composed=composed)
    label = EXPERT if models == EXPERT else "shipped"
    for outcome in tqdm(outcomes, total=len(task_names) * episodes, unit="episode", desc="eval via ROS", file=sys.stderr):
        row.add(label, outcome, first_step_observed=False)  # the graph runs the actors of ``models`` (or the expert)
    for task_name in task_names:
        actor = Path(models or actor_io.models_dir()) / get_task(task_name).scene / "actor.json"
        row.seed_steps.setdefault(label, set()).add(0 if label == EXPERT else json.loads(actor.read_text())["env_steps"])
    row.wall_s = time.perf_counter() - started
    return row


# -- reports ---------------------------------------------------------------------------------------------
def _steps_text(env_steps: set[int]) -> str:
    """A run stops at the first whole batch of episodes past its budget (300480 for 300k): round to k first."""
    low, high = min(env_steps) // 1000, max(env_steps) // 1000
    return f"{low}k" if low == high else f"{low}k-{high}k"


def _seeds_text(row: Row, tasks: list[str]) -> str:
    counts = {row.training_seeds(t) for t in tasks}
    return str(min(counts)) if len(counts) == 1 else f"{min(counts)}-{max(counts)}"


def _in_paper(tasks: list[str]) -> bool:
    """Whether the paper's Table 1 has every one of ``tasks`` (the tabletop's it has not): its rows are shown then."""
    return set(tasks) <= set(TASKS)


def write_markdown(rows: list[Row], tasks: list[str], record: dict, path: Path) -> None:
    header = "| Method | training seeds | training steps | episodes per task and seed | " + " | ".join(tasks) + " |"
    paper = _in_paper(tasks)
    lines = [
        "# Table 1: task completion (%)" if paper else "# Task completion (%)",
        "",
        f"Ours: task seeds from {record['seed']} (episode i of every agent starts from the same state), at most "
        f"{TASK_STEP_BUDGET} control steps each; success when the goal's literals hold with the world at rest "
        f"(every block slower than {REST_SPEED} m/s, none held unless asked) over {SETTLE_STEPS} control steps, "
        "the executive's rule; brackets hold the 95 % (Wilson) interval."
        + (" Paper: Table 1 of the paper (2M training steps, 50 episodes, mean of three training seeds)." if paper
           else " These tasks are not the paper's: it has no row for them."),
        f"Regenerate: `{record['command']}`",
        f"Produced by {describe(record)}.",
        *(["The hierarchy's actor: the scripted expert (`--models expert`), not a learned one."]
          if any(EXPERT in row.per_seed for row in rows) else []),
        "",
        header,
        "|" + "---|" * (4 + len(tasks)),
    ]
    for agent in AGENT_NAMES:
        if any(r.agent.startswith(agent) for r in rows) and _in_paper(tasks):
            paper = PAPER_TABLE1[agent]
            lines.append(f"| {PAPER_NAMES[agent]} (paper) | 3 | 2000k | 50 | "
                         + " | ".join(f"{paper[t]}" for t in tasks) + " |")
        for row in rows:
            if row.agent.split(" ")[0] == agent:
                cells = [f"{100 * row.rate(t):.0f} [{100 * low:.0f}-{100 * high:.0f}]"
                         for t in tasks for low, high in [row.interval(t)]]
                episodes = min(tally.episodes for t in tasks for tally in row.tallies(t))
                lines.append(f"| **{row.agent} (ours)** | {_seeds_text(row, tasks)} | {_steps_text(row.env_steps)} | "
                             f"{episodes} | " + " | ".join(cells) + " |")
                if all(row.first_step_rate(t) is not None for t in tasks):
                    lines.append(f"| {row.agent} (ours), first-step rule, same episodes | "
                                 f"{_seeds_text(row, tasks)} | {_steps_text(row.env_steps)} | {episodes} | "
                                 + " | ".join(f"{100 * row.first_step_rate(t):.0f}" for t in tasks) + " |")
    for row in rows:
        if len(row.per_seed) > 1:
            lines += _per_seed_lines(row, tasks)
    path.write_text("\n".join(lines) + "\n")


def _per_seed_lines(row: Row, tasks: list[str]) -> list[str]:
    """The row's rates split by training seed (blank where a seed has no actor for the task's scene): the
    spread between seeds, which the pooled interval above does not show."""
    lines = ["", f"{row.agent} (ours) by training seed (`shipped`: the actors under `models/`; others: "
             "`models/seeds/<scene>/<seed>`; a scene's `pool.json` names them where a rule chose them):", "",
             "| training seed | training steps | " + " | ".join(tasks) + " |", "|" + "---|" * (2 + len(tasks))]
    for label in sorted(row.per_seed, key=lambda name: (name != "shipped", name)):
        results = row.per_seed[label]
        cells = [f"{100 * results[t].wins / results[t].episodes:.0f}" if t in results else "" for t in tasks]
        lines.append(f"| {label} | {_steps_text(row.seed_steps[label])} | " + " | ".join(cells) + " |")
    return lines


def write_csv(rows: list[Row], tasks: list[str], record: dict, path: Path) -> None:
    """A row per agent and task; ours carry the commit that produced them (the paper's: blank)."""
    with path.open("w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["agent", "source", "task", "success_rate", "episodes", "ci95_low", "ci95_high", "mean_steps",
                         "training_seeds", "training_steps", "median_settled_steps", "first_step_rule_rate", "commit"])
        for agent in AGENT_NAMES:
            if any(r.agent.startswith(agent) for r in rows) and _in_paper(tasks):
                for t in tasks:
                    writer.writerow([agent, "paper", t, PAPER_TABLE1[agent][t] / 100, 50, "", "", "", 3, 2_000_000, "", "",
                                     ""])
        for row in rows:
            for t in tasks:
                writer.writerow([row.agent, "ours", t, round(row.rate(t), 4), row.episodes(t),
                                 *(round(bound, 4) for bound in row.interval(t)),
                                 round(row.mean_steps(t), 1), row.training_seeds(t),
                                 "/".join(map(str, sorted(row.env_steps))), _blank(row.median_settled_steps(t)),
                                 _blank(row.first_step_rate(t)), record["commit"]])


def _blank(value: float | None) -> str | float:
    return "" if value is None else round(value, 4)


def _error_bars(row: Row, tasks: list[str]) -> list[list[float]]:
    """matplotlib's asymmetric yerr: distances (%) from each rate down and up to its interval's ends."""
    bounds = [row.interval(t) for t in tasks]
    return [[100 * (row.rate(t) - low) for t, (low, _) in zip(tasks, bounds, strict=True)],
            [100 * (high - row.rate(t)) for t, (_, high) in zip(tasks, bounds, strict=True)]]


def write_chart(rows: list[Row], tasks: list[str], path: Path) -> None:
    """Grouped bars per task: ours solid (with 95 % intervals), the paper's hatched beside them."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    colours = {"hierarchical": "tab:blue", VIA_ROS: "tab:cyan", "flat-semantic": "tab:orange",
               "flat-continuous": "tab:green"}
    series = []
    for agent in AGENT_NAMES:
        ours = [r for r in rows if r.agent.split(" ")[0] == agent]
        if ours and _in_paper(tasks):
            series.append((f"{PAPER_NAMES[agent]} (paper)", [PAPER_TABLE1[agent][t] for t in tasks], None,
                           colours[agent], "//"))
        series += [(f"{r.agent} (ours)", [100 * r.rate(t) for t in tasks], _error_bars(r, tasks), colours[r.agent], None)
                   for r in ours]
    width = 0.8 / len(series)
    x = np.arange(len(tasks))
    fig, ax = plt.subplots(figsize=(11, 4.2), dpi=110)
    for i, (label, values, errors, colour, hatch) in enumerate(series):
        ax.bar(x + (i - (len(series) - 1) / 2) * width, values, width, yerr=errors, label=label, capsize=2,
               color="white" if hatch else colour, edgecolor=colour, hatch=hatch, linewidth=1)
    ax.set_xticks(x, tasks)
    ax.set(ylabel="task completion (%)", ylim=(0, 105),
           title="Table 1: ours beside the paper's" if _in_paper(tasks) else "Task completion at rest")
    ax.grid(axis="y", alpha=0.3)
    ax.legend(fontsize=7, ncol=2, loc="upper center", bbox_to_anchor=(0.5, -0.08))
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def summary(rows: list[Row], task: str) -> dict:
    """One task's JSON: each agent's rate at rest, the median steps to success at rest and, where observed,
    the rate under the first-step rule on the same episodes."""
    def observed(rate) -> dict:
        return {row.agent: round(rate(row), 4) for row in rows if rate(row) is not None}

    return {**{row.agent: round(row.rate(task), 4) for row in rows},
            "settled_steps": {row.agent: row.median_settled_steps(task) for row in rows},
            "first_step_rule": observed(lambda row: row.first_step_rate(task)),
            "linger_holds": observed(lambda row: row.linger_rate(task)),
            "fell_off": observed(lambda row: row.fell_off_rate(task))}


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="semgoal eval", description=__doc__.split("\n\n")[0])
    parser.add_argument("--tasks", default="all", help="comma-separated task names, all (the paper's) or tabletop")
    parser.add_argument("--episodes", type=count, default=50, help="episodes per task and training seed")
    parser.add_argument("--seed", type=natural, default=DEFAULT_SEED, help="first task seed (fixes every start)")
    parser.add_argument("--seeds", type=count, default=3, help="training seeds to average where actors exist")
    parser.add_argument("--agents", type=names, default="hierarchical", help=f"comma-separated: {', '.join(AGENT_NAMES)}")
    parser.add_argument("--via-ros", action="store_true", help="also run the hierarchical agent through the node graph")
    parser.add_argument("--ros-episodes", type=count, help="episodes per task through the graph (default: --episodes)")
    parser.add_argument("--record", type=Path, help="with --via-ros: write each graph episode to DIR/TASK-SEED.mcap")
    parser.add_argument("--composed", action="store_true", help="with --via-ros: the graph's nodes in one process "
                        "(graph_node), their messages to each other handed over as objects")
    parser.add_argument("--models", type=Path, help="folder of exported actors, SCENE/actor.pt (default: the shipped "
                        "ones), in process and, with --via-ros, through the graph; 'expert': the scripted expert, the "
                        "actors' teacher, drives the hierarchy")
    add_sight_arguments(parser)
    parser.add_argument("--out", type=Path, help="write table1.md, table1.csv and table1.png here")
    parser.add_argument("--json", action="store_true", help="print the JSON summary as the last line")
    parser.add_argument("--jobs", type=count, default=os.cpu_count() or 1, help="worker processes (in-process episodes)")
    parser.add_argument("--executor", default="local", type=check_executor,
                        help="local (a process pool), dask (a Dask LocalCluster on 127.0.0.1) or dask:ADDRESS (a running "
                             "Dask scheduler)")
    parser.add_argument("--chunk", type=natural, default=10, help="episodes per job (per agent and task; 0: all in one)")
    parser.add_argument("--awake", action="store_true", help="the hierarchical agent's blocks never sleep (MuJoCo's "
                        "sleeping islands off, as the actors were trained): in process only")
    parser.add_argument("--linger", type=natural, default=0, help="after each success, this many control steps of the idle "
                        "arm, then whether the goal still holds at rest (linger_holds; the hierarchical agent in process)")
    parser.add_argument("--misses", action="store_true", help="list each start missed in process and why (for a block "
                        "off the table: which, over which edge, at which control step, during which robot steps; else "
                        "the goal's literals that did not hold at the end)")
    args = parser.parse_args(argv)
    try:
        tasks = parse_tasks(args.tasks)
    except KeyError as error:
        parser.error(str(error.args[0]))
    if args.linger < 0:
        parser.error(f"--linger takes control steps (0 or more), got {args.linger}")
    if args.record and not args.via_ros:
        parser.error("--record writes the episodes run through the graph: add --via-ros")
    if args.composed and not args.via_ros:
        parser.error("--composed runs the graph's nodes in one process: add --via-ros")
    sight = sight_of(args, parser, tasks)
    if sight != TRUTH and not args.via_ros:
        parser.error("--perception / --policy-input camera run through the graph: add --via-ros")
    agents = args.agents
    unknown = [a for a in agents if a not in AGENT_NAMES]
    if unknown or not tasks:
        parser.error(f"need tasks and agents from {', '.join(AGENT_NAMES)} (got {','.join(agents)!r})")
    if args.awake and (args.via_ros or agents != ["hierarchical"]):
        parser.error("--awake runs the hierarchical agent in process: give --agents hierarchical, without --via-ros")
    from semgoal_policy import actor as actor_io

    models_dir = args.models or actor_io.models_dir()
    try:
        rows = evaluate_in_process(agents, tasks, args.episodes, args.seed, args.seeds, models_dir, args.jobs,
                                   args.executor, args.chunk, args.linger, not args.awake)
    except FileNotFoundError as error:
        print(f"semgoal eval: {error}", file=sys.stderr)
        return 2
    failed, as_in_process = False, {}
    if args.via_ros:
        graph_models = "" if args.models is None else EXPERT if str(args.models) == EXPERT else str(args.models.resolve())
        try:
            rows.append(evaluate_via_ros(tasks, args.ros_episodes or args.episodes, args.seed, args.record, sight,
                                         graph_models, args.composed))
        except RuntimeError as error:  # the in-process rows are still written
            print(f"semgoal eval: through the graph: {error}", file=sys.stderr)
            failed = True
        else:
            as_in_process = compare_with_graph(rows, tasks, EXPERT if graph_models == EXPERT else "shipped", sight)
    for row in rows:
        print(f"{row.agent:24s} " + "  ".join(f"{t} {100 * row.rate(t):5.1f}%" for t in tasks)
              + f"   ({row.wall_s:.0f} s)", file=sys.stderr if args.json else sys.stdout)
    if args.misses:
        for line in missed_in_process([row for row in rows if row.agent != VIA_ROS], tasks):
            print(line, file=sys.stderr if args.json else sys.stdout)
    if args.out:
        args.out.mkdir(parents=True, exist_ok=True)
        record = provenance(shlex.join(["./semgoal", "eval", *argv]), args.seed)
        write_markdown(rows, tasks, record, args.out / "table1.md")
        write_csv(rows, tasks, record, args.out / "table1.csv")
        write_chart(rows, tasks, args.out / "table1.png")
        (args.out / "table1.json").write_text(json.dumps({"provenance": record, "tasks": {t: summary(rows, t) for t in tasks}},
                                                         indent=2) + "\n")
        print(f"wrote {args.out}/table1.md, table1.csv, table1.json, table1.png", file=sys.stderr)
    if args.json:
        print(json.dumps({t: {**summary(rows, t), **({"via_ros_as_in_process": as_in_process[t]} if as_in_process else {})}
                          for t in tasks}))
    return 1 if failed else 0


def compare_with_graph(rows: list[Row], tasks: list[str], label: str, sight: Sight) -> dict[str, dict[str, int]]:
    """Print how many of the graph's episodes ended as the same starts did in process, and each that did not; per
    task ``{"same": k, "episodes": n}`` (on ground truth the two agree episode for episode: the graph runs in
    lockstep). Empty where there is nothing to compare (no in-process hierarchical row, or the graph saw by camera):
    then it names the starts the graph missed."""
    in_process = next((row for row in rows if row.agent == "hierarchical"), None)
    if in_process is None or sight != TRUTH:
        print_missed(rows[-1], tasks, label)
        return {}
    via_ros, counts, unlike_all = rows[-1], {}, []
    for task in tasks:
        unlike = unlike_in_process(in_process, via_ros, label, task)
        counts[task] = {"same": via_ros.episodes(task) - len(unlike), "episodes": via_ros.episodes(task)}
        unlike_all += unlike
    same, total = (sum(c[key] for c in counts.values()) for key in ("same", "episodes"))
    print(f"via ROS: {same} of {total} episodes ended as in process (success at rest and control steps)", file=sys.stderr)
    for line in unlike_all:
        print(f"    {line}", file=sys.stderr)
    return counts
