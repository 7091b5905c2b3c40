"""gymnasium ids for the scenes' envs, registered when ``semgoal_sim`` is imported, so that after
``import semgoal_sim`` a gymnasium or Stable-Baselines3 user writes
``gym.make("semgoal/SubGoal-desk_cleanup-v0", render_mode="rgb_array")`` (or, without the import,
``gym.make("semgoal_sim:semgoal/SubGoal-desk_cleanup-v0")``).

- ``semgoal/SubGoal-SCENE-v0``: :class:`~semgoal_sim.env.SubgoalEnv`, one sub-goal per episode (what the
  hierarchical agent's actor is trained on; the shipped actors: ``semgoal_policy.pretrained``).
- ``semgoal/Task-SCENE-v0`` and ``semgoal/Task-SCENE-positions-v0``: :class:`~semgoal_sim.task_env.TaskEnv`, a
  whole benchmark task per episode with a semantic goal or one of block positions (continuous): the flat baselines',
  for the paper's scenes.

The entry points are strings: registering loads neither MuJoCo nor the envs' modules.
"""

from __future__ import annotations

import gymnasium as gym

from semgoal_core.vocabulary import PAPER_SCENES, SCENES

NAMESPACE = "semgoal"


def env_ids() -> list[str]:
    """Every id :func:`register_envs` registers."""
    return [f"{NAMESPACE}/{name}" for name, _, _ in _specs()]


def register_envs() -> None:
    """Register every scene's envs (once: registering again would only warn)."""
    for name, entry_point, kwargs in _specs():
        if f"{NAMESPACE}/{name}" not in gym.registry:
            gym.register(id=f"{NAMESPACE}/{name}", entry_point=entry_point, kwargs=kwargs)


def _specs() -> list[tuple[str, str, dict]]:
    specs = [(f"SubGoal-{scene}-v0", "semgoal_sim.env:SubgoalEnv", {"scene": scene}) for scene in SCENES]
    for scene in PAPER_SCENES:
        specs.append((f"Task-{scene}-v0", "semgoal_sim.task_env:TaskEnv", {"scene": scene, "goal": "semantic"}))
        specs.append((f"Task-{scene}-positions-v0", "semgoal_sim.task_env:TaskEnv", {"scene": scene, "goal": "positions"}))
    return specs
