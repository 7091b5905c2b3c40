"""Batched rollouts of goal-conditioned envs: evaluation of an actor per sub-goal type, and collection.

Several envs step side by side so the actor runs once per step for all of them. An evaluation episode
succeeds when its goal held at rest (the env's ``is_success``) over ``SETTLE_STEPS`` consecutive steps
within the horizon: the rule by which the planner's executive confirms a robot step.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from semgoal_core.settling import SETTLE_STEPS

EVAL_SEED_BASE = 1_000_000
"""Evaluation episodes use seeds from here on; training envs are seeded far below (see trainer)."""
KIND_SEED_STRIDE = 10_000
"""The ``k``-th kind's episodes are seeded from ``seed + k * KIND_SEED_STRIDE`` (:func:`success_by_kind`)."""

ActFn = Callable[[np.ndarray, np.ndarray], np.ndarray]


@dataclass
class Episodes:
    """A batch of finished episodes, in the arrays the replay buffer stores."""

    obs: np.ndarray
    achieved: np.ndarray
    motion: np.ndarray
    """(B, T+1, M) each state's motion bits (empty where the env reports none)."""
    goal: np.ndarray
    action: np.ndarray
    expert_action: np.ndarray
    success: np.ndarray
    """(B,) whether the goal held at rest over ``SETTLE_STEPS`` consecutive steps."""
    kinds: list[str]


def run_episodes(envs: Sequence, act: ActFn, options: Sequence[dict], seeds: Sequence[int | None] | None = None,
                 label: bool = True, expert_mask: np.ndarray | None = None, expert_noise: float = 0.0,
                 rng: np.random.Generator | None = None) -> Episodes:
    """One episode in each env (``len(options)`` of them), all of the same horizon, stepped together.

    :param act: batched actor, (obs, goal) -> actions in [-1, 1].
    :param label: record the expert's action in every state (for behaviour cloning).
    :param expert_mask: (B,) envs that follow the expert (plus Gaussian ``expert_noise``) instead of ``act``.
    """
    count = len(options)
    seeds = seeds if seeds is not None else [None] * count
    resets = [env.reset(seed=seed, options=opt) for env, opt, seed in zip(envs, options, seeds, strict=False)]
    first = [o for o, _ in resets]
    horizon = envs[0].max_steps
    obs = np.zeros((count, horizon + 1, first[0]["observation"].size), np.float32)
    achieved = np.zeros((count, horizon + 1, first[0]["achieved_goal"].size), np.float32)
    motion = np.zeros((count, horizon + 1, np.size(resets[0][1].get("motion", ()))), np.float32)
    motion[:, 0] = [info.get("motion", ()) for _, info in resets]
    streak = np.zeros(count, int)
    actions = np.zeros((count, horizon, 4), np.float32)
    labels = np.zeros((count, horizon, 4), np.float32)
    success = np.zeros(count, bool)
    goal = np.stack([o["desired_goal"] for o in first])
    obs[:, 0] = [o["observation"] for o in first]
    achieved[:, 0] = [o["achieved_goal"] for o in first]
    for t in range(horizon):
        action = np.asarray(act(obs[:, t], goal), np.float32)
        if label or expert_mask is not None:
            labels[:, t] = [env.expert_action() for env in envs[:count]]
        if expert_mask is not None and expert_mask.any():
            noisy = labels[:, t] + expert_noise * rng.standard_normal((count, 4))
            action[expert_mask] = np.clip(noisy[expert_mask], -1.0, 1.0)
        actions[:, t] = action
        for i, env in enumerate(envs[:count]):
            step_obs, _, _, _, info = env.step(action[i])
            obs[i, t + 1], achieved[i, t + 1] = step_obs["observation"], step_obs["achieved_goal"]
            motion[i, t + 1] = info.get("motion", ())
            streak[i] = streak[i] + 1 if info["is_success"] else 0
            success[i] |= streak[i] >= SETTLE_STEPS
    kinds = [env.kind for env in envs[:count]]
    return Episodes(obs, achieved, motion, goal, actions, labels, success, kinds)


def success_by_kind(envs: Sequence, act: ActFn, kinds: Sequence[str], episodes: int, seed: int = EVAL_SEED_BASE,
                    on_miss: Callable[[str, int, Any], None] | None = None) -> dict[str, float]:
    """Deterministic success rate per kind (sub-goal type, or task for the flat agents), ``episodes`` each, batched over ``envs``.

    :param on_miss: called as ``on_miss(kind, seed, env)`` for each failed episode, with the env as it ended.
    """
    rates = {}
    for k, kind in enumerate(kinds):
        wins = 0
        for start in range(0, episodes, len(envs)):
            batch = min(len(envs), episodes - start)
            seeds = [seed + KIND_SEED_STRIDE * k + start + i for i in range(batch)]
            result = run_episodes(envs, act, [{"kind": kind}] * batch, seeds, label=False)
            wins += int(result.success.sum())
            if on_miss is not None:
                for env, episode_seed, success in zip(envs, seeds, result.success, strict=False):
                    if not success:
                        on_miss(kind, episode_seed, env)
        rates[kind] = wins / episodes
    return rates
