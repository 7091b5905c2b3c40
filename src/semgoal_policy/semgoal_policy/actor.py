"""The goal-conditioned actor: its network, and the exported form the policy node and evaluation load.

An exported actor is a directory with ``actor.pt`` (a plain ``state_dict`` plus the observation
normaliser; no SB3, no pickled classes) and ``actor.json`` (the observation/goal layout it was trained
on, with any derived features appended to the observation, training steps, wall time, command,
evaluation). Loading compares the stored layout with :func:`semgoal_core.layout.describe` for the current
code and refuses a mismatch.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import torch
from torch import nn

from semgoal_core import features, layout
from semgoal_ros.package_data import share_path

HIDDEN = (256, 256)
LOG_STD_MIN, LOG_STD_MAX = -5.0, 2.0
"""Clamp of the Gaussian's log std before tanh; 2 is SB3's and CleanRL's upper bound (see ``SacConfig.log_std_max``)."""
HALF_LOG_TWO_PI = 0.5 * math.log(2 * math.pi)
OBS_CLIP = 5.0
"""Normalised observations are clipped to +-5 standard deviations (as in the HER baselines)."""
def models_dir() -> Path:
    """The shipped actors as installed: ``share/semgoal_policy/models/<scene>/`` (hierarchical),
    ``<scene>-<agent>/`` (baselines) and ``seeds/<name>/seedS/`` (the pooled training seeds)."""
    return share_path("semgoal_policy", "models")


class LayoutMismatchError(RuntimeError):
    """The exported actor was trained on another observation or goal layout than the code defines."""


def mlp(inputs: int, outputs: int, hidden: tuple[int, ...] = HIDDEN) -> nn.Sequential:
    """Linear layers with ReLUs between them. A ReLU overwrites its layer's output, which nothing else reads (a
    linear layer's backward needs its input, not its output): the same values and gradients without a new tensor
    per layer, about 7 % of a bf16 SAC update."""
    layers: list[nn.Module] = []
    for width in hidden:
        layers += [nn.Linear(inputs, width), nn.ReLU(inplace=True)]
        inputs = width
    return nn.Sequential(*layers, nn.Linear(inputs, outputs))


class Normaliser(nn.Module):
    """Running mean and standard deviation of observations; part of the actor's state."""

    def __init__(self, size: int) -> None:
        super().__init__()
        self.register_buffer("count", torch.tensor(1e-4, dtype=torch.float64))
        self.register_buffer("mean", torch.zeros(size, dtype=torch.float64))
        self.register_buffer("var", torch.ones(size, dtype=torch.float64))

    def update(self, batch: np.ndarray) -> None:
        """Chan's parallel update of mean and variance with a batch of observations (none: no change)."""
        x = torch.as_tensor(batch, dtype=torch.float64).reshape(-1, self.mean.numel())
        if not len(x):
            return
        n, mean, var = x.shape[0], x.mean(0), x.var(0, unbiased=False)
        delta, total = mean - self.mean, self.count + n
        self.var.copy_((self.var * self.count + var * n + delta**2 * self.count * n / total) / total)
        self.mean.add_(delta * n / total)
        self.count.fill_(total)

    def forward(self, obs: torch.Tensor) -> torch.Tensor:
        std = torch.sqrt(self.var + 1e-8).float()
        return torch.clamp((obs - self.mean.float()) / std, -OBS_CLIP, OBS_CLIP)


class GaussianPolicy(nn.Module):
    """A squashed Gaussian policy over (observation, goal): subclasses give ``forward`` -> (mean, log_std) of the
    pre-tanh Gaussian, ``features`` (the critic's input, ``feature_size`` wide), ``net`` (every trained weight)
    and ``normaliser``."""

    feature_size: int

    def sample(self, obs: torch.Tensor, goal: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
        """(action, log_prob, pre-tanh mean): reparameterised tanh-Gaussian (SAC, appendix C)."""
        return self.squashed(*self(obs, goal))

    @staticmethod
    def squashed(mean: torch.Tensor, log_std: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
        """:meth:`sample` from the pre-tanh Gaussian's ``mean`` and ``log_std``. The Gaussian's log density at
        ``mean + std * noise`` is written out (``-noise²/2 - log std - log √(2π)``): the same value and gradients as
        ``torch.distributions.Normal.log_prob``, without building a distribution each update."""
        noise = torch.randn_like(mean)
        action = torch.tanh(mean + log_std.exp() * noise)
        log_prob = -0.5 * noise.pow(2) - log_std - HALF_LOG_TWO_PI - torch.log1p(-action.pow(2) + 1e-6)
        return action, log_prob.sum(-1), mean

    @torch.inference_mode()
    def act(self, obs: np.ndarray, goal: np.ndarray, noise: np.ndarray | None = None) -> np.ndarray:
        """Action(s) in [-1, 1] for numpy input (one row or a batch): the policy's mean, or with ``noise``
        (standard normal, the action's shape) a sample of the policy's Gaussian, reproducible from it."""
        mean, log_std = self(torch.as_tensor(obs, dtype=torch.float32), torch.as_tensor(goal, dtype=torch.float32))
        if noise is not None:
            mean = mean + log_std.exp() * torch.as_tensor(noise, dtype=torch.float32)
        return torch.tanh(mean).numpy()


class Actor(GaussianPolicy):
    """Squashed Gaussian policy over (normalised observation, goal); goals are 0/1 and used as is."""

    def __init__(self, obs_size: int, goal_size: int, hidden: tuple[int, ...] = HIDDEN,
                 log_std_max: float = LOG_STD_MAX) -> None:
        super().__init__()
        self.obs_size, self.goal_size, self.log_std_max = obs_size, goal_size, log_std_max
        self.feature_size = obs_size + goal_size
        self.normaliser = Normaliser(obs_size)
        self.net = mlp(obs_size + goal_size, 8, hidden)

    def features(self, obs: torch.Tensor, goal: torch.Tensor) -> torch.Tensor:
        return torch.cat([self.normaliser(obs), goal], dim=-1)

    def forward(self, obs: torch.Tensor, goal: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        """(mean, log_std) of the pre-tanh Gaussian."""
        mean, log_std = self.net(self.features(obs, goal)).float().chunk(2, dim=-1)  # fp32 under autocast too
        return mean, torch.clamp(log_std, LOG_STD_MIN, self.log_std_max)


def export(actor: GaussianPolicy, directory: Path, scene: str, info: dict, goal: str = "semantic",
           derived: tuple[str, ...] = ()) -> None:
    """Write ``actor.pt`` and ``actor.json`` (layout + ``info``) into ``directory``; ``derived``: the
    features (``semgoal_core.features``) appended to the observation it was trained on."""
    from semgoal_policy import object_actor

    directory.mkdir(parents=True, exist_ok=True)
    torch.save({k: v.detach().cpu() for k, v in actor.state_dict().items()}, directory / "actor.pt")
    meta = {"layout": layout.describe(scene, goal, features.widths(derived)), "hidden": list(HIDDEN),
            "log_std_max": actor.log_std_max, "feature_versions": {n: features.FEATURE_VERSIONS[n] for n in derived},
            **info}
    if isinstance(actor, object_actor.ObjectActor):
        meta |= {"architecture": object_actor.ARCHITECTURE, "token_version": object_actor.TOKEN_VERSION}
    (directory / "actor.json").write_text(json.dumps(meta, indent=2) + "\n")


def load(directory: Path | str, scene: str | None = None) -> tuple[GaussianPolicy, dict]:
    """Load an exported actor; refuse it when its layout differs from the current code's (an object-centric actor
    loads for any scene: :mod:`semgoal_policy.object_actor`). ``expert`` loads the scripted expert
    (:mod:`semgoal_policy.expert_actor`)."""
    from semgoal_policy.expert_actor import EXPERT, ExpertActor

    if str(directory) == EXPERT:
        scene = scene or ""
        return ExpertActor(scene), {"actor": EXPERT, "layout": layout.describe(scene)}
    directory = Path(directory)
    meta_path, weights_path = directory / "actor.json", directory / "actor.pt"
    if not meta_path.exists() or not weights_path.exists():
        raise FileNotFoundError(f"no exported actor in {directory} (expected actor.json and actor.pt); "
                                f"train one with ./semgoal train --scene SCENE")
    meta = json.loads(meta_path.read_text())
    stored = meta["layout"]
    scene = scene or stored["scene"]
    names = derived_features(meta)
    if meta.get("architecture") == "object":
        return _load_object_actor(directory, meta, scene, names), meta
    try:
        current = layout.describe(scene, stored.get("goal", "semantic"), features.widths(features.check(names)))
    except ValueError as error:
        raise LayoutMismatchError(f"actor in {directory}: {error}") from error
    if stored != current:
        diff = sorted(k for k in current if stored.get(k) != current[k])
        raise LayoutMismatchError(f"actor in {directory} was trained on another layout than the code's for "
                                  f"scene {scene!r} (differs in: {', '.join(diff)}); retrain or use a matching actor")
    trained_on = meta.get("feature_versions", dict.fromkeys(names, 1))  # actors exported without versions: 1
    changed = [n for n in names if trained_on.get(n) != features.FEATURE_VERSIONS[n]]
    if changed:
        raise LayoutMismatchError(f"actor in {directory} was trained on another version of the derived feature(s) "
                                  f"{', '.join(changed)} (actor: {trained_on}, code: {features.FEATURE_VERSIONS}); "
                                  "retrain it")
    actor = Actor(current["observation_size"] + features.width(names), current["goal_size"],
                  tuple(meta["hidden"]),
                  meta.get("log_std_max", LOG_STD_MAX))  # older exports: the default
    actor.load_state_dict(torch.load(weights_path, weights_only=True))
    actor.eval()
    return actor, meta


def _load_object_actor(directory: Path, meta: dict, scene: str, names: tuple[str, ...]) -> GaussianPolicy:
    """An object-centric actor's weights, for ``scene`` whatever scene it was trained on: its tokens must be the
    code's and its derived features known."""
    from semgoal_policy import object_actor

    if meta.get("token_version") != object_actor.TOKEN_VERSION:
        raise LayoutMismatchError(f"actor in {directory} reads version {meta.get('token_version')} of the block tokens, "
                                  f"the code version {object_actor.TOKEN_VERSION}; retrain it")
    try:
        width = features.width(features.check(names))
    except ValueError as error:
        raise LayoutMismatchError(f"actor in {directory}: {error}") from error
    actor = object_actor.ObjectActor(scene, width, meta.get("log_std_max", LOG_STD_MAX))
    actor.load_state_dict(torch.load(directory / "actor.pt", weights_only=True))
    actor.eval()
    return actor


def derived_features(meta: dict) -> tuple[str, ...]:
    """The derived features an exported actor (its ``actor.json``) expects appended to the observation."""
    return tuple(name for name, _ in meta["layout"].get("derived_features", []))
