"""Training the block voter on labelled frames (arrays from ``semgoal_sim.perception_data``): per-pixel
cross-entropy on the labels and a robust loss on the offsets of block pixels; curves per epoch, exported
weights beside their architecture. No MuJoCo: the frames arrive as arrays."""

from __future__ import annotations

import csv
import json
import time
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np
import torch
from torch.nn import functional

from semgoal_perception.estimator import BlockEstimator, detections
from semgoal_perception.geometry import PinholeCamera
from semgoal_perception.network import OFFSET_SCALE, BlockVoter, VoterConfig, network_input


@dataclass(frozen=True)
class VoterRecipe:
    """How the voter is trained (saved with it)."""

    epochs: int = 14
    batch: int = 16
    learning_rate: float = 3e-3
    background_weight: float = 0.25
    """Cross-entropy weight of no-block pixels (they are ~98 % of a frame)."""
    offset_weight: float = 1.0
    validation_fraction: float = 0.1
    """The last frames (whole episodes) are held out for the curve's centre error."""
    crop: tuple[int, int] = (64, 80)
    """Training crops (height, width): a quarter of a frame, mostly around a block (4x faster than whole
    frames; the network is fully convolutional, so it runs on whole frames after)."""
    block_crop_fraction: float = 0.8
    """Share of crops centred near a block pixel; the rest fall anywhere."""
    seed: int = 0


def frame_camera(camera: np.ndarray, world_from_camera: np.ndarray) -> PinholeCamera:
    return PinholeCamera(*map(float, camera[:4]), world_from_camera)


def tensors(frames) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor, np.ndarray, np.ndarray]:
    """Network inputs (N, 7, H, W), labels (N, H, W), offsets to the labelled block's centre in half block
    edges (N, 3, H, W), and the points and valid masks (for the votes)."""
    inputs, offsets, points_all, valid_all = [], [], [], []
    for i in range(len(frames.rgb)):
        points, valid = frame_camera(frames.camera[i], frames.world_from_camera[i]).world_points(frames.depth[i])
        inputs.append(network_input(frames.rgb[i], points, valid))
        centres = np.nan_to_num(np.vstack([np.zeros((1, 3)), frames.centres[i]]))
        target = (centres[frames.labels[i]] - points) / OFFSET_SCALE
        target[(frames.labels[i] == 0) | ~valid] = 0.0
        offsets.append(target.transpose(2, 0, 1).astype(np.float32))
        points_all.append(points)
        valid_all.append(valid)
    return (torch.from_numpy(np.stack(inputs)), torch.from_numpy(frames.labels.astype(np.int64)),
            torch.from_numpy(np.stack(offsets)), np.stack(points_all), np.stack(valid_all))


def centre_errors(estimator: BlockEstimator, frames, indices: np.ndarray, points: np.ndarray,
                  valid: np.ndarray, inputs: torch.Tensor) -> np.ndarray:
    """Centre errors (m) of the blocks found in the frames ``indices`` (labelled colours only)."""
    errors = []
    with torch.inference_mode():
        for i in indices:
            logits, offsets = estimator.network(inputs[i: i + 1])
            labels = logits[0].argmax(0).numpy()
            votes = points[i] + offsets[0].permute(1, 2, 0).numpy() * OFFSET_SCALE
            for found in detections(labels[valid[i]], votes[valid[i]]):
                truth = frames.centres[i][found.colour]
                if np.isfinite(truth).all():
                    errors.append(np.linalg.norm(found.centre - truth))
    return np.array(errors)


def crop_corners(labels: torch.Tensor, batch: np.ndarray, recipe: VoterRecipe,
                 rng: np.random.Generator) -> list[tuple[int, int]]:
    """Top-left corners of one training crop per frame of ``batch``."""
    height, width = labels.shape[1:]
    ch, cw = recipe.crop
    corners = []
    for i in batch:
        rows, cols = np.nonzero(labels[i].numpy())
        if len(rows) and rng.random() < recipe.block_crop_fraction:
            k = rng.integers(len(rows))
            top, left = rows[k] - rng.integers(ch), cols[k] - rng.integers(cw)
        else:
            top, left = rng.integers(height - ch + 1), rng.integers(width - cw + 1)
        corners.append((int(np.clip(top, 0, height - ch)), int(np.clip(left, 0, width - cw))))
    return corners


def _crops(tensor: torch.Tensor, batch: np.ndarray, corners: list[tuple[int, int]], size: tuple[int, int]) -> torch.Tensor:
    ch, cw = size
    return torch.stack([tensor[i, ..., top: top + ch, left: left + cw] for i, (top, left) in zip(batch, corners, strict=True)])


def train_voter(frames, out: Path, recipe: VoterRecipe | None = None, config: VoterConfig | None = None,
                progress: bool = True) -> dict:
    """Train on ``frames``, write ``voter.pt``, ``voter.json`` and ``curve.csv`` to ``out``; the summary."""
    recipe, config = recipe or VoterRecipe(), config or VoterConfig()
    from tqdm import tqdm

    torch.manual_seed(recipe.seed)
    rng = np.random.default_rng(recipe.seed)
    inputs, labels, offsets, points, valid = tensors(frames)
    count = len(inputs)
    held = max(1, int(count * recipe.validation_fraction))
    train_idx, val_idx = np.arange(count - held), np.arange(count - held, count)
    network = BlockVoter(config)
    optimiser = torch.optim.AdamW(network.parameters(), lr=recipe.learning_rate, weight_decay=1e-4)
    steps = recipe.epochs * (len(train_idx) // recipe.batch)
    schedule = torch.optim.lr_scheduler.OneCycleLR(optimiser, recipe.learning_rate, total_steps=steps)
    weights = torch.ones(config.classes)
    weights[0] = recipe.background_weight
    out.mkdir(parents=True, exist_ok=True)
    rows, started = [], time.perf_counter()
    bar = tqdm(total=steps, desc="training the block voter", unit="batch", disable=not progress)
    for epoch in range(1, recipe.epochs + 1):
        network.train()
        order = rng.permutation(train_idx)
        losses = []
        for start in range(0, len(order) - recipe.batch + 1, recipe.batch):
            batch = order[start: start + recipe.batch]
            corners = crop_corners(labels, batch, recipe, rng)
            x, target, offset = (_crops(t, batch, corners, recipe.crop) for t in (inputs, labels, offsets))
            logits, predicted = network(x)
            mask = (target > 0) & (x[:, 6] > 0)
            loss = functional.cross_entropy(logits, target, weight=weights)
            if mask.any():
                error = functional.smooth_l1_loss(predicted.permute(0, 2, 3, 1)[mask],
                                                  offset.permute(0, 2, 3, 1)[mask], beta=0.1)
                loss = loss + recipe.offset_weight * error
            optimiser.zero_grad()
            loss.backward()
            optimiser.step()
            schedule.step()
            losses.append(loss.item())
            bar.update(1)
        network.eval()
        errors = centre_errors(BlockEstimator(network), frames, val_idx, points, valid, inputs)
        median, p99 = (1e3 * float(np.quantile(errors, q)) if len(errors) else float("nan") for q in (0.5, 0.99))
        rows.append({"epoch": epoch, "loss": float(np.mean(losses)), "val_median_mm": median, "val_p99_mm": p99,
                     "val_blocks_found": len(errors), "wall_s": time.perf_counter() - started})
        bar.set_postfix(loss=f"{rows[-1]['loss']:.3f}", median_mm=f"{rows[-1]['val_median_mm']:.2f}")
    bar.close()
    torch.save(network.state_dict(), out / "voter.pt")
    summary = {"config": asdict(config), "recipe": asdict(recipe), "frames": count, "final": rows[-1]}
    (out / "voter.json").write_text(json.dumps(summary, indent=2) + "\n")
    with (out / "curve.csv").open("w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    return summary
