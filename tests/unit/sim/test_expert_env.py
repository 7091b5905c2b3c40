"""The scripted expert solves tasks and sub-goals; the env follows the gymnasium goal-env contract."""

import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

from semgoal_sim.env import SubgoalEnv
from semgoal_sim.expert import expert_action
from semgoal_sim.layout import goal_reward, observation_size
from semgoal_sim.rollout import run_task
from semgoal_sim.tasks import TASKS


@pytest.mark.parametrize("task", list(TASKS))
def test_expert_solves_each_task(task: str) -> None:
    results = [run_task(task, seed) for seed in range(100, 104)]
    assert sum(r.success for r in results) >= 3, results


@pytest.mark.parametrize("scene", ["two_blocks", "three_blocks", "desk_cleanup"])
def test_expert_achieves_sampled_subgoals(scene: str) -> None:
    env = SubgoalEnv(scene)
    successes = 0
    for seed in range(12):
        env.reset(seed=seed)
        for _ in range(env.max_steps):
            _, reward, _, _, _ = env.step(expert_action(env.subgoal, env.world.view()))
            if reward:
                successes += 1
                break
    assert successes >= 11


def test_env_contract_and_her_reward() -> None:
    env = SubgoalEnv("three_blocks")
    check_env(env, skip_render_check=True)
    obs, info = env.reset(seed=3)
    assert obs["observation"].shape == (observation_size("three_blocks"),)
    assert not info["is_success"], "episodes never start solved"
    achieved = np.stack([obs["achieved_goal"]] * 4)
    desired = np.stack([obs["desired_goal"]] * 4)
    relabelled = desired.copy()
    relabelled[1] = achieved[1]  # HER: an achieved goal copied into the desired one is always reached
    rewards = env.compute_reward(achieved, relabelled, {})
    assert rewards[1] == 1.0 and rewards[0] == 0.0
    assert np.array_equal(rewards, goal_reward(achieved, relabelled))


def test_explicit_subgoal_option() -> None:
    env = SubgoalEnv("desk_cleanup", n_blocks=3)
    _, info = env.reset(seed=0, options={"subgoal": "put_in_bin(blue)"})
    assert info["subgoal"] == "put_in_bin(blue)"
    assert "holding(blue)" in env.layout.readable(env.world.semantic_vector())
