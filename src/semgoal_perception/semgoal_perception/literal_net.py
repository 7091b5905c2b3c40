"""The paper's alternative, kept to be measured beside the block voter: a network from the frame (and the arm's
own grip and finger opening) straight to the probability of every literal, no poses in between. Trained on
the same labelled frames; ``eval-perception`` puts its literal agreement beside poses-then-predicates."""

from __future__ import annotations

import json
import time
from pathlib import Path

import numpy as np
import torch
from torch import nn
from torch.nn import functional

from semgoal_core.geometry import TABLE_TOP
from semgoal_core.vocabulary import BLOCK_COLOURS, LAYOUTS, PAPER_SCENES, evaluate
from semgoal_perception.geometry import PinholeCamera
from semgoal_perception.network import INPUT_CHANNELS, network_input

ATOMS: tuple[tuple[str, tuple[str, ...]], ...] = tuple(sorted({atom for scene in PAPER_SCENES
                                                               for atom in LAYOUTS[scene].atoms}))
"""Every grounded literal of the paper's scenes, whose frames it is trained and measured on: the network's outputs."""
INDEX = {atom: i for i, atom in enumerate(ATOMS)}


class LiteralNet(nn.Module):
    """Four strided convolutions, global average and max pooling, and a head that also takes the arm's grip
    position (about the table) and finger opening."""

    def __init__(self, width: int = 24) -> None:
        super().__init__()
        layers, channels = [], INPUT_CHANNELS
        for out in (width, 2 * width, 3 * width, 3 * width):
            layers += [nn.Conv2d(channels, out, 3, stride=2, padding=1), nn.BatchNorm2d(out), nn.ReLU(inplace=True)]
            channels = out
        self.encoder = nn.Sequential(*layers)
        self.head = nn.Sequential(nn.Linear(2 * channels + 4, 128), nn.ReLU(inplace=True), nn.Linear(128, len(ATOMS)))

    def forward(self, x: torch.Tensor, arm: torch.Tensor) -> torch.Tensor:
        features = self.encoder(x)
        pooled = torch.cat([features.mean((2, 3)), features.amax((2, 3)), arm], 1)
        return self.head(pooled)


def arm_input(grip: np.ndarray) -> np.ndarray:
    """(4,) the grip site about the table (dm) and the finger opening (cm): inputs of order one."""
    return np.array([*(10.0 * (grip[:3] - np.array([1.3, 0.75, TABLE_TOP]))), 100.0 * grip[3]], dtype=np.float32)


def targets(frames, tasks: list) -> tuple[np.ndarray, np.ndarray]:
    """(N, atoms) truth and mask (the atoms of the frame's scene whose blocks are present), from the labels."""
    colours = list(BLOCK_COLOURS)
    truth = np.zeros((len(frames.rgb), len(ATOMS)), dtype=np.float32)
    mask = np.zeros_like(truth)
    for i, task in enumerate(tasks):
        layout = LAYOUTS[task.scene]
        slots, present = np.zeros((len(layout.objects), 3)), np.zeros(len(layout.objects), dtype=bool)
        for block in task.blocks:
            slots[layout.objects.index(block)], present[layout.objects.index(block)] = frames.centres[i][colours.index(block)], True
        vector = evaluate(layout, slots, frames.grip[i][:3], float(frames.grip[i][3]), TABLE_TOP, present)
        for entry, (name, args) in enumerate(layout.atoms):
            if all(present[layout.objects.index(a)] for a in args):
                truth[i, INDEX[(name, args)]] = vector[entry]
                mask[i, INDEX[(name, args)]] = 1.0
    return truth, mask


def inputs(frames) -> tuple[torch.Tensor, torch.Tensor]:
    xs, arms = [], []
    for i in range(len(frames.rgb)):
        camera = PinholeCamera(*map(float, frames.camera[i][:4]), frames.world_from_camera[i])
        points, valid = camera.world_points(frames.depth[i])
        xs.append(network_input(frames.rgb[i], points, valid))
        arms.append(arm_input(frames.grip[i]))
    return torch.from_numpy(np.stack(xs)), torch.from_numpy(np.stack(arms))


def train_literal_net(frames, tasks: list, out: Path, epochs: int = 20, batch: int = 32, seed: int = 0) -> dict:
    """Train on ``frames`` (whose tasks are ``tasks``), write ``literal_net.pt`` and ``literal_net.json``."""
    torch.manual_seed(seed)
    rng = np.random.default_rng(seed)
    x, arm = inputs(frames)
    truth, mask = (torch.from_numpy(a) for a in targets(frames, tasks))
    net = LiteralNet()
    optimiser = torch.optim.AdamW(net.parameters(), lr=3e-3, weight_decay=1e-4)
    steps = epochs * (len(x) // batch)
    schedule = torch.optim.lr_scheduler.OneCycleLR(optimiser, 3e-3, total_steps=steps)
    started, losses = time.perf_counter(), []
    for _ in range(epochs):
        order = rng.permutation(len(x))
        for start in range(0, len(order) - batch + 1, batch):
            b = torch.from_numpy(order[start: start + batch])
            loss = (functional.binary_cross_entropy_with_logits(net(x[b], arm[b]), truth[b], reduction="none")
                     * mask[b]).sum() / mask[b].sum()
            optimiser.zero_grad()
            loss.backward()
            optimiser.step()
            schedule.step()
            losses.append(loss.item())
    out.mkdir(parents=True, exist_ok=True)
    torch.save(net.state_dict(), out / "literal_net.pt")
    summary = {"atoms": [f"{n}({','.join(a)})" for n, a in ATOMS], "epochs": epochs, "batch": batch, "seed": seed,
               "frames": len(x), "final_loss": float(np.mean(losses[-20:])), "wall_s": round(time.perf_counter() - started, 1)}
    (out / "literal_net.json").write_text(json.dumps(summary, indent=2) + "\n")
    return summary


def load_literal_net(folder: Path) -> LiteralNet:
    net = LiteralNet()
    net.load_state_dict(torch.load(folder / "literal_net.pt", map_location="cpu", weights_only=True))
    return net.eval()


@torch.inference_mode()
def literal_probabilities(net: LiteralNet, rgb: np.ndarray, depth: np.ndarray, camera: PinholeCamera,
                          grip: np.ndarray) -> np.ndarray:
    """(atoms,) the probability of each of :data:`ATOMS` in one frame; ``grip``: position and finger opening."""
    points, valid = camera.world_points(depth)
    x = torch.from_numpy(network_input(rgb, points, valid))[None]
    return torch.sigmoid(net(x, torch.from_numpy(arm_input(grip))[None]))[0].numpy()
