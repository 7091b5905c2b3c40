"""A model card per exported actor (``MODEL_CARD.md`` beside ``actor.json``), written from ``actor.json`` alone
so that it cannot drift from it: intended use, training budget and recipe, its evaluation, provenance, limits.
``./semgoal model-card DIR...`` (re)writes the cards; every export writes its own. An actor exported before
provenance was kept gets it traced in git history first (``--trace``): the first commit that held its weights."""

from __future__ import annotations

import argparse
import csv
import json
from pathlib import Path

from semgoal_core.provenance import describe, traced

LIMITS = {
    "hierarchical": "It executes one sub-goal (a pick, a put) at a time; whole tasks need the planner, which "
                    "sequences the sub-goals and checks each at rest. Trained and measured in simulation only.",
    "flat-semantic": "A flat baseline of the paper's Table 1: one network for a whole task from a semantic goal, "
                     "no planner. It is weak by design (the paper's point); do not use it to do tasks.",
    "flat-continuous": "A flat baseline of the paper's Table 1: one network for a whole task from goal block "
                       "positions, no planner. It is weak by design (the paper's point); do not use it to do tasks.",
}


REACHED = 0.9
"""The success rate whose first env step the card reports per kind: the tabletop's sample-efficiency yardstick."""
REACHED_WINDOW = 3
"""Evaluations averaged for it: training's own evaluation has few episodes per type (20 in the recipes), so one
lucky evaluation does not count."""


def steps_to_reach(rows: list[dict[str, str]], rate: float = REACHED, window: int = REACHED_WINDOW) -> dict[str, int | None]:
    """Per kind (sub-goal type or task) of a progress CSV: the env steps of the first evaluation at which the mean
    success of it and the ``window - 1`` evaluations before it is at least ``rate``; None where that never happens."""
    kinds = [k.removeprefix("eval/success/") for k in (rows[0] if rows else {})
             if k.startswith("eval/success/") and k != "eval/success/overall"]
    reached: dict[str, int | None] = {}
    for kind in kinds:  # over the evaluations that report it (a resumed run may report a kind from later on)
        measured = [(int(r["env_steps"]), float(r[f"eval/success/{kind}"])) for r in rows if r[f"eval/success/{kind}"]]
        rates = [value for _, value in measured]
        reached[kind] = next((measured[i][0] for i in range(window - 1, len(measured))
                              if sum(rates[i - window + 1:i + 1]) / window >= rate), None)
    return reached


def _sample_efficiency(directory: Path) -> list[str]:
    """The card's lines on how many env steps each kind took to reach :data:`REACHED` (none without a progress CSV)."""
    path = directory / "progress.csv"
    if not path.exists():
        return []
    with path.open() as f:
        rows = list(csv.DictReader(f))
    if not rows:
        return []
    reached = steps_to_reach(rows)
    said = ", ".join(f"{kind} {steps:,}" if steps is not None else f"{kind} not by {int(rows[-1]['env_steps']):,}"
                     for kind, steps in reached.items())
    return [f"**Env steps to {REACHED * 100:.0f} % per kind** (training's own evaluation in `progress.csv`, the mean of "
            f"{REACHED_WINDOW} evaluations in a row): {said}.", ""]


def model_card(directory: Path) -> str:
    """The card of the actor exported in ``directory``."""
    meta = json.loads((directory / "actor.json").read_text())
    scene, agent = meta["layout"]["scene"], meta.get("agent", "hierarchical")
    final = meta.get("final_eval", {})
    rates = ", ".join(f"{kind} {100 * rate:.0f} %" for kind, rate in final.get("per_kind", {}).items())
    derived = ", ".join(name for name, _ in meta["layout"].get("derived_features") or []) or "none"
    record = meta.get("provenance")
    lines = [
        f"# {scene} · {agent} actor (seed {meta.get('seed')})",
        "",
        f"**Intended use.** The {agent} agent's policy for the simulated Fetch in the `{scene}` scene of semgoal: "
        f"SAC+HER, goal-conditioned ({meta['layout'].get('goal', 'semantic')} goals), 4-D end-effector and gripper "
        "commands at 25 Hz. Research and teaching in simulation; not a controller for a real robot.",
        "",
        f"**Training.** {meta.get('env_steps', 0):,} env steps, {meta.get('wall_s', 0) / 60:.0f} min wall, seed "
        f"{meta.get('seed')}; derived observation features: {derived}. Command: `{meta.get('command', 'not recorded')}`.",
        "",
        f"**Evaluation** (at the end of training, {final.get('episodes_per_kind', '?')} episodes per kind from "
        f"seed {final.get('seed', '?')}, seeds never used in training, success at rest): {rates or 'not recorded'}. "
        "Task-level figures: `results/table1.md`.",
        "",
        *_sample_efficiency(directory),
        f"**Provenance.** {describe(record) if record else 'not recorded (exported before provenance was kept)'}.",
        "",
        f"**Limits.** {LIMITS.get(agent, LIMITS['hierarchical'])}",
        "",
        "Files: `actor.pt` (weights), `actor.json` (layout, recipe, figures), `learning_curve.png`, `progress.csv`.",
    ]
    return "\n".join(lines) + "\n"


def write_card(directory: Path) -> Path:
    path = directory / "MODEL_CARD.md"
    path.write_text(model_card(directory))
    return path


def trace_provenance(directory: Path) -> bool:
    """Give an actor exported without provenance the one git history traces for its weights; whether it did."""
    path = directory / "actor.json"
    meta = json.loads(path.read_text())
    if meta.get("provenance"):
        return False
    record = traced(directory / "actor.pt", meta.get("command", "not recorded"), meta.get("seed"))
    if record is None:
        return False
    meta["provenance"] = record
    path.write_text(json.dumps(meta, indent=2) + "\n")
    return True


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="semgoal model-card", description=__doc__.split("\n\n")[0])
    parser.add_argument("dirs", nargs="+", type=Path, help="folders with an exported actor (actor.json)")
    parser.add_argument("--trace", action="store_true",
                        help="first give actors without provenance the one traced in git history")
    args = parser.parse_args(argv)
    if missing := [str(d) for d in args.dirs if not (d / "actor.json").is_file()]:
        parser.error(f"no exported actor (actor.json) in {', '.join(missing)}")
    for directory in args.dirs:
        if args.trace and trace_provenance(directory):
            print(f"traced the provenance of {directory / 'actor.json'} in git history")
        print(f"wrote {write_card(directory)}")
    return 0
