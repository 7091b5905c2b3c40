"""`./semgoal ablation --scene S --steps N [--jobs J]`: what each element of expert supervision buys.

Trains one actor per variant with the same seed and budget (each a plain `./semgoal train` in its own
process, ``--jobs`` at a time), then writes ``docs/ablation-SCENE.md`` (final success per sub-goal type,
the first evaluation at which the overall success reached 80 %, wall time) and a PNG of the overall
learning curves. Variants drop one element of the recipe at a time, and all of them at once.
"""

from __future__ import annotations

import argparse
import csv
import json
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from semgoal_core.arguments import count, natural

VARIANTS: dict[str, list[str]] = {
    "full recipe": [],
    "no demonstrations": ["--demo-fraction", "0"],
    "no behaviour cloning": ["--bc-weight", "0"],
    "cloning without Q-filter": ["--no-q-filter"],
    "no curriculum": ["--no-curriculum"],
    "plain SAC + HER": ["--demo-fraction", "0", "--bc-weight", "0", "--no-curriculum"],
}
REACHED = 0.8


def _slug(variant: str) -> str:
    return variant.replace(" ", "-").replace("+", "").replace("--", "-")


def train(scene: str, variant: str, steps: int, seed: int, final_episodes: int, out: Path) -> dict:
    run_dir = out / _slug(variant)
    command = [sys.executable, "-m", "semgoal_bringup.cli", "train", "--scene", scene, "--steps", str(steps),
               "--seed", str(seed), "--run-dir", str(run_dir), "--export-dir", str(run_dir / "actor"),
               "--final-eval-episodes", str(final_episodes), "--resume", *VARIANTS[variant]]
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        raise RuntimeError(f"{variant}: training failed\n{result.stderr[-2000:]}")
    summary = json.loads(result.stdout.strip().splitlines()[-1])
    with (run_dir / "progress.csv").open() as f:
        rows = list(csv.DictReader(f))
    curve = [(int(r["env_steps"]), float(r["eval/success/overall"])) for r in rows]
    summary["curve"] = curve
    summary["reached"] = next((s for s, v in curve if v >= REACHED), None)
    return summary


def write_report(scene: str, steps: int, seed: int, results: dict[str, dict], docs: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    kinds = list(next(iter(results.values()))["per_kind"])
    lines = [f"# Ablation of expert supervision: {scene}, {steps:,} env steps, training seed {seed}", "",
             f"Command: `./semgoal ablation --scene {scene} --steps {steps} --seed {seed}`. Final success of the "
             "deterministic actor per sub-goal type (evaluation seeds from 1,000,000, never used in training); "
             f"'80 % at' is the first evaluation (every 10k steps, 20 episodes per type) whose mean reached {REACHED:.0%}.",
             "", "| variant | " + " | ".join(kinds) + " | overall | 80 % at | wall (min) |",
             "|---|" + "---|" * (len(kinds) + 3)]
    for variant, r in results.items():
        rates = " | ".join(f"{100 * r['per_kind'][k]:.0f}" for k in kinds)
        overall = 100 * sum(r["per_kind"].values()) / len(kinds)
        reached = f"{r['reached']:,}" if r["reached"] else "—"
        lines.append(f"| {variant} | {rates} | {overall:.0f} | {reached} | {r['wall_s'] / 60:.1f} |")
    report = docs / f"ablation-{scene}.md"
    report.write_text("\n".join(lines) + "\n")
    fig, ax = plt.subplots(figsize=(7, 4), dpi=110)
    for variant, r in results.items():
        ax.plot(*zip(*r["curve"], strict=True), label=variant)
    ax.set(xlabel="env steps", ylabel="overall sub-goal success", ylim=(-0.02, 1.02), title=f"Ablation: {scene}")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(docs / f"ablation-{scene}.png")
    plt.close(fig)
    return report


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="semgoal ablation", description=__doc__.split("\n\n")[0])
    parser.add_argument("--scene", default="two_blocks")
    parser.add_argument("--steps", type=count, default=50_000)
    parser.add_argument("--seed", type=natural, default=1)
    parser.add_argument("--final-eval-episodes", type=count, default=50)
    parser.add_argument("--jobs", type=count, default=2)
    parser.add_argument("--out", type=Path, default=Path("runs/ablation"))
    parser.add_argument("--docs", type=Path, default=Path("docs"))
    args = parser.parse_args(argv)
    out = args.out / args.scene
    with ThreadPoolExecutor(args.jobs) as pool:
        futures = {v: pool.submit(train, args.scene, v, args.steps, args.seed, args.final_eval_episodes, out)
                   for v in VARIANTS}
        results = {v: f.result() for v, f in futures.items()}
    report = write_report(args.scene, args.steps, args.seed, results, args.docs)
    print(report.read_text())
    print(json.dumps({v: {"per_kind": r["per_kind"], "reached": r["reached"]} for v, r in results.items()}))
    return 0
