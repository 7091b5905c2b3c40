"""`./semgoal train perception [--images N] [--seed S] [--two-arm-images N] [--tabletop-images N]`: render labelled frames
(the expert at work under a randomised look; some with a second Fetch across the table, some on the tabletop with its
eight colours and towers), train the block voter on them and export it beside its model card.

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
TWO_ARM_TASKS = ("DC-2", "DC-3", "DC-4")
"""The desk's tasks, worked by two arms for the frames with a second Fetch in view."""
TWO_ARM_STEPS = 60
"""A two-arm episode's frames are drawn from its first this many control steps (the shortest, DC-2, takes about 55)."""


def cached_frames(count: int, seed: int, size: tuple[int, int], strength: float, cache: Path,
                  condition: str = "nominal", arms: int = 1, tabletop: bool = False, repaint: bool = False):
    """Labelled frames from the cache, rendered first when missing: of the paper's eight tasks, or with ``tabletop``
    of the tabletop's (``arms`` 2: :func:`two_arm_frames`, the desk's); ``repaint``: the blocks' colours shuffled per
    episode."""
    from semgoal_core.tasks import TABLETOP_TASKS, TASKS
    from semgoal_sim.perception_data import LabelledFrames, labelled_frames

    kind = "frames" if arms == 1 else "two-arm-frames"
    kind = f"tabletop-{kind}" if tabletop else kind
    kind = f"repainted-{kind}" if repaint else kind
    path = cache / f"{kind}-seed{seed}-n{count}-{size[0]}x{size[1]}-s{strength:g}-{condition}.npz"
    if path.exists():
        return LabelledFrames.load(path)
    tasks = tuple(TABLETOP_TASKS if tabletop else TASKS)
    if arms == 1:
        frames = labelled_frames(count, seed, size, strength, condition, progress=True, tasks=tasks, repaint=repaint)
    else:
        frames = two_arm_frames(count, seed, size, strength)
    cache.mkdir(parents=True, exist_ok=True)
    frames.save(path)
    return frames


def two_arm_frames(count: int, seed: int, size: tuple[int, int], strength: float):
    """``count`` labelled frames of the desk with a second Fetch across the table, both arms working the desk's tasks
    in turn under the scripted expert as ``eval arms`` runs them (the planner's shares, the guard), from starts
    ``seed + episode``, a randomised look per episode: the voter must not take the other robot for a block."""
    import numpy as np
    from tqdm import tqdm

    from semgoal_bringup.experiments.episodes import make_agent
    from semgoal_core.tasks import get_task
    from semgoal_policy.expert_actor import EXPERT
    from semgoal_sim.camera import CONDITIONS, Appearance, RgbdCamera
    from semgoal_sim.perception_data import FRAME_TASKS, FRAMES_PER_EPISODE, frame_row, stack_rows

    agent = make_agent("hierarchical", "desk_cleanup", Path(EXPERT), arms=2)
    cameras: dict[int, RgbdCamera] = {}
    rows: list[tuple] = []
    bar = tqdm(total=count, desc="rendering two-arm frames", unit="frame")
    episode = 0
    while len(rows) < count:
        task, start = get_task(TWO_ARM_TASKS[episode % len(TWO_ARM_TASKS)]), seed + episode
        rng = np.random.default_rng([seed, episode])
        look = Appearance.randomised(rng, strength, CONDITIONS["nominal"].placement)
        chosen = set(rng.choice(np.arange(1, TWO_ARM_STEPS + 1), size=FRAMES_PER_EPISODE, replace=False).tolist())

        def record(world, task=task, start=start, look=look, chosen=chosen) -> None:
            if world.step_count not in chosen:
                return
            if id(world) not in cameras:
                cameras[id(world)] = RgbdCamera(world, *size)
            camera = cameras[id(world)]
            if camera.appearance is not look:
                camera.set_appearance(look, noise_seed=start)
            rows.append((*frame_row(camera.frame(labels=True), world.snapshot(), world.blocks), FRAME_TASKS.index(task.name)))
            bar.update(1)

        agent.run_goals(task.initial_state(start)[0], (task.name,), start, label=task.name, on_step=record)
        episode += 1
    bar.close()
    for camera in cameras.values():
        camera.close()
    return stack_rows(rows[:count])


def interleaved(first, second):
    """Two sets of labelled frames as one, the second's spread evenly through the first's (training holds out the
    last frames: both kinds are among them)."""
    import numpy as np

    from semgoal_sim.perception_data import LabelledFrames

    order = np.argsort(np.concatenate([np.arange(len(first.rgb)) / len(first.rgb),
                                       np.arange(len(second.rgb)) / len(second.rgb)]), kind="stable")
    return LabelledFrames(**{name: np.concatenate([getattr(first, name), getattr(second, name)])[order]
                             for name in LabelledFrames.__dataclass_fields__})


def main(argv: list[str]) -> int:
    os.environ.setdefault("MUJOCO_GL", "osmesa")
    from semgoal_perception.network import VoterConfig
    from semgoal_perception.training import VoterRecipe, train_voter
    from semgoal_ros.package_data import share_path

    recipe = json.loads(share_path("semgoal_perception", "recipes", "block_voter.json").read_text())
    parser = argparse.ArgumentParser(prog="semgoal train perception", description=__doc__.split("\n\n")[0])
    parser.add_argument("--images", type=count, default=recipe["images"], help="labelled frames to render and train on")
    parser.add_argument("--seed", type=natural, default=recipe["seed"], help="task starts seed + episode (8,000,000: training's range)")
    parser.add_argument("--two-arm-images", type=natural, default=recipe["two_arm_images"],
                        help="frames more with a second Fetch across the table (the desk's tasks, both arms at work)")
    parser.add_argument("--two-arm-seed", type=natural, default=recipe["two_arm_seed"],
                        help="their task starts: seed + episode")
    parser.add_argument("--tabletop-images", type=natural, default=recipe["tabletop_images"],
                        help="frames more of the tabletop's tasks (eight colours, towers)")
    parser.add_argument("--tabletop-seed", type=natural, default=recipe["tabletop_seed"],
                        help="their task starts: seed + episode")
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
    if args.two_arm_images:
        frames = interleaved(frames, cached_frames(args.two_arm_images, args.two_arm_seed, size,
                                                   recipe["randomisation_strength"], args.cache, arms=2))
    if args.tabletop_images:
        frames = interleaved(frames, cached_frames(args.tabletop_images, args.tabletop_seed, size,
                                                   recipe["randomisation_strength"], args.cache, tabletop=True,
                                                   repaint=recipe["tabletop_repaint"]))
    rendered = time.perf_counter() - started
    if args.literal_net:
        return train_literal_alternative(frames, args.out.parent / "literal_net", args.epochs, argv)
    voter = {f.name: recipe["voter"][f.name] for f in fields(VoterRecipe)}
    voter.update(epochs=args.epochs, crop=tuple(voter["crop"]))
    summary = train_voter(frames, args.out, VoterRecipe(**voter), VoterConfig(**recipe["network"]))
    summary.update(images=args.images, seed=args.seed, two_arm_images=args.two_arm_images,
                   two_arm_seed=args.two_arm_seed, tabletop_images=args.tabletop_images,
                   tabletop_seed=args.tabletop_seed, tabletop_repaint=recipe["tabletop_repaint"],
                   camera_size=list(size),
                   randomisation_strength=recipe["randomisation_strength"],
                   render_s=round(rendered, 1), total_s=round(time.perf_counter() - started, 1),
                   provenance=provenance("./semgoal train-perception " + " ".join(argv), args.seed))
    (args.out / "voter.json").write_text(json.dumps(summary, indent=2) + "\n")
    plot_curve(args.out / "curve.csv", args.out / "curve.png")
    write_model_card(args.out, summary)
    print(json.dumps(summary["final"], indent=2))
    return 0


def train_literal_alternative(frames, out: Path, epochs: int, argv: list[str]) -> int:
    """The paper's alternative on the same frames of the paper's scenes, exported beside the voter (``eval-perception``
    compares them)."""
    import numpy as np

    from semgoal_core.vocabulary import PAPER_SCENES
    from semgoal_perception.literal_net import train_literal_net

    frames = frames.where(np.array([task.scene in PAPER_SCENES for task in frames.tasks()]))
    summary = train_literal_net(frames, frames.tasks(), out, epochs=epochs)
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
    repainted = (", the blocks' colours shuffled per episode so that every colour is seen in every place, the bin too"
                 if summary.get("tabletop_repaint") else "")
    (folder / "MODEL_CARD.md").write_text(f"""# Block voter

A fully convolutional network (two levels down and up, {summary['config']['width']} channels at full
resolution) that labels each pixel of the {summary['camera_size'][0]}x{summary['camera_size'][1]} RGB-D frame with a
block colour (or none) and the 3-D offset to that block's centre; `semgoal_perception.estimator` takes the median of
each block's votes. Inputs: colour and each pixel's world point (from depth and the camera's pose).

- **Data**: {summary['images']} frames rendered by `./semgoal train-perception` (the expert working the eight tasks,
  6 frames per episode, task starts from seed {summary['seed']:,}) and {summary.get('two_arm_images', 0)} more with a
  second Fetch across the table (both arms working the desk's tasks under the expert, task starts from seed
  {summary.get('two_arm_seed', 0):,}: its blue links are not a blue block) and {summary.get('tabletop_images', 0)} of the
  tabletop (its eleven tasks, eight colours and towers, task starts from seed
  {summary.get('tabletop_seed', 0):,}{repainted}), with the look randomised per episode (light
  strength and tint, camera 2 cm / 2 degrees, block shades, table colour, depth noise and drop-outs; strength
  {summary['randomisation_strength']}). Labels are the simulator's: block centres and per-pixel block ids.
- **Training**: {recipe['epochs']} epochs of {recipe['batch']}-crop batches ({recipe['crop'][0]}x{recipe['crop'][1]},
  {recipe['block_crop_fraction']:.0%} around a block), AdamW with a one-cycle rate up to {recipe['learning_rate']}, seed
  {recipe['seed']}; the frames rendered (or read from the cache) in {summary['render_s']} s, all told {summary['total_s']} s on
  this machine (2 cores).
- **Held-out frames of training's seeds** (the last {recipe['validation_fraction']:.0%}, moving blocks included):
  median centre error {final['val_median_mm']:.2f} mm, p99 {final['val_p99_mm']:.1f} mm (`curve.csv`, `curve.png`).
- **Accuracy at rest on unseen starts**, literal agreement and latency: `./semgoal eval-perception`, in
  docs/perception.md.
- **Provenance**: commit {summary['provenance']['commit'][:12]}, command `{summary['provenance']['command'].strip()}`.

Limits: the block colours it was trained on ({summary['config']['classes'] - 1}) are its classes (a new colour needs new
data); the camera's pose must be known (/tf_static); blocks are taken as cubes of 5 cm.
""")
