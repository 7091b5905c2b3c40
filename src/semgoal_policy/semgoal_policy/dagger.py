"""DAgger for an exported actor: it drives, the scripted expert labels every state it reaches, and it is fitted to
all the labels so far (Ross, Gordon and Bagnell, "A Reduction of Imitation Learning and Structured Prediction to
No-Regret Online Learning", AISTATS 2011).

SAC+HER with expert supervision clones the expert only in the expert's own states, the demonstrations. An actor that
strays (a block let go off-centre on a tower of four, a hand brushing a tower on its way to the next block) meets
states that no demonstration covers. Here the labels come from where the actor itself goes. This module collects
sub-goal episodes of the training distribution (:class:`~semgoal_sim.env.SubgoalEnv`) and fits the actor to the
aggregate. The caller may add states from whole tasks (:class:`Recorder`), where towers grow taller than any
sub-goal's start. No ROS.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
import torch

from semgoal_core.layout import observation_size
from semgoal_policy.actor import GaussianPolicy
from semgoal_policy.evaluate import run_episodes
from semgoal_policy.expert_actor import ExpertActor


@dataclass(frozen=True)
class DaggerConfig:
    iterations: int = 4
    subgoal_episodes: int = 400
    """Sub-goal episodes the actor drives per iteration (types drawn as training draws them)."""
    task_episodes: int = 3
    """Whole-task episodes per task and iteration (the caller runs them through the executive)."""
    epochs: int = 4
    """Passes over the aggregate per iteration."""
    batch_size: int = 256
    lr: float = 3e-4
    """Adam's rate: a third of SAC's, a fine-tune of a trained actor."""
    seed: int = 1
    subgoal_seed: int = 600_000
    task_seed: int = 700_000
    """First starts of iteration 1; iteration k adds (k - 1) times :data:`ITERATION_SEED_STRIDE` (runs/README.md)."""


ITERATION_SEED_STRIDE = 10_000


@dataclass
class Aggregate:
    """Every labelled state so far: the actor's input (observation with its derived features, goal) and the
    expert's command there."""

    obs: list[np.ndarray] = field(default_factory=list)
    goal: list[np.ndarray] = field(default_factory=list)
    label: list[np.ndarray] = field(default_factory=list)

    def add(self, obs: np.ndarray, goal: np.ndarray, label: np.ndarray) -> None:
        if not len(obs) == len(goal) == len(label):
            raise ValueError(f"{len(obs)} states, {len(goal)} goals and {len(label)} labels")
        self.obs.append(np.asarray(obs, np.float32))
        self.goal.append(np.asarray(goal, np.float32))
        self.label.append(np.asarray(label, np.float32))

    def __len__(self) -> int:
        return sum(len(rows) for rows in self.obs)

    def arrays(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        return np.concatenate(self.obs), np.concatenate(self.goal), np.concatenate(self.label)


class Recorder:
    """Stands in for an actor (``act``, as the controller calls it) and keeps every input it was asked about, for
    the expert to label afterwards (:func:`label`)."""

    def __init__(self, actor: GaussianPolicy) -> None:
        self.actor = actor
        self.obs: list[np.ndarray] = []
        self.goal: list[np.ndarray] = []

    def act(self, obs: np.ndarray, goal: np.ndarray, noise: np.ndarray | None = None) -> np.ndarray:
        self.obs.append(np.asarray(obs, np.float32))
        self.goal.append(np.asarray(goal, np.float32))
        with torch.no_grad():
            return self.actor.act(obs, goal, noise)


def label(scene: str, obs: np.ndarray, goal: np.ndarray) -> np.ndarray:
    """(B, 4): the expert's command in each state (it reads the observation without the derived features)."""
    return ExpertActor(scene).act(np.asarray(obs)[:, :observation_size(scene)], goal).astype(np.float32)


def collect_subgoals(envs: Sequence, actor: GaussianPolicy, episodes: int, seed: int) -> tuple[Aggregate, float]:
    """The actor's mean drives ``episodes`` sub-goal episodes (seeds from ``seed``), batched over ``envs``; every
    state it acted in comes back labelled by the expert, with the share of episodes that succeeded at rest."""

    def act(obs: np.ndarray, goal: np.ndarray) -> np.ndarray:
        with torch.no_grad():
            return actor.act(obs, goal)

    states, wins = Aggregate(), 0
    for start in range(0, episodes, len(envs)):
        batch = min(len(envs), episodes - start)
        result = run_episodes(envs, act, [{}] * batch, [seed + start + i for i in range(batch)], label=True)
        horizon = result.action.shape[1]
        states.add(result.obs[:, :horizon].reshape(batch * horizon, -1), np.repeat(result.goal, horizon, axis=0),
                   result.expert_action.reshape(batch * horizon, -1))
        wins += int(result.success.sum())
    return states, wins / episodes


def fit(actor: GaussianPolicy, data: Aggregate, config: DaggerConfig, rng: np.random.Generator) -> float:
    """``config.epochs`` passes of behaviour cloning over ``data`` (squared error of the squashed mean to the
    expert's command, as the SAC trainer's cloning term); the normaliser's statistics stay as trained. Returns the
    last epoch's mean loss."""
    obs, goal, target = (torch.as_tensor(a) for a in data.arrays())
    optimiser = torch.optim.Adam(actor.net.parameters(), lr=config.lr)
    actor.train()
    loss_sum = 0.0
    for _ in range(config.epochs):
        order = torch.as_tensor(rng.permutation(len(obs)))
        loss_sum, batches = 0.0, 0
        for start in range(0, len(obs), config.batch_size):
            rows = order[start:start + config.batch_size]
            mean = torch.tanh(actor(obs[rows], goal[rows])[0])
            loss = ((mean - target[rows]) ** 2).sum(-1).mean()
            optimiser.zero_grad()
            loss.backward()
            optimiser.step()
            loss_sum, batches = loss_sum + loss.item(), batches + 1
        loss_sum /= max(batches, 1)
    actor.eval()
    return loss_sum
