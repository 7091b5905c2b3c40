"""A shipped actor as the policy a gymnasium or Stable-Baselines3 user calls: :meth:`PretrainedPolicy.predict`
has SB3's signature, so ``stable_baselines3.common.evaluation.evaluate_policy(load_policy("two_blocks"), env)``
runs it on ``semgoal/SubGoal-two_blocks-v0`` (``import semgoal_sim`` registers the id). It takes that env's dict
observation, one or a batch (a VecEnv's), and computes the derived features the actor was trained with from the
observation and the goal, as the policy node does."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from semgoal_core import features
from semgoal_policy import actor as actor_io


class PretrainedPolicy:
    """An exported actor of ``scene``: SAC's mean action with ``deterministic``, a sample of its Gaussian else."""

    def __init__(self, scene: str, model_dir: Path | str | None = None, seed: int | None = None) -> None:
        self.scene = scene
        self.actor, self.meta = actor_io.load(Path(model_dir or actor_io.models_dir() / scene), scene)
        self.derived = actor_io.derived_features(self.meta)
        self.bin_shown = features.shown_bin(scene, self.meta["layout"]["scene"])
        self.rng = np.random.default_rng(seed)

    def predict(self, observation: dict[str, np.ndarray], state=None, episode_start=None,
                deterministic: bool = False) -> tuple[np.ndarray, None]:
        """Actions in [-1, 1] for ``observation["observation"]`` and ``["desired_goal"]`` (one row or a batch);
        SB3's ``(actions, state)`` (the actor keeps no state)."""
        obs = np.asarray(observation["observation"], dtype=np.float32)
        goal = np.asarray(observation["desired_goal"], dtype=np.float32)
        rows, goals = np.atleast_2d(obs), np.atleast_2d(goal)
        inputs = np.stack([features.augment(self.scene, row, self.derived, g, self.bin_shown)
                           for row, g in zip(rows, goals, strict=True)])
        noise = None if deterministic else self.rng.standard_normal((len(rows), 4))
        actions = self.actor.act(inputs, goals, noise)
        return (actions if obs.ndim == 2 else actions[0]), None


def load_policy(scene: str, model_dir: Path | str | None = None, seed: int | None = None) -> PretrainedPolicy:
    """The scene's shipped actor (or the one exported in ``model_dir``); ``seed`` seeds the sampled actions."""
    return PretrainedPolicy(scene, model_dir, seed)
