"""The scripted expert solves tasks and sub-goals; the env follows the gymnasium goal-env contract."""

import itertools

import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

from semgoal_core.expert import expert_action
from semgoal_core.layout import goal_reward, observation_size
from semgoal_core.tasks import SPAWN_HIGH, SPAWN_LOW, TABLE_TOP, TASKS
from semgoal_core.vocabulary import BLOCK_HALF_SIZE
from semgoal_sim import env as env_module
from semgoal_sim.env import SubgoalEnv
from semgoal_sim.rollout import run_task


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


@pytest.mark.parametrize("kind", ["put_near", "put_away"])
def test_expert_labels_keep_a_put_achieved_to_the_end_of_the_episode(kind: str) -> None:
    """After a put holds, the expert backs away; re-picking the block would teach undoing the sub-goal."""
    env = SubgoalEnv("three_blocks")
    held_at_end = 0
    for seed in range(6):
        env.reset(seed=seed, options={"kind": kind})
        for _ in range(env.max_steps):
            _, reward, _, _, _ = env.step(env.expert_action())
        held_at_end += int(reward)
    assert held_at_end >= 5


def test_the_expert_is_not_done_while_a_block_lies_off_the_table() -> None:
    """The rule every success here follows: the goal at rest and every block on the table."""
    from semgoal_core.vocabulary import Literal
    from semgoal_sim.rollout import solve
    from semgoal_sim.world import FetchWorld

    world = FetchWorld("desk_cleanup", 2)
    world.reset(TASKS["DC-2"].initial_state(0)[0])
    goal = [Literal("in_bin", ("red",), False)]
    assert solve(world, goal).success
    world.set_block_pose("green", np.array([1.3, 0.2, BLOCK_HALF_SIZE]))  # on the floor beside the table
    assert world.fallen_blocks() == ["green"] and not solve(world, goal).success


@pytest.mark.parametrize("scene", ["two_blocks", "desk_cleanup", "tabletop"])
def test_a_steps_reward_is_what_her_recomputes_from_it(scene: str) -> None:
    """The step's reward (worked out from the sub-goal's entries, once per sub-goal) is compute_reward of the step's
    own achieved and desired goals and info, over expert episodes that reach their sub-goals, at rest and not."""
    env = SubgoalEnv(scene)
    rewards, achieved_moving = [], 0
    for seed in range(4):
        env.reset(seed=seed)
        for _ in range(env.max_steps):
            obs, reward, _, _, info = env.step(env.expert_action())
            recomputed = env.compute_reward(obs["achieved_goal"], obs["desired_goal"], info)
            assert reward == recomputed == float(info["is_success"])
            achieved_moving += int(goal_reward(obs["achieved_goal"], obs["desired_goal"]) > reward)
            rewards.append(reward)
    assert 0 < sum(rewards) < len(rewards) and achieved_moving > 0


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
    still = {"motion": np.zeros((4, 6), np.float32)}
    rewards = env.compute_reward(achieved, relabelled, still)
    assert rewards[1] == 1.0 and rewards[0] == 0.0
    assert np.array_equal(rewards, goal_reward(achieved, relabelled))
    falling = {"motion": np.zeros((4, 6), np.float32)}
    falling["motion"][1, 2] = 1.0  # blue moves: the relabelled goal is not achieved at rest
    assert env.compute_reward(achieved, relabelled, falling)[1] == 0.0
    assert env.compute_reward(achieved, relabelled, [{"motion": m} for m in still["motion"]])[1] == 1.0  # SB3 passes a list


def test_explicit_subgoal_option() -> None:
    env = SubgoalEnv("desk_cleanup", n_blocks=3)
    _, info = env.reset(seed=0, options={"subgoal": "put_in_bin(blue)"})
    assert info["subgoal"] == "put_in_bin(blue)"
    assert "holding(blue)" in env.layout.readable(env.world.semantic_vector())


def test_put_episodes_start_where_a_pick_leaves_the_arm() -> None:
    """Most puts start after a confirmed expert pick, at the block's spot, not at the home pose."""
    env = SubgoalEnv("three_blocks")
    home = env.world.view().grip.copy()
    away_from_home = 0
    for seed in range(10):
        env.reset(seed=seed, options={"kind": "put_away"})
        assert f"holding({env.subgoal.block})" in env.layout.readable(env.world.semantic_vector())
        away_from_home += np.linalg.norm(env.world.view().grip[:2] - home[:2]) > 0.02
    assert away_from_home >= 6


def test_pick_episodes_sometimes_start_with_the_arm_elsewhere() -> None:
    env = SubgoalEnv("desk_cleanup")
    grips = [env.reset(seed=seed, options={"kind": "pick"})[0]["observation"][:3] for seed in range(20)]
    assert len({tuple(np.round(g, 2)) for g in grips}) >= 5  # about half of them leave the home pose


@pytest.mark.parametrize("scene", ["three_blocks", "desk_cleanup"])
def test_picks_sometimes_start_where_a_put_of_another_block_left_the_arm(scene: str) -> None:
    """The hand-over a plan makes: the open fingers above the block just put, nothing held (a put lets go
    from up to carry height and backs away upward; opened fully at once, the fingers can leave the block
    landing a few cm off to the side)."""
    env = SubgoalEnv(scene)
    after_put = 0
    for seed in range(30):
        env.reset(seed=seed, options={"kind": "pick"})
        view, target = env.world.view(), env.subgoal.block
        assert not any(view.holds(block) for block in view.positions)
        put_down = [b for b, p in view.others(target).items()
                    if np.linalg.norm(p[:2] - view.grip[:2]) < 0.06 and p[2] < view.grip[2] < p[2] + 0.2]
        after_put += bool(put_down)
    assert 6 <= after_put <= 20  # about 40 % of the starts


@pytest.mark.parametrize("scene", ["two_blocks", "three_blocks"])
def test_some_starts_have_a_stack_and_never_ask_to_pick_its_bottom_block(scene: str) -> None:
    env = SubgoalEnv(scene)
    stacked, starts = 0, 60
    for seed in range(starts):
        env.reset(seed=seed, options={"kind": "pick"})
        heights = sorted(p[2] for p in env.world.view().positions.values())
        stacked += heights[-1] - heights[0] > 0.04
        assert not env._under_another(env.subgoal.block)
    share = env_module.STACKED_START_SHARE[scene]
    assert 0.4 * share * starts <= stacked <= 2 * share * starts


def test_near_two_references_starts_with_them_close_and_keeps_its_share() -> None:
    """Where the two references start apart the expert joins them first, rather than the draw being thrown
    away (which left near-both about a tenth of the put nears)."""
    env, starts = SubgoalEnv("three_blocks"), 60
    near_both = 0
    for seed in range(starts):
        env.reset(seed=seed, options={"kind": "put_near"})
        if len(env.subgoal.references) == 2:
            near_both += 1
            assert env._close(env.world.semantic_vector(), env.subgoal.references)
            assert not env._achieved
    assert 0.6 * env_module.NEAR_BOTH_SHARE * starts <= near_both <= 1.6 * env_module.NEAR_BOTH_SHARE * starts


def test_a_missed_put_starts_with_the_block_resting_just_beyond_close_and_the_expert_picks_it_again() -> None:
    """The state the actors' misses left (the block let go 0.10 to 0.12 m from a reference, the open fingers
    hovering over it): training starts some put nears there, so that the actor learns to try again."""
    env, missed, done = SubgoalEnv("three_blocks", missed_put_share=env_module.MAX_MISSED_PUT_SHARE), 0, 0
    low, high = env_module.MISSED_PUT_REACH
    for seed in range(30):
        env.reset(seed=seed, options={"kind": "put_near"})
        view, block = env.world.view(), env.subgoal.block
        if view.holds(block):
            continue
        missed += 1
        gaps = [np.linalg.norm(view.positions[block][:2] - view.positions[ref][:2]) for ref in env.subgoal.references]
        assert any(low - 0.005 <= gap <= high + 0.005 for gap in gaps), gaps
        assert not env._achieved and env.world.motion().max() < 0.02
        assert 0.05 < view.grip[2] - view.positions[block][2] < 0.11
        for _ in range(env.max_steps):
            _, reward, _, _, _ = env.step(env.expert_action())
        done += int(reward)  # picked again and put within reach, at rest at the end
    assert 0.25 * 30 <= missed <= 0.75 * 30
    assert done >= 0.8 * missed


def test_missed_puts_are_a_training_setting_off_by_default() -> None:
    env = SubgoalEnv("three_blocks")
    for seed in range(10):
        env.reset(seed=seed, options={"kind": "put_near"})
        assert env.world.view().holds(env.subgoal.block)
    with pytest.raises(ValueError, match="missed_put_share"):
        SubgoalEnv("three_blocks", missed_put_share=0.9)


PINNED_PUT_NEAR_STARTS = [  # (seed, sub-goal, grip xyz, block xyz), as eval-subgoals draws them
    (2010000, "put_near(blue,green)", (1.381, 0.557, 0.547), (1.386, 0.557, 0.548)),
    (2010001, "put_near(blue,red,green)", (1.191, 0.736, 0.562), (1.183, 0.737, 0.529)),
    (2010002, "put_near(blue,red,not green)", (1.342, 0.749, 0.533), (1.342, 0.749, 0.532)),
    (2010004, "put_near(blue,green,red)", (1.228, 0.630, 0.553), (1.229, 0.630, 0.543)),
    (2010005, "put_near(green,red,blue)", (1.428, 0.626, 0.549), (1.439, 0.625, 0.549)),
]


@pytest.mark.parametrize(("seed", "subgoal", "grip", "block"), PINNED_PUT_NEAR_STARTS)
def test_evaluation_starts_stay_put_when_training_only_settings_are_off(seed, subgoal, grip, block) -> None:
    """Per-type rates compare across sessions only on the same starts: a training-only setting that is off
    (missed puts, spawn margin) must not draw from the episode's generator. A deliberate change of the
    sampler re-pins these and re-measures every per-type figure it compares."""
    env = SubgoalEnv("three_blocks")
    env.reset(seed=seed, options={"kind": "put_near"})
    view = env.world.view()
    assert str(env.subgoal) == subgoal
    np.testing.assert_allclose(view.grip, grip, atol=2e-3)
    np.testing.assert_allclose(view.positions[env.subgoal.block], block, atol=2e-3)


def test_the_shortfall_says_which_literal_fails_how_far_off_and_what_is_not_at_rest() -> None:
    """What ``eval-subgoals --misses`` prints: a block let go just out of reach, one falling, one put."""
    env = SubgoalEnv("three_blocks")
    env.reset(seed=0, options={"subgoal": "put_near(red,green)"})
    green = env.world.view().positions["green"]
    env._move_grip(green + np.array([0.0, 0.3, 0.25]), steps=40)  # fingers open, well away from the blocks
    rest_z = TABLE_TOP + BLOCK_HALF_SIZE

    def put_red(offset: float, height: float, steps: int) -> list[str]:
        env.world.set_block_pose("red", np.array([green[0] + offset, green[1], rest_z + height]))
        for _ in range(steps):
            env.world.step(np.zeros(4))
        return env.shortfall()

    assert put_red(0.11, 0.0, 30) == ["close(red,green) is false (0.110 m)"]
    falling = put_red(0.06, 0.15, 3)
    assert any(reason.startswith("not at rest (moving: red") for reason in falling), falling
    assert put_red(0.06, 0.0, 30) == []


def test_three_block_puts_mostly_say_where_the_block_ends_up_with_respect_to_every_other_block() -> None:
    """As the planner's steps do (put_near(x,y,not z), put_away(x,y,z)); a few name one reference only."""
    env = SubgoalEnv("three_blocks")
    whole = 0
    for seed in range(60):
        env.reset(seed=seed, options={"kind": ("put_near", "put_away")[seed % 2]})
        whole += len(env.subgoal.references) + len(env.subgoal.apart) == 2
    assert 0.6 * 60 <= whole <= 0.95 * 60


def test_the_expert_puts_a_block_near_one_and_apart_from_the_other() -> None:
    env = SubgoalEnv("three_blocks")
    done = tried = 0
    for seed in range(40):
        env.reset(seed=seed, options={"kind": "put_near"})
        if not env.subgoal.apart:
            continue
        tried += 1
        for _ in range(env.max_steps):
            _, reward, _, _, _ = env.step(env.expert_action())
        done += int(reward)  # close to the reference, not to the other, at rest at the end
    assert tried >= 12 and done >= tried - 2


def test_achieved_goal_keeps_only_the_masked_entries() -> None:
    """A relabelled goal must look like one the planner sends: zeros outside the mask."""
    env = SubgoalEnv("three_blocks")
    obs, _ = env.reset(seed=1, options={"subgoal": "put_near(red,green)"})
    size = env.layout.size
    achieved, mask = obs["achieved_goal"][:size], obs["achieved_goal"][size:]
    assert np.array_equal(mask, obs["desired_goal"][size:])
    assert not achieved[mask == 0].any()
    assert achieved[env.layout.index(env.subgoal.literals()[-1])] == 1.0  # holding(red), masked, is true


def test_desk_starts_fill_the_bin_with_any_number_of_blocks_apart_from_each_other() -> None:
    env = SubgoalEnv("desk_cleanup", n_blocks=4)
    env.reset(seed=0)
    bin_, counts, per_block, off_slot = env.scene.bin, [], np.zeros(4), 0
    for _ in range(400):
        positions = env._sample_positions()
        inside = bin_.contains(positions, TABLE_TOP)
        binned = positions[inside]
        assert all(np.linalg.norm(a[:2] - b[:2]) >= 0.055 for a, b in itertools.combinations(binned, 2))
        counts.append(int(inside.sum()))
        per_block += inside
        off_slot += any(np.abs(bin_.slots()[:, 0] - x).min() > 0.013 for x in binned[:, 0])
    assert set(counts) == {0, 1, 2, 3}  # never all four: a put_in_bin needs a block left out
    assert counts.count(3) >= 100  # DC-4's last put: 128 here (with the earlier sampler: 34)
    assert per_block.min() >= 30  # any block, yellow too (it never was)
    assert off_slot >= 50  # untidy bins, blocks wherever a put let go of them: 77 here


def test_desk_sub_goals_mostly_take_a_block_outside_the_bin() -> None:
    """As desk plans do: the last pick of DC-4 (three blocks binned) must be common in training."""
    env = SubgoalEnv("desk_cleanup", n_blocks=4)
    env.reset(seed=0)
    binned_targets = last_picks = 0
    for _ in range(300):
        env.world.reset(env._sample_positions())
        positions = env.world.view().positions
        inside = env.scene.bin.contains(np.array([positions[b] for b in env.world.blocks]), TABLE_TOP)
        subgoal = env._sample_subgoal("pick")
        if subgoal is None or inside.sum() == 0:
            continue
        binned_targets += bool(inside[env.world.blocks.index(subgoal.block)])
        last_picks += inside.sum() == 3 and not inside[env.world.blocks.index(subgoal.block)]
    assert binned_targets <= 10  # 2 here; drawn alike, 41
    assert last_picks >= 20  # 29 here; drawn alike, 10


def test_a_spawn_margin_starts_table_blocks_beyond_the_task_area_in_x_only() -> None:
    """Desk actors stalled over blocks at the far edge of the task area, the edge of their data."""
    def table_xy(env: SubgoalEnv) -> np.ndarray:
        positions = env._sample_positions()
        on_table = ~env.scene.bin.contains(positions, TABLE_TOP)
        return positions[on_table, :2]

    plain, wide = SubgoalEnv("desk_cleanup", n_blocks=4), SubgoalEnv("desk_cleanup", n_blocks=4, spawn_margin=0.05)
    plain.reset(seed=0)
    wide.reset(seed=0)
    plain_xy = np.vstack([table_xy(plain) for _ in range(200)])
    wide_xy = np.vstack([table_xy(wide) for _ in range(200)])
    assert plain_xy[:, 0].min() >= SPAWN_LOW[0] and plain_xy[:, 0].max() <= SPAWN_HIGH[0]
    assert (wide_xy[:, 0] > SPAWN_HIGH[0] + 0.02).sum() >= 20 and (wide_xy[:, 0] < SPAWN_LOW[0] - 0.02).sum() >= 20
    assert wide_xy[:, 0].max() <= SPAWN_HIGH[0] + 0.05 and wide_xy[:, 0].min() >= SPAWN_LOW[0] - 0.05
    assert wide_xy[:, 1].min() >= SPAWN_LOW[1] and wide_xy[:, 1].max() <= SPAWN_HIGH[1]


@pytest.mark.parametrize("margin", [-0.01, 0.2, float("nan")])
def test_a_spawn_margin_out_of_range_is_refused(margin: float) -> None:
    with pytest.raises(ValueError, match="spawn_margin"):
        SubgoalEnv("two_blocks", spawn_margin=margin)
