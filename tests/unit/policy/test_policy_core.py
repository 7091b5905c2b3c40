"""Policy cores: HER replay, the normaliser, actor export/load with the layout check, the safe controller."""

import json

import numpy as np
import pytest
import torch
from torch.nn import functional

from semgoal_bringup.experiments.training import make_env
from semgoal_core import features, layout
from semgoal_core.lockstep import followed_decision, lockstep_subgoal
from semgoal_core.settling import SETTLE_STEPS
from semgoal_core.vocabulary import LAYOUTS, Literal, VocabularyError
from semgoal_policy.actor import Actor, LayoutMismatchError, Normaliser, derived_features, export, load, mlp
from semgoal_policy.agents import semantic_reward
from semgoal_policy.controller import HOLD, Idle, SubgoalController
from semgoal_policy.replay import EpisodeReplay

SCENE = "two_blocks"


def test_her_relabels_with_future_achieved_goals_and_keeps_labels_only_for_own_goals() -> None:
    horizon, goal_size = 5, 4
    replay = EpisodeReplay(10, horizon, 3, goal_size, lambda a, d, m: layout.goal_reward(a, d), her_ratio=1.0)
    achieved = np.zeros((1, horizon + 1, goal_size), np.float32)
    achieved[0, :, 2:] = 1.0  # mask travels with the achieved goal
    achieved[0, 3:, 0] = 1.0  # entry 0 becomes true at step 3
    goal = np.array([[1.0, 0.0, 1.0, 1.0]], np.float32)
    replay.add(np.zeros((1, horizon + 1, 3)), achieved, np.zeros((1, horizon + 1, 0)), goal, np.zeros((1, horizon, 4)),
               np.ones((1, horizon, 4)))
    batch = replay.sample(np.random.default_rng(0), 2000)
    assert batch.reward.shape == (2000,)
    # relabelled goals are achieved ones: entry 0 false (early) or true (from step 3); both rewards occur
    assert set(np.unique(batch.goal[:, 0])) == {0.0, 1.0} and set(np.unique(batch.reward)) == {0.0, 1.0}
    own = np.all(batch.goal == goal, axis=1)
    assert np.array_equal(batch.has_label.astype(bool), own)
    clone = replay.sample(np.random.default_rng(1), 100, her_ratio=0.0)
    assert clone.has_label.all() and np.all(clone.goal == goal)


def test_her_pays_a_relabelled_goal_only_where_the_world_was_at_rest() -> None:
    """put_near(red,green)'s literals hold from the first step, but red falls until step 3: a transition
    into steps 1 to 3 earns nothing, into steps 4 and 5 it earns 1."""
    horizon = 5
    goal_layout = LAYOUTS[SCENE]
    target, mask = goal_layout.encode([Literal("close", ("red", "green")), Literal("holding", ("red",), False)])
    goal = np.concatenate([target, mask])[None]
    achieved = np.repeat(layout.achieved_goal(target, mask)[None, None], horizon + 1, axis=1)
    motion = np.zeros((1, horizon + 1, 4), np.float32)
    motion[0, :4, 0] = 1.0  # red moving at steps 0..3
    obs = np.arange(horizon + 1, dtype=np.float32).reshape(1, -1, 1)  # obs = the step, to read it back
    replay = EpisodeReplay(4, horizon, 1, goal.shape[1], semantic_reward(SCENE), motion_size=4)
    replay.add(obs, achieved, motion, goal, np.zeros((1, horizon, 4)), np.zeros((1, horizon, 4)))
    batch = replay.sample(np.random.default_rng(0), 500)
    assert np.array_equal(batch.reward, (batch.next_obs[:, 0] >= 4).astype(np.float32))
    assert set(np.unique(batch.reward)) == {0.0, 1.0}


def test_a_saved_buffer_larger_than_the_capacity_loads_its_newest_episodes(tmp_path) -> None:
    horizon, goal_size = 2, 2
    reward = lambda a, d, m: layout.goal_reward(a, d)  # noqa: E731
    big = EpisodeReplay(4, horizon, 1, goal_size, reward)
    for episode in range(6):  # wraps: the ring holds episodes 2..5, the oldest (2) at next_index 2
        big.add(np.zeros((1, horizon + 1, 1)), np.zeros((1, horizon + 1, goal_size)), np.zeros((1, horizon + 1, 0)),
                np.full((1, goal_size), episode), np.zeros((1, horizon, 4)), np.zeros((1, horizon, 4)))
    big.save(tmp_path / "replay.npz")
    same = EpisodeReplay(4, horizon, 1, goal_size, reward)
    same.load(tmp_path / "replay.npz")
    assert np.array_equal(same.goal, big.goal) and same.next_index == big.next_index == 2
    small = EpisodeReplay(3, horizon, 1, goal_size, reward)
    small.load(tmp_path / "replay.npz")
    assert small.goal[:, 0].tolist() == [3, 4, 5] and small.size == 3 and small.next_index == 0


def test_a_save_that_stops_half_way_leaves_the_buffer_saved_before(tmp_path, monkeypatch) -> None:
    reward = lambda a, d, m: layout.goal_reward(a, d)  # noqa: E731
    replay = EpisodeReplay(2, 2, 1, 2, reward)
    replay.add(np.zeros((1, 3, 1)), np.zeros((1, 3, 2)), np.zeros((1, 3, 0)), np.ones((1, 2)), np.zeros((1, 2, 4)),
               np.zeros((1, 2, 4)))
    replay.save(tmp_path / "replay.npz")

    def stopped(file, **arrays) -> None:
        file.write(b"PK\x03\x04 half a zip")
        raise KeyboardInterrupt

    monkeypatch.setattr(np, "savez", stopped)
    with pytest.raises(KeyboardInterrupt):
        replay.save(tmp_path / "replay.npz")
    monkeypatch.undo()
    restored = EpisodeReplay(2, 2, 1, 2, reward)
    restored.load(tmp_path / "replay.npz")
    assert restored.size == 1 and np.array_equal(restored.goal[0], [1, 1])


def test_normaliser_tracks_mean_and_variance() -> None:
    rng = np.random.default_rng(0)
    data = rng.normal(3.0, 2.0, size=(5000, 4))
    norm = Normaliser(4)
    for chunk in np.split(data, 10):
        norm.update(chunk)
    assert np.allclose(norm.mean.numpy(), data.mean(0), atol=1e-6)
    assert np.allclose(norm.var.numpy(), data.var(0), rtol=1e-3)


def _actor() -> Actor:
    torch.manual_seed(0)
    return Actor(layout.observation_size(SCENE), layout.goal_size(SCENE))


def test_export_and_load_round_trip(tmp_path) -> None:
    actor = _actor()
    export(actor, tmp_path, SCENE, {"env_steps": 7})
    loaded, meta = load(tmp_path, SCENE)
    obs = np.random.default_rng(0).normal(size=(3, layout.observation_size(SCENE))).astype(np.float32)
    goal = np.zeros((3, layout.goal_size(SCENE)), np.float32)
    assert np.allclose(actor.act(obs, goal), loaded.act(obs, goal))
    assert meta["env_steps"] == 7


def test_the_log_std_clamp_is_applied_and_travels_with_the_export(tmp_path) -> None:
    actor = Actor(layout.observation_size(SCENE), layout.goal_size(SCENE), log_std_max=-1.0)
    with torch.no_grad():
        actor.net[-1].bias[4:] = 10.0  # log std far above the clamp
    obs = torch.zeros(2, layout.observation_size(SCENE))
    goal = torch.zeros(2, layout.goal_size(SCENE))
    assert torch.all(actor(obs, goal)[1] == -1.0)
    export(actor, tmp_path, SCENE, {})
    loaded, meta = load(tmp_path, SCENE)
    assert meta["log_std_max"] == -1.0 and torch.all(loaded(obs, goal)[1] == -1.0)
    del meta["log_std_max"]  # an actor exported before the clamp was a setting: the old default
    (tmp_path / "actor.json").write_text(json.dumps(meta))
    assert load(tmp_path, SCENE)[0].log_std_max == 2.0


def test_load_refuses_another_layout(tmp_path) -> None:
    export(_actor(), tmp_path, SCENE, {})
    meta = json.loads((tmp_path / "actor.json").read_text())
    meta["layout"]["semantic_atoms"] = meta["layout"]["semantic_atoms"][::-1]
    (tmp_path / "actor.json").write_text(json.dumps(meta))
    with pytest.raises(LayoutMismatchError, match="semantic_atoms"):
        load(tmp_path, SCENE)
    with pytest.raises(FileNotFoundError, match="no exported actor"):
        load(tmp_path / "missing", SCENE)


def test_controller_never_outputs_nan_or_out_of_range(tmp_path) -> None:
    actor = _actor()
    with torch.no_grad():
        actor.net[-1].bias.fill_(50.0)  # a saturating actor
    export(actor, tmp_path, SCENE, {})
    controller = SubgoalController(SCENE, tmp_path)
    obs = np.ones(layout.observation_size(SCENE), np.float32)
    controller.set_subgoal([], Idle.HOLD)
    assert np.array_equal(controller.act(obs), HOLD)  # no sub-goal, paused: hold still
    controller.set_subgoal([Literal("holding", ("red",))])
    action = controller.act(obs)
    assert np.isfinite(action).all() and np.abs(action).max() <= 1.0 and not np.array_equal(action, HOLD)
    assert np.array_equal(controller.act(np.full_like(obs, np.nan)), HOLD)
    assert np.array_equal(controller.act(obs[:5]), HOLD)
    assert np.isfinite(controller.act(obs, (-5, 2**63 - 1))).all()  # a malformed seed keys noise too
    with pytest.raises(VocabularyError):
        controller.set_subgoal([Literal("in_bin", ("red",))])


def test_controller_knows_when_its_subgoal_holds(tmp_path) -> None:
    export(_actor(), tmp_path, SCENE, {})
    controller = SubgoalController(SCENE, tmp_path)
    vector = np.zeros(controller.layout.size, np.float32)
    assert not controller.achieved(vector)  # no sub-goal
    controller.set_subgoal([Literal("holding", ("red",))])
    assert not controller.achieved(vector)
    vector[controller.layout.index(Literal("holding", ("red",)))] = 1.0
    assert controller.achieved(vector)
    # confirmed (the planner's rule) only once it held over SETTLE_STEPS distinct steps
    assert [controller.confirmed(step, vector) for step in range(10, 10 + SETTLE_STEPS)] == \
        [False] * (SETTLE_STEPS - 1) + [True]
    controller.set_subgoal([Literal("holding", ("red",))])  # the same sub-goal again: the count goes on
    assert controller.confirmed(10 + SETTLE_STEPS, vector)
    controller.set_subgoal([Literal("holding", ("green",))])
    assert not controller.confirmed(20, np.zeros_like(vector))


def test_sampled_actions_are_reproducible_from_their_key_and_differ_from_the_mean(tmp_path) -> None:
    export(_actor(), tmp_path, SCENE, {})
    sampled, mean = SubgoalController(SCENE, tmp_path), SubgoalController(SCENE, tmp_path, mode="mean")
    for controller in (sampled, mean):
        controller.set_subgoal([Literal("holding", ("red",))])
    obs = np.ones(layout.observation_size(SCENE), np.float32)
    assert np.array_equal(sampled.act(obs, (3, 7)), sampled.act(obs, (3, 7)))
    assert not np.array_equal(sampled.act(obs, (3, 7)), sampled.act(obs, (3, 8)))
    assert np.array_equal(mean.act(obs, (3, 7)), mean.act(obs, (4, 9)))
    assert not np.array_equal(sampled.act(obs, (3, 7)), mean.act(obs))
    with pytest.raises(ValueError, match="action mode"):
        SubgoalController(SCENE, tmp_path, mode="greedy")


def test_flat_continuous_actors_keep_their_goal_layout(tmp_path) -> None:
    actor = Actor(layout.observation_size(SCENE), layout.goal_size(SCENE, "positions"))
    export(actor, tmp_path, SCENE, {}, goal="positions")
    loaded, meta = load(tmp_path, SCENE)
    assert meta["layout"]["goal"] == "positions" and loaded.goal_size == 3 * 2
    with pytest.raises(ValueError, match="goal kind"):
        layout.goal_size(SCENE, "pixels")


@pytest.mark.parametrize(("target", "direction"), [(10.0, 1.0), (-100.0, -1.0)])
def test_the_temperature_moves_toward_the_configured_target_entropy(target: float, direction: float) -> None:
    from semgoal_policy.replay import Batch
    from semgoal_policy.sac import SacAgent, SacConfig

    rng = np.random.default_rng(0)
    n, obs_size, goal_size = 32, 6, 4
    batch = Batch(*(rng.standard_normal((n, k)).astype(np.float32) for k in (obs_size, goal_size, 4)),
                  np.zeros(n, np.float32), rng.standard_normal((n, obs_size)).astype(np.float32),
                  np.zeros((n, 4), np.float32), np.zeros(n, np.float32))
    agent = SacAgent(obs_size, goal_size, SacConfig(target_entropy=target))
    agent.update(batch)
    assert np.sign(agent.log_alpha.item()) == direction


def test_the_mean_penalty_keeps_cloned_finger_means_out_of_tanh_saturation() -> None:
    """Cloning a finger label of exactly -1 pushes the pre-tanh mean without bound; the penalty holds it."""
    import torch

    from semgoal_policy.replay import Batch
    from semgoal_policy.sac import SacAgent, SacConfig

    rng = np.random.default_rng(0)
    n, obs_size, goal_size = 64, 6, 4
    closed = np.tile(np.array([0.0, 0.0, 0.0, -1.0], np.float32), (n, 1))
    batch = Batch(*(rng.standard_normal((n, k)).astype(np.float32) for k in (obs_size, goal_size, 4)),
                  np.zeros(n, np.float32), rng.standard_normal((n, obs_size)).astype(np.float32),
                  closed, np.ones(n, np.float32))
    finger_means = {}
    for weight in (0.0, 1.0):
        torch.manual_seed(0)
        agent = SacAgent(obs_size, goal_size, SacConfig(mean_reg=weight, q_filter=False))
        for _ in range(200):
            agent.update(batch, batch)
        with torch.no_grad():
            finger_means[weight] = agent.actor(torch.as_tensor(batch.obs), torch.as_tensor(batch.goal))[0][:, 3].mean().item()
    assert finger_means[0.0] < -0.8 < -0.6 < finger_means[1.0] < 0.0  # held back, still closing


def test_derived_features_travel_with_the_export_and_the_controller_appends_them(tmp_path) -> None:
    scene, derived = "desk_cleanup", ("bin_target", "subject_offset")
    size = layout.observation_size(scene)
    actor = Actor(size + features.width(derived), layout.goal_size(scene))
    export(actor, tmp_path, scene, {}, derived=derived)
    loaded, meta = load(tmp_path, scene)
    assert derived_features(meta) == derived and loaded.obs_size == size + 5
    controller = SubgoalController(scene, tmp_path, mode="mean")
    controller.set_subgoal([Literal("in_bin", ("red",))])
    obs = np.random.default_rng(1).uniform(0.3, 1.2, size).astype(np.float32)
    goal = controller.goal
    assert np.allclose(controller.act(obs), loaded.act(features.augment(scene, obs, derived, goal), goal))
    meta["layout"]["derived_features"] = [["colour", 3]]
    (tmp_path / "actor.json").write_text(json.dumps(meta))
    with pytest.raises(LayoutMismatchError, match="unknown derived feature 'colour'"):
        load(tmp_path, scene)


def test_flat_agents_refuse_derived_features() -> None:
    with pytest.raises(ValueError, match="hierarchical agent only"):
        make_env("flat-semantic", "desk_cleanup", ("bin_target",))


def test_blocks_kept_awake_are_the_hierarchys_option() -> None:
    """The envs' blocks at rest sleep; `eval subgoals --awake` keeps the sub-goal episodes' blocks awake (as the
    actors were trained), and the flat baselines' task envs refuse that rather than ignore it."""
    import mujoco

    sleeping = int(mujoco.mjtEnableBit.mjENBL_SLEEP)
    assert make_env("hierarchical", "three_blocks").world.model.opt.enableflags & sleeping
    assert make_env("flat-semantic", "three_blocks").world.model.opt.enableflags & sleeping
    assert not make_env("hierarchical", "three_blocks", sleep=False).world.model.opt.enableflags & sleeping
    with pytest.raises(ValueError, match="blocks kept awake are for the hierarchical agent only"):
        make_env("flat-semantic", "three_blocks", sleep=False)


def test_lockstep_follows_the_decision_on_the_step_before_when_it_names_a_subgoal() -> None:
    assert lockstep_subgoal("pick(red)", "put_near(red,green)") == "pick(red)"
    assert lockstep_subgoal(None, "pick(red)") == "pick(red)"  # first step, or the step before named none
    assert lockstep_subgoal(None, None) is None  # the world waits


def test_followed_decision_reads_the_active_decisions_of_the_worlds_episode() -> None:
    from types import SimpleNamespace

    pick, empty = SimpleNamespace(status="active"), SimpleNamespace(status="empty")
    decisions = {(3, 4): pick, (3, 5): empty, (2, 5): pick}
    assert followed_decision(decisions, 3, 5) is pick  # the step before
    assert followed_decision(decisions, 3, 6) is None  # the step before named none, this one has not come
    assert followed_decision(decisions, 4, 0) is None  # another episode's decisions do not count


def test_an_actor_trained_on_another_feature_version_refuses_to_load(tmp_path, monkeypatch) -> None:
    actor = Actor(layout.observation_size("desk_cleanup") + features.width(("bin_target",)),
                  layout.goal_size("desk_cleanup"))
    export(actor, tmp_path, "desk_cleanup", {}, derived=("bin_target",))
    assert json.loads((tmp_path / "actor.json").read_text())["feature_versions"] == {"bin_target": 1}
    load(tmp_path, "desk_cleanup")
    monkeypatch.setitem(features.FEATURE_VERSIONS, "bin_target", 2)
    with pytest.raises(LayoutMismatchError, match="another version of the derived feature"):
        load(tmp_path, "desk_cleanup")


def test_holding_still_keeps_a_held_block(tmp_path) -> None:
    """Paused, the arm holds still; with a block between the closed fingers it keeps squeezing, so the block is
    not let slip (as it does with no step to act on: ``test_retreat.py``)."""
    from semgoal_policy.controller import HOLD_GRIP
    from semgoal_sim.world import FetchWorld

    export(_actor(), tmp_path, SCENE, {})
    controller = SubgoalController(SCENE, tmp_path)
    world = FetchWorld(SCENE)
    world.reset(np.array([[1.25, 0.70, 0.425], [1.40, 0.80, 0.425]]))
    controller.set_subgoal([], Idle.HOLD)
    assert np.array_equal(controller.act(world.observation()), HOLD)
    world.place_in_gripper("red")
    assert np.array_equal(controller.act(world.observation()), HOLD_GRIP)
    for _ in range(25):  # held still for a second: the block stays in the hand
        world.step(controller.act(world.observation()))
    assert world.view().holds("red")
    assert np.array_equal(controller.hold(np.full(3, np.nan)), HOLD)


def test_the_second_arm_acts_as_the_first_would_in_the_reflected_world() -> None:
    """The shipped actor drives the arm across the table through the reflection about the table's centre line: its
    command for a world is the reflection of the first arm's command for the reflected world."""
    from semgoal_core.arms import ArmFrame
    from semgoal_sim.world import FetchWorld

    world = FetchWorld("desk_cleanup", 3)
    world.reset(np.array([[1.2, 0.6, 0.425], [1.4, 0.8, 0.425], [1.3, 1.0, 0.425]]))
    first, second = SubgoalController("desk_cleanup", mode="mean"), SubgoalController("desk_cleanup", mode="mean", arm=1)
    for controller in (first, second):
        controller.set_subgoal([Literal("holding", ("green",))])
    observation = world.observation()
    seen = ArmFrame("desk_cleanup", 1).observation(observation)
    np.testing.assert_allclose(second.act(observation), ArmFrame("desk_cleanup", 1).action(first.act(seen)), atol=1e-5)
    shared = SubgoalController("desk_cleanup", arm=1, shared=True)
    assert shared.hold(observation)[0] > 0  # an idle empty hand across the table draws back towards its own side


@pytest.mark.parametrize("architecture", ["mlp", "object"])
def test_a_bf16_update_multiplies_in_bf16_and_moves_the_weights_as_fp32_does(architecture: str) -> None:
    """Under ``precision: bf16`` the networks' linear layers see bfloat16 inputs, while weights, losses and the
    actions the losses read stay fp32; one update from the same weights moves them in nearly the same direction."""
    import torch

    from semgoal_policy.replay import Batch
    from semgoal_policy.sac import SacAgent, SacConfig

    scene = "tabletop" if architecture == "object" else ""
    obs_size = layout.observation_size("tabletop") if scene else 6
    goal_size = layout.goal_size("tabletop") if scene else 4
    rng = np.random.default_rng(0)
    n = 64
    obs = rng.uniform(0.0, 1.0, (n, obs_size)).astype(np.float32)
    batch = Batch(obs, rng.integers(0, 2, (n, goal_size)).astype(np.float32), rng.uniform(-1, 1, (n, 4)).astype(np.float32),
                  rng.integers(0, 2, n).astype(np.float32), obs + 0.01, rng.uniform(-1, 1, (n, 4)).astype(np.float32),
                  np.ones(n, np.float32))
    moves = {}
    for precision in ("fp32", "bf16"):
        torch.manual_seed(0)
        agent = SacAgent(obs_size, goal_size, SacConfig(precision=precision, architecture=architecture), scene)
        seen: set[torch.dtype] = set()
        hook = torch.nn.modules.module.register_module_forward_hook(
            lambda module, inputs, output, seen=seen: seen.add(output.dtype) if isinstance(module, torch.nn.Linear) else None)
        before = torch.cat([p.detach().flatten() for p in agent.critic.parameters()])
        torch.manual_seed(1)
        metrics = agent.update(batch, batch)
        hook.remove()
        after = torch.cat([p.detach().flatten() for p in agent.critic.parameters()])
        assert np.isfinite(list(metrics.values())).all() and after.dtype == torch.float32
        assert seen == ({torch.bfloat16} if precision == "bf16" else {torch.float32})
        moves[precision] = after - before
    cosine = torch.nn.functional.cosine_similarity(moves["fp32"], moves["bf16"], dim=0).item()
    assert cosine > 0.9, cosine


def test_an_unknown_precision_is_refused() -> None:
    from semgoal_policy.sac import SacAgent, SacConfig

    with pytest.raises(ValueError, match="unknown precision 'fp8'; valid: fp32, bf16"):
        SacAgent(6, 4, SacConfig(precision="fp8"))


def test_the_networks_relus_in_place_give_the_values_and_gradients_of_plain_ones() -> None:
    """mlp's ReLUs overwrite their layer's output: the same forward values and gradients as out-of-place ReLUs, in fp32
    and under bf16 autocast (the update's)."""
    torch.manual_seed(0)
    net = mlp(6, 3, (16, 16))
    linears = [layer for layer in net if isinstance(layer, torch.nn.Linear)]

    def plain(x: torch.Tensor) -> torch.Tensor:
        for layer in linears[:-1]:
            x = functional.relu(layer(x))
        return linears[-1](x)

    for autocast in (False, True):
        x = torch.randn(32, 6)
        with torch.autocast("cpu", dtype=torch.bfloat16, enabled=autocast):
            ours, reference = net(x).float(), plain(x).float()
        torch.testing.assert_close(ours, reference, rtol=0, atol=0)
        grads = [torch.autograd.grad(out.square().sum(), list(net.parameters())) for out in (ours, reference)]
        for ours_grad, reference_grad in zip(*grads, strict=True):
            torch.testing.assert_close(ours_grad, reference_grad, rtol=0, atol=0)
