"""The gymnasium front door: every registered id passes gymnasium's env checker and renders an RGB frame."""

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import semgoal_sim  # noqa: F401  (registers the ids)
from semgoal_core.vocabulary import PAPER_SCENES, SCENES
from semgoal_sim.registration import env_ids


def test_every_scene_has_its_ids() -> None:
    assert set(env_ids()) == {f"semgoal/SubGoal-{scene}-v0" for scene in SCENES} | {
        f"semgoal/Task-{scene}-{version}" for scene in PAPER_SCENES for version in ("v0", "positions-v0")}
    assert set(env_ids()) <= set(gym.registry)


@pytest.mark.parametrize("env_id", env_ids())
def test_a_registered_env_passes_the_checker_and_renders(env_id: str) -> None:
    env = gym.make(env_id, render_mode="rgb_array")
    try:
        check_env(env.unwrapped, skip_render_check=False)
        env.reset(seed=3)
        frame = env.render()
        assert frame.shape == (360, 480, 3) and frame.dtype == np.uint8 and frame.std() > 10  # a picture, not a blank
    finally:
        env.close()


def test_an_unknown_render_mode_is_refused() -> None:
    with pytest.raises(ValueError, match="rgb_array"):
        gym.make("semgoal/SubGoal-two_blocks-v0", render_mode="depth_array")
