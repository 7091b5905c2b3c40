"""`./semgoal train perception [--images N] [--seed S]`: render labelled frames (the expert at work under a
randomised look), train the block voter on them and export it beside its model card.

The recipe is data (``semgoal_perception/recipes/block_voter.json``); flags override it and the exported
``voter.json`` records what ran. Rendered frames are cached under ``runs/perception/`` by seed, count and size.
"""

from __future__ import annotations

import argparse
import json
import os
import time
from dataclasses import fields
from pathlib import Path

from semgoal_core.arguments import count, natural
from semgoal_core.provenance import provenance

CHECKOUT_PACKAGE = Path(os.environ.get("SEMGOAL_ROOT") or Path.cwd()) / "src" / "semgoal_perception"
"""Where a new voter is shipped: the checkout's package (``make setup`` installs it)."""


def cached_frames(count: int, seed: int, size: tuple[int, int], strength: float, cache: Path,
                  condition: str = "nominal"):
    """Labelled frames from the cache, rendered first when missing."""
    from semgoal_sim.perception_data import LabelledFrames, labelled_frames

    path = cache / f"frames-seed{seed}-n{count}-{size[0]}x{size[1]}-s{strength:g}-{condition}.npz"
    if path.exists():
        return LabelledFrames.load(path)
    frames = labelled_frames(count, seed, size, strength, condition, progress=True)
    cache.mkdir(parents=True, exist_ok=True)
    frames.save(path)
    return frames


def main(argv: list[str]) -> int:
    os.environ.setdefault("MUJOCO_GL", "osmesa")
    from semgoal_perception.network import VoterConfig
    from semgoal_perception.training import VoterRecipe, train_voter
    from semgoal_ros.package_data import share_path

    recipe = json.loads(share_path("semgoal_perception", "recipes", "block_voter.json").read_text())
    parser = argparse.ArgumentParser(prog="semgoal train perception", description=__doc__.split("\n\n")[0])
    parser.add_argument("--images", type=count, default=recipe["images"], help="labelled frames to render and train on")
    parser.add_argument("--seed", type=natural, default=recipe["seed"], help="task starts seed + episode (8,000,000: training's range)")
    parser.add_argument("--epochs", type=count, default=recipe["voter"]["epochs"])
    parser.add_argument("--out", type=Path, default=CHECKOUT_PACKAGE / "models" / "block_voter",
                        help="export folder (default: the shipped model, in the checkout)")
    parser.add_argument("--cache", type=Path, default=Path("runs/perception"))
    parser.add_argument("--literal-net", action="store_true",
                        help="train the paper's alternative instead (literals straight from the frame) into OUT/../literal_net")
    args = parser.parse_args(argv)
    size = tuple(recipe["camera_size"])
    started = time.perf_counter()
    frames = cached_frames(args.images, args.seed, size, recipe["randomisation_strength"], args.cache)
    rendered = time.perf_counter() - started
    if args.literal_net:
        return train_literal_alternative(frames, args.out.parent / "literal_net", args.epochs, argv)
    voter = {f.name: recipe["voter"][f.name] for f in fields(VoterRecipe)}
    voter.update(epochs=args.epochs, crop=tuple(voter["crop"]))
    summary = train_voter(frames, args.out, VoterRecipe(**voter), VoterConfig(**recipe["network"]))
    summary.update(images=args.images, seed=args.seed, camera_size=list(size),
                   randomisation_strength=recipe["randomisation_strength"],
                   render_s=round(rendered, 1), total_s=round(time.perf_counter() - started, 1),
                   provenance=provenance("./semgoal train-perception " + " ".join(argv), args.seed))
    (args.out / "voter.json").write_text(json.dumps(summary, indent=2) + "\n")
    plot_curve(args.out / "curve.csv", args.out / "curve.png")
    write_model_card(args.out, summary)
    print(json.dumps(summary["final"], indent=2))
    return 0


def train_literal_alternative(frames, out: Path, epochs: int, argv: list[str]) -> int:
    """The paper's alternative on the same frames, exported beside the voter (``eval-perception`` compares them)."""
    from semgoal_core.tasks import TASKS, get_task
    from semgoal_perception.literal_net import train_literal_net

    summary = train_literal_net(frames, [get_task(list(TASKS)[t]) for t in frames.task], out, epochs=epochs)
    summary["provenance"] = provenance("./semgoal train-perception " + " ".join(argv), None)
    (out / "literal_net.json").write_text(json.dumps(summary, indent=2) + "\n")
    print(json.dumps({k: summary[k] for k in ("frames", "epochs", "final_loss", "wall_s")}, indent=2))
    return 0


def plot_curve(csv_path: Path, png_path: Path) -> None:
    """Loss and held-out centre error per epoch, side by side."""
    import csv

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = list(csv.DictReader(csv_path.open()))
    epochs = [int(r["epoch"]) for r in rows]
    figure, (loss, error) = plt.subplots(1, 2, figsize=(9, 3.2))
    loss.plot(epochs, [float(r["loss"]) for r in rows], marker="o")
    loss.set(xlabel="epoch", ylabel="training loss", yscale="log", title="loss")
    error.plot(epochs, [float(r["val_median_mm"]) for r in rows], marker="o", label="median")
    error.plot(epochs, [float(r["val_p99_mm"]) for r in rows], marker="o", label="p99")
    error.set(xlabel="epoch", ylabel="centre error (mm)", yscale="log", title="held-out frames (all, moving too)")
    error.legend()
    figure.tight_layout()
    figure.savefig(png_path, dpi=110)
    plt.close(figure)


def write_model_card(folder: Path, summary: dict) -> None:
    final, recipe = summary["final"], summary["recipe"]
    (folder / "MODEL_CARD.md").write_text(f"""# Block voter

A fully convolutional network (two levels down and up, {summary['config']['width']} channels at full
resolution) that labels each pixel of the {summary['camera_size'][0]}x{summary['camera_size'][1]} RGB-D frame with a
block colour (or none) and the 3-D offset to that block's centre; `semgoal_perception.estimator` takes the median of
each block's votes. Inputs: colour and each pixel's world point (from depth and the camera's pose).

- **Data**: {summary['images']} frames rendered by `./semgoal train-perception` (the expert working the eight tasks,
  6 frames per episode, task starts from seed {summary['seed']:,}), with the look randomised per episode
  (light strength and tint, camera 2 cm / 2 degrees, block shades, table colour, depth noise and drop-outs; strength
  {summary['randomisation_strength']}). Labels are the simulator's: block centres and per-pixel block ids.
- **Training**: {recipe['epochs']} epochs of {recipe['batch']}-crop batches ({recipe['crop'][0]}x{recipe['crop'][1]},
  {recipe['block_crop_fraction']:.0%} around a block), AdamW with a one-cycle rate up to {recipe['learning_rate']}, seed
  {recipe['seed']}; rendering {summary['render_s']} s, all told {summary['total_s']} s on this machine (2 cores).
- **Held-out frames of training's seeds** (the last {recipe['validation_fraction']:.0%}, moving blocks included):
  median centre error {final['val_median_mm']:.2f} mm, p99 {final['val_p99_mm']:.1f} mm (`curve.csv`, `curve.png`).
- **Accuracy at rest on unseen starts**, literal agreement and latency: `./semgoal eval-perception`, in
  docs/perception.md.
- **Provenance**: commit {summary['provenance']['commit'][:12]}, command `{summary['provenance']['command'].strip()}`.

Limits: the four block colours of the scenes are the classes (a new colour needs new data); the camera's pose must be
known (/tf_static); blocks are taken as cubes of 5 cm.
""")
