"""`./semgoal eval perception [--frames N] [--conditions nominal,randomised,moved,tabletop] [--json]`: how well the
shipped block voter sees, on frames from held-out task starts (seeds from 9,000,000, the tabletop's from 9,700,000;
training's are from 8,000,000 and 8,700,000), one frame at a time (no tracker: what the camera gives at that instant).

- **Poses at rest, blocks in view**: centre error of each block moving slower than the rest threshold whose
  true pixels (the simulator's labels) number at least the estimator's minimum; a block in view but not
  found is counted as missed, not as an error.
- **Literals at rest**: on frames where every block rests and is in view, the scene's predicates on the
  estimated centres against the same predicates on the true ones, overall and per predicate; literals whose
  true geometry lies within 5 mm of a threshold are reported apart.
- **Latency**: wall time of one frame through the voter and the reduction (one torch thread), p50 and p99.

With ``--recordings FILE...`` instead: the voter and the tracker over recorded episodes, against the simulator's poses
recorded beside them (:mod:`semgoal_bringup.experiments.perception_replay`).
"""

from __future__ import annotations

import argparse
import json
import os
import time
from pathlib import Path

import numpy as np

from semgoal_core.arguments import count, names, natural

NEAR_THRESHOLD = 0.005
"""A literal whose true geometry is this close to a threshold (m) counts as a near-threshold case."""
CONDITION_LOOKS = {"nominal": ("nominal", 0.0, False), "randomised": ("nominal", 1.0, False), "moved": ("moved", 0.0, False),
                   "tabletop": ("nominal", 1.0, True)}
"""Measured condition: (camera condition, randomisation strength, the tabletop's tasks rather than the paper's)."""


def measure(frames, estimator, literal_net=None) -> dict:
    """The figures of one set of frames (module doc); with ``literal_net`` (the paper's alternative: literals
    straight from the frame) its agreement on the same literals too."""
    import torch

    from semgoal_core.geometry import TABLE_TOP
    from semgoal_core.settling import REST_SPEED
    from semgoal_core.vocabulary import BLOCK_COLOURS, LAYOUTS, evaluate, threshold_margins
    from semgoal_perception.estimator import MIN_PIXELS
    from semgoal_perception.literal_net import INDEX as ATOM_INDEX
    from semgoal_perception.literal_net import literal_probabilities
    from semgoal_perception.training import frame_camera

    torch.set_num_threads(1)
    colours = list(BLOCK_COLOURS)
    errors, missed, latencies = [], 0, []
    agree: dict[str, list[int]] = {}
    near = {"agree": 0, "total": 0}
    direct: dict[str, list[int]] = {}
    direct_near = {"agree": 0, "total": 0}
    seen = []
    for i in range(len(frames.rgb)):  # timed alone, as the node runs it (the alternative evicts its caches)
        started = time.perf_counter()
        seen.append(estimator.detect(frames.rgb[i], frames.depth[i],
                                     frame_camera(frames.camera[i], frames.world_from_camera[i])))
        latencies.append(time.perf_counter() - started)
    for i, task in enumerate(frames.tasks()):
        found = {d.colour: d for d in seen[i]}
        layout = LAYOUTS[task.scene]
        truth = np.array([frames.centres[i][colours.index(b)] for b in task.blocks])
        at_rest = frames.speeds[i][[colours.index(b) for b in task.blocks]] < REST_SPEED
        in_view = np.array([(frames.labels[i] == colours.index(b) + 1).sum() >= MIN_PIXELS for b in task.blocks])
        for k, block in enumerate(task.blocks):
            if at_rest[k] and in_view[k]:
                detection = found.get(colours.index(block))
                if detection is None:
                    missed += 1
                else:
                    errors.append(float(np.linalg.norm(detection.centre - truth[k])))
        if not (at_rest.all() and in_view.all()) or any(colours.index(b) not in found for b in task.blocks):
            continue
        slots = np.zeros((len(layout.objects), 3))
        present = np.zeros(len(layout.objects), dtype=bool)
        estimate = slots.copy()
        for k, block in enumerate(task.blocks):
            j = layout.objects.index(block)
            slots[j], estimate[j], present[j] = truth[k], found[colours.index(block)].centre, True
        grip, opening = frames.grip[i][:3], float(frames.grip[i][3])
        true_vector = evaluate(layout, slots, grip, opening, TABLE_TOP, present)
        seen_vector = evaluate(layout, estimate, grip, opening, TABLE_TOP, present)
        margins = threshold_margins(layout, slots, grip, TABLE_TOP)
        probabilities = None
        if literal_net is not None:
            probabilities = literal_probabilities(literal_net, frames.rgb[i], frames.depth[i],
                                                  frame_camera(frames.camera[i], frames.world_from_camera[i]), frames.grip[i])
        for entry, (name, args) in enumerate(layout.atoms):
            if not all(present[layout.objects.index(a)] for a in args):
                continue
            near_threshold = margins[entry] <= NEAR_THRESHOLD
            tally(agree, near, name, near_threshold, int(true_vector[entry] == seen_vector[entry]))
            if probabilities is not None:
                said = bool(probabilities[ATOM_INDEX[(name, args)]] > 0.5)
                tally(direct, direct_near, name, near_threshold, int(true_vector[entry] == said))
    errors_mm = 1e3 * np.array(errors)
    return {
        "frames": len(frames.rgb),
        "poses": {"blocks": len(errors), "missed": missed, "median_mm": float(np.median(errors_mm)),
                  "p90_mm": float(np.quantile(errors_mm, 0.9)), "p99_mm": float(np.quantile(errors_mm, 0.99)),
                  "max_mm": float(errors_mm.max())},
        "literals": agreement(agree, near),
        **({"literals_straight_from_the_frame": agreement(direct, direct_near)} if literal_net is not None else {}),
        "latency_ms": {"p50": 1e3 * float(np.median(latencies)), "p99": 1e3 * float(np.quantile(latencies, 0.99))},
    }


def tally(per_predicate: dict[str, list[int]], near: dict[str, int], name: str, near_threshold: bool, same: int) -> None:
    """Count one literal's agreement: apart when its true geometry is near a threshold."""
    if near_threshold:
        near["agree"] += same
        near["total"] += 1
    else:
        per_predicate.setdefault(name, []).append(same)


def agreement(per_predicate: dict[str, list[int]], near: dict[str, int]) -> dict:
    """Overall, per predicate and near-threshold agreement, with Wilson intervals."""
    from semgoal_bringup.experiments.evaluation import wilson_interval

    def row(agreed: int, total: int) -> dict:
        return {"agree": agreed, "total": total, "rate": agreed / max(total, 1),
                "wilson95": wilson_interval(agreed, total) if total else None}

    every = [v for values in per_predicate.values() for v in values]
    return {"overall": row(int(sum(every)), len(every)),
            "per_predicate": {name: row(int(sum(v)), len(v)) for name, v in sorted(per_predicate.items())},
            "near_threshold": row(near["agree"], near["total"])}


def _rate_cell(row: dict | None) -> str:
    """``rate % (total)``, or a dash where no literal of the kind was measured."""
    return f"{100 * row['rate']:.2f} ({row['total']})" if row and row["total"] else "-"


PREDICATES = ("close", "above", "holding", "in_bin")


def table(results: dict) -> str:
    lines = ["| condition | blocks | missed | median mm | p99 mm | literals | "
             + " | ".join(PREDICATES) + " | near 5 mm | p50 ms | p99 ms |", "|---" * 13 + "|"]
    for condition, r in results.items():
        poses = r["poses"]
        for approach, key in (("poses, then predicates", "literals"),
                              ("literals straight from the frame", "literals_straight_from_the_frame")):
            if key not in r:
                continue
            literals = r[key]
            cells = [f"{condition}: {approach}", poses["blocks"], poses["missed"], f"{poses['median_mm']:.2f}",
                     f"{poses['p99_mm']:.2f}", _rate_cell(literals["overall"]),
                     *(_rate_cell(literals["per_predicate"].get(name)) for name in PREDICATES),
                     _rate_cell(literals["near_threshold"]), f"{r['latency_ms']['p50']:.1f}", f"{r['latency_ms']['p99']:.1f}"]
            if key != "literals":
                cells[1:5] = ["-"] * 4
                cells[-2:] = ["-", "-"]
            lines.append("| " + " | ".join(map(str, cells)) + " |")
    return "\n".join(lines)


def figure(frames, estimator, path: Path, count: int = 4) -> None:
    """Frames of different tasks with the estimated centres (crosses) and the true ones (circles) drawn on
    them, and what the voter labels each pixel beside each."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from semgoal_core.vocabulary import BLOCK_COLOURS
    from semgoal_perception.training import frame_camera

    colours = list(BLOCK_COLOURS)
    labels_map = matplotlib.colors.ListedColormap([(0.9, 0.9, 0.9), *(rgba[:3] for rgba in BLOCK_COLOURS.values())])
    chosen = [int(np.flatnonzero(frames.task == task)[3]) for task in np.unique(frames.task)][::2][:count]
    plot, axes = plt.subplots(2, len(chosen), figsize=(3.2 * len(chosen), 5.0))
    for column, i in enumerate(chosen):
        camera = frame_camera(frames.camera[i], frames.world_from_camera[i])
        pixels = estimator.label(frames.rgb[i], frames.depth[i], camera)
        top, bottom = axes[0, column], axes[1, column]
        top.imshow(frames.rgb[i])
        for found in pixels.detections():
            u, v = camera.project(found.centre[None])[0]
            top.plot(u, v, "x", color="black", markersize=9, markeredgewidth=2)
            top.annotate(colours[found.colour], (u, v), xytext=(4, -6), textcoords="offset points", fontsize=7)
        truth = frames.centres[i][np.isfinite(frames.centres[i]).all(axis=1)]
        u, v = camera.project(truth).T
        top.plot(u, v, "o", markerfacecolor="none", color="white", markersize=10)
        bottom.imshow(pixels.labels, cmap=labels_map, vmin=0, vmax=len(colours), interpolation="nearest")
        for axis in (top, bottom):
            axis.set_xticks([])
            axis.set_yticks([])
    axes[0, 0].set_ylabel("frame: estimate x, truth o")
    axes[1, 0].set_ylabel("the voter's labels")
    plot.tight_layout()
    plot.savefig(path, dpi=130)
    plt.close(plot)


def replay_recordings(paths: list[Path], estimator, as_json: bool, parser: argparse.ArgumentParser) -> int:
    """``--recordings``: each file's :class:`~semgoal_bringup.experiments.perception_replay.TrackingScore`, and all."""
    from mcap.exceptions import McapError

    from semgoal_bringup.experiments.perception_replay import TrackingScore, replay_table, score_recording, summed

    scores: dict[str, TrackingScore] = {}  # by the path as given: recordings of two runs share their names
    for path in paths:
        if not path.is_file():
            parser.error(f"no such file: {path}")
        try:
            scores[str(path)] = score_recording(path, estimator)
        except McapError as error:
            parser.error(f"{path}: not an MCAP recording ({error})")
        if not scores[str(path)].frames:
            parser.error(f"{path}: no camera frame with its world state (record an episode run on the camera)")
    print(json.dumps({"recordings": {name: s.as_dict() for name, s in scores.items()},
                      "all": summed(scores.values()).as_dict()})
          if as_json else replay_table(scores))
    return 0


def main(argv: list[str]) -> int:
    os.environ.setdefault("MUJOCO_GL", "osmesa")
    from semgoal_bringup.experiments.perception_training import cached_frames
    from semgoal_perception.estimator import BlockEstimator
    from semgoal_perception.literal_net import load_literal_net
    from semgoal_ros.package_data import share_path
    from semgoal_sim.perception_data import MEASUREMENT_SEED, TABLETOP_MEASUREMENT_SEED

    parser = argparse.ArgumentParser(prog="semgoal eval perception", description=__doc__.split("\n\n")[0])
    parser.add_argument("--frames", type=count, default=400)
    parser.add_argument("--seed", type=natural, default=MEASUREMENT_SEED, help="the paper's task starts: seed + episode")
    parser.add_argument("--tabletop-seed", type=natural, default=TABLETOP_MEASUREMENT_SEED,
                        help="the tabletop's task starts: seed + episode")
    parser.add_argument("--conditions", type=names, default=",".join(CONDITION_LOOKS), help=f"of {', '.join(CONDITION_LOOKS)}")
    parser.add_argument("--model-dir", type=Path, help="exported voter (default: the shipped one)")
    parser.add_argument("--cache", type=Path, default=Path("runs/perception"))
    parser.add_argument("--json", action="store_true")
    parser.add_argument("--figure", type=Path, help="also draw frames of a condition with the estimates (PNG)")
    parser.add_argument("--figure-of", help="the condition drawn (default: the first)")
    parser.add_argument("--recordings", type=Path, nargs="+", metavar="FILE",
                        help="instead: the voter and the tracker over these MCAP recordings of episodes on the camera, "
                             "beside the simulator's poses recorded with them")
    args = parser.parse_args(argv)
    folder = args.model_dir or share_path("semgoal_perception", "models", "block_voter")
    estimator = BlockEstimator.load(folder)
    if args.recordings:
        return replay_recordings(args.recordings, estimator, args.json, parser)
    literals_folder = folder.parent / "literal_net"
    literal_net = load_literal_net(literals_folder) if (literals_folder / "literal_net.pt").exists() else None
    size = tuple(json.loads((folder / "voter.json").read_text())["camera_size"])
    results = {}
    for condition in args.conditions:
        if condition not in CONDITION_LOOKS:
            parser.error(f"unknown condition {condition!r}: conditions are {', '.join(CONDITION_LOOKS)}")
        look, strength, tabletop = CONDITION_LOOKS[condition]
        frames = cached_frames(args.frames, args.tabletop_seed if tabletop else args.seed, size, strength, args.cache,
                               look, tabletop=tabletop)
        results[condition] = measure(frames, estimator, None if tabletop else literal_net)  # it knows the paper's scenes
        if args.figure and condition == (args.figure_of or args.conditions[0]):
            figure(frames, estimator, args.figure)
    print(json.dumps(results, indent=2) if args.json else table(results))
    return 0
