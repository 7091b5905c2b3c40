"""Stable-Baselines3's SAC + HER trains on every registered sub-goal env, relabelling at rest from the kept infos."""

import gymnasium as gym
import numpy as np
import pytest
from stable_baselines3 import SAC, HerReplayBuffer
from stable_baselines3.common.logger import Logger

import semgoal_sim  # noqa: F401  (registers the ids)
from semgoal_core.layout import goal_reward
from semgoal_core.settling import HER_REPLAY_KWARGS
from semgoal_core.vocabulary import SCENES
from semgoal_sim.registration import env_ids

SUBGOAL_ENVS = [env_id for env_id in env_ids() if "/SubGoal-" in env_id]
STEPS = 300


def test_each_scene_has_a_subgoal_env() -> None:
    assert sorted(SUBGOAL_ENVS) == sorted(f"semgoal/SubGoal-{scene}-v0" for scene in SCENES)


def _sac(env_id: str, her_kwargs: dict) -> SAC:
    model = SAC("MultiInputPolicy", gym.make(env_id), replay_buffer_class=HerReplayBuffer,
                replay_buffer_kwargs={"n_sampled_goal": 4, "goal_selection_strategy": "future", **her_kwargs},
                learning_starts=100, batch_size=64, policy_kwargs={"net_arch": [32, 32]}, seed=0, verbose=0)
    model.set_logger(Logger(None, []))  # not SB3's default, which leaves an empty folder in the temp dir
    return model


@pytest.mark.slow
@pytest.mark.parametrize("env_id", SUBGOAL_ENVS)
def test_sac_her_trains_and_relabels_at_rest(env_id: str) -> None:
    model = _sac(env_id, HER_REPLAY_KWARGS)
    model.learn(total_timesteps=STEPS)
    assert model.num_timesteps == STEPS
    batch = model.replay_buffer.sample(512)
    rewards = batch.rewards.numpy().ravel()
    achieved, desired = batch.next_observations["achieved_goal"].numpy(), batch.observations["desired_goal"].numpy()
    literals_hold = goal_reward(achieved, desired)
    assert set(np.unique(rewards)) <= {0.0, 1.0}
    assert rewards.max() == 1.0, "HER's relabelled goals should often be met"
    assert np.all(rewards <= literals_hold), "a reward where the literals do not hold"


def test_without_the_kept_infos_the_error_says_what_to_pass() -> None:
    env = gym.make("semgoal/SubGoal-two_blocks-v0").unwrapped
    obs, _ = env.reset(seed=1)
    with pytest.raises(ValueError, match="copy_info_dict"):
        env.compute_reward(obs["achieved_goal"][None], obs["desired_goal"][None], [{}])


def test_a_step_info_and_a_batch_of_them_give_the_same_reward() -> None:
    env = gym.make("semgoal/SubGoal-two_blocks-v0").unwrapped
    obs, _ = env.reset(seed=1)
    obs, reward, _, _, info = env.step(np.zeros(4, dtype=np.float32))
    batch = env.compute_reward(np.stack([obs["achieved_goal"]] * 3), np.stack([obs["desired_goal"]] * 3), [info] * 3)
    assert batch.tolist() == [reward] * 3
    assert float(env.compute_reward(obs["achieved_goal"], obs["desired_goal"], info)) == reward
