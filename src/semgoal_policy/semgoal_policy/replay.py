"""Episode replay buffer with vectorised HER ("future" strategy) and the expert's action labels.

Episodes have a fixed length T. Each stored step keeps the action taken and the scripted expert's action
in that state for the episode's own goal, so behaviour cloning can use every state the agent visited
(DAgger-style labels) and not only the demonstrations. Relabelled samples carry no expert label. Each
state also keeps its motion bits (:func:`semgoal_core.settling.motion_bits`), so the reward of a relabelled
goal is judged at rest, as the episode's own goal was.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import NamedTuple

import numpy as np

RewardFn = Callable[[np.ndarray, np.ndarray, np.ndarray], np.ndarray]
"""(achieved, desired, motion) -> reward, vectorised over the leading axis."""


class Batch(NamedTuple):
    obs: np.ndarray
    goal: np.ndarray
    action: np.ndarray
    reward: np.ndarray
    next_obs: np.ndarray
    expert_action: np.ndarray
    has_label: np.ndarray
    """1 where ``goal`` is the episode's own goal (the expert label applies), 0 where HER relabelled."""


class EpisodeReplay:
    """Ring buffer of whole episodes: obs and achieved goals (T+1 rows), actions and labels (T rows)."""

    FIELDS = ("obs", "achieved", "motion", "goal", "action", "expert_action")

    def __init__(self, capacity_episodes: int, horizon: int, obs_size: int, goal_size: int,
                 reward_fn: RewardFn, her_ratio: float = 0.8, motion_size: int = 0) -> None:
        self.capacity, self.horizon, self.reward_fn, self.her_ratio = capacity_episodes, horizon, reward_fn, her_ratio
        e, t = capacity_episodes, horizon
        self.obs = np.zeros((e, t + 1, obs_size), np.float32)
        self.achieved = np.zeros((e, t + 1, goal_size), np.float32)
        self.motion = np.zeros((e, t + 1, motion_size), np.float32)
        self.goal = np.zeros((e, goal_size), np.float32)
        self.action = np.zeros((e, t, 4), np.float32)
        self.expert_action = np.zeros((e, t, 4), np.float32)
        self.next_index = 0
        self.size = 0

    def clear(self) -> None:
        """Empty (the rows a load that failed half-way wrote are never sampled)."""
        self.size = self.next_index = 0

    @property
    def transitions(self) -> int:
        return self.size * self.horizon

    def add(self, obs: np.ndarray, achieved: np.ndarray, motion: np.ndarray, goal: np.ndarray, action: np.ndarray,
            expert_action: np.ndarray) -> None:
        """Store a batch of episodes: obs (B, T+1, O), achieved (B, T+1, G), motion (B, T+1, M), goal (B, G),
        actions (B, T, 4)."""
        for i in range(len(goal)):
            j = self.next_index
            self.obs[j], self.achieved[j], self.motion[j], self.goal[j] = obs[i], achieved[i], motion[i], goal[i]
            self.action[j], self.expert_action[j] = action[i], expert_action[i]
            self.next_index = (j + 1) % self.capacity
            self.size = min(self.size + 1, self.capacity)

    def sample(self, rng: np.random.Generator, batch_size: int, her_ratio: float | None = None) -> Batch:
        """Transitions with HER relabelling at ``her_ratio`` (default: the buffer's; 0 for cloning batches)."""
        episodes = rng.integers(0, self.size, batch_size)
        steps = rng.integers(0, self.horizon, batch_size)
        own = self.goal.take(episodes, axis=0)
        goal = own.copy()
        relabel = rng.uniform(size=batch_size) < (self.her_ratio if her_ratio is None else her_ratio)
        # "future": a goal achieved later in the same episode (Andrychowicz et al. 2017, section 4.5)
        future = steps + 1 + (rng.uniform(size=batch_size) * (self.horizon - steps)).astype(int)
        # rows of the (episode, step) arrays seen flat: one index per sample, a third of the time of two
        state = episodes * (self.horizon + 1) + steps
        step = episodes * self.horizon + steps
        achieved, obs = _rows(self.achieved), _rows(self.obs)
        goal[relabel] = achieved.take(state[relabel] - steps[relabel] + future[relabel], axis=0)
        # a relabelled goal equal to the episode's own keeps its label
        has_label = ~relabel | np.all(goal == own, axis=1)
        return Batch(
            obs=obs.take(state, axis=0),
            goal=goal,
            action=_rows(self.action).take(step, axis=0),
            reward=self.reward_fn(achieved.take(state + 1, axis=0), goal, _rows(self.motion).take(state + 1, axis=0)),
            next_obs=obs.take(state + 1, axis=0),
            expert_action=_rows(self.expert_action).take(step, axis=0),
            has_label=has_label.astype(np.float32),
        )

    def save(self, path: Path) -> None:
        """Written beside ``path`` and moved onto it: a run stopped while saving keeps the buffer it had (one was
        left half written, and the resume stopped on it)."""
        arrays = {name: getattr(self, name)[: self.size] for name in self.FIELDS}
        partial = path.with_name(f"{path.name}.partial")
        with partial.open("wb") as file:
            np.savez(file, next_index=self.next_index, **arrays)
        partial.replace(path)

    def load(self, path: Path) -> None:
        """Restore a saved buffer; one holding more episodes than this buffer's capacity (a run resumed
        with fewer ``--steps``) keeps its newest ``capacity`` episodes."""
        with np.load(path) as data:
            stored, next_index = len(data["goal"]), int(data["next_index"])
            if stored <= self.capacity:
                self.size, self.next_index = stored, next_index
                for name in self.FIELDS:
                    getattr(self, name)[:stored] = data[name]
                return
            newest = np.roll(np.arange(stored), -(next_index % stored))[-self.capacity:]  # oldest first
            self.size, self.next_index = self.capacity, 0
            for name in self.FIELDS:
                getattr(self, name)[:] = data[name][newest]


def _rows(array: np.ndarray) -> np.ndarray:
    """An (episode, step, value) array as (episode * step, value) rows: a view, as the buffers are contiguous."""
    return array.reshape(array.shape[0] * array.shape[1], array.shape[2])
