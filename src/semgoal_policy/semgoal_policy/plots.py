"""Learning-curve pictures from a training run's progress CSV."""

from __future__ import annotations

import csv
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

TARGET = 0.95


def learning_curve(csv_path: Path, png_path: Path, title: str) -> int | None:
    """Plot success per kind against env steps; return the first env step at which every kind reached 95 %."""
    with csv_path.open() as f:
        rows = list(csv.DictReader(f))
    if not rows:
        return None
    steps = [int(r["env_steps"]) for r in rows]
    kinds = [k for k in rows[0] if k.startswith("eval/success/") and k != "eval/success/overall"]
    fig, ax = plt.subplots(figsize=(8.2, 4), dpi=110)
    for key in kinds:  # a kind reported from a later evaluation on (a resumed run that reports more) from there
        measured = [(step, float(r[key])) for step, r in zip(steps, rows, strict=True) if r[key]]
        ax.plot(*zip(*measured, strict=True), label=key.removeprefix("eval/success/"))
    ax.plot(steps, [float(r["eval/success/overall"]) for r in rows], "k--", lw=2, label="overall")
    reached = next((s for s, r in zip(steps, rows, strict=True)
                    if all(r[k] for k in kinds) and min(float(r[k]) for k in kinds) >= TARGET), None)
    ax.axhline(TARGET, color="grey", lw=0.8, ls=":")
    xlabel = "env steps"
    if reached is not None:  # said under the axis: text inside it collides with the legend or the curves
        ax.axvline(reached, color="green", lw=1, ls=":")
        xlabel += f" (dotted green: every kind ≥ 95 % first at {reached:,})"
    ax.set(xlabel=xlabel, ylabel="success (deterministic actor)", ylim=(-0.02, 1.02), title=title)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="center left", bbox_to_anchor=(1.01, 0.5))  # beside the axes: it hides no curve
    fig.tight_layout()
    png_path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(png_path)
    plt.close(fig)
    return reached
