"""A shipped actor as an SB3 user calls it: Stable-Baselines3's own evaluate_policy, on a vectorised
`semgoal/SubGoal-SCENE-v0`, solves the sub-goals it draws."""

import numpy as np
import pytest
from stable_baselines3.common.env_util import make_vec_env
from stable_baselines3.common.evaluation import evaluate_policy

import semgoal_sim  # noqa: F401  (registers the ids)
from semgoal_policy.pretrained import load_policy

EPISODES = 10


@pytest.mark.parametrize("scene", ["two_blocks", "desk_cleanup"])
def test_evaluate_policy_runs_a_shipped_actor(scene: str) -> None:
    env = make_vec_env(f"semgoal/SubGoal-{scene}-v0", n_envs=2, seed=5_000_000)  # seeds never used in training
    rewards, _ = evaluate_policy(load_policy(scene, seed=1), env, n_eval_episodes=EPISODES, return_episode_rewards=True)
    solved = sum(reward > 0 for reward in rewards)  # a step's reward is 1 while the sub-goal holds at rest
    assert solved >= 8, rewards


def test_one_observation_or_a_batch() -> None:
    policy = load_policy("two_blocks", seed=1)
    env = make_vec_env("semgoal/SubGoal-two_blocks-v0", n_envs=2, seed=5)
    batch = env.reset()
    actions, state = policy.predict(batch, deterministic=True)
    one, _ = policy.predict({key: value[0] for key, value in batch.items()}, deterministic=True)
    assert actions.shape == (2, 4) and state is None and np.allclose(one, actions[0], atol=1e-6)
    assert np.all(np.abs(actions) <= 1.0)
