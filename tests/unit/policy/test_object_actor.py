"""The object-centric actor reads roles, not names or slots: the same output for the other blocks in any order, in
any scene, with two blocks or eight."""

import statistics

import numpy as np
import pytest
import torch

from semgoal_core import layout
from semgoal_core.vocabulary import LAYOUTS, SubGoal
from semgoal_policy import actor as actor_io
from semgoal_policy.object_actor import ObjectActor
from semgoal_policy.replay import Batch
from semgoal_policy.sac import SacAgent, SacConfig

GRIP = np.array([1.30, 0.62, 0.55])
SPOTS = np.array([[1.22, 0.55, 0.425], [1.38, 0.70, 0.425], [1.15, 0.74, 0.425], [1.45, 0.52, 0.425],
                  [1.30, 0.78, 0.425], [1.20, 0.62, 0.425], [1.40, 0.60, 0.425], [1.33, 0.50, 0.425]])


def _inputs(scene: str, positions: np.ndarray, subgoal: SubGoal) -> tuple[torch.Tensor, torch.Tensor]:
    obs = layout.observation(scene, GRIP, np.zeros(3), np.full(2, 0.04), np.zeros(2), positions, np.zeros_like(positions))
    goal = np.concatenate(LAYOUTS[scene].encode(subgoal.literals()))
    return torch.as_tensor(obs[None]), torch.as_tensor(goal[None])


@pytest.fixture(scope="module")
def policy() -> ObjectActor:
    torch.manual_seed(0)
    trained = ObjectActor("tabletop")
    trained.normaliser.update(np.stack([_inputs("tabletop", SPOTS[:n], SubGoal("pick", ("red",)))[0][0].numpy()
                                        for n in range(2, 9)]))
    return trained


def _act(policy: ObjectActor, scene: str, positions: np.ndarray, subgoal: SubGoal) -> np.ndarray:
    return policy(*_inputs(scene, positions, subgoal))[0].detach().numpy()


def test_the_other_blocks_in_any_order_give_the_same_command(policy: ObjectActor) -> None:
    subgoal = SubGoal("put_on", ("red", "green"))
    before = _act(policy, "tabletop", SPOTS[:6], subgoal)
    others = SPOTS[:6].copy()
    others[2:] = others[[4, 2, 5, 3]]  # blue, yellow, orange and purple trade places
    np.testing.assert_allclose(_act(policy, "tabletop", others, subgoal), before, atol=1e-5)
    swapped = SPOTS[:6].copy()
    swapped[[1, 2]] = swapped[[2, 1]]  # the reference is now blue, where green was, and green where blue was
    np.testing.assert_allclose(_act(policy, "tabletop", swapped, SubGoal("put_on", ("red", "blue"))), before, atol=1e-5)
    assert not np.allclose(_act(policy, "tabletop", SPOTS[:6], SubGoal("put_on", ("red", "blue"))), before, atol=1e-3)


def test_an_exported_object_actor_loads_for_any_scene_and_two_to_eight_blocks(policy: ObjectActor, tmp_path) -> None:
    actor_io.export(policy, tmp_path, "tabletop", {"steps": 0})
    subgoal = SubGoal("pick", ("red",))
    two = _act(policy, "tabletop", SPOTS[:2], subgoal)
    for scene in ("two_blocks", "desk_cleanup", "tabletop"):
        loaded, meta = actor_io.load(tmp_path, scene)
        assert meta["architecture"] == "object" and isinstance(loaded, ObjectActor)
        np.testing.assert_allclose(_act(loaded, scene, SPOTS[:2], subgoal), two, atol=1e-5)
    eight = actor_io.load(tmp_path, "tabletop")[0]
    assert np.all(np.isfinite(_act(eight, "tabletop", SPOTS, subgoal)))
    assert not np.allclose(_act(eight, "tabletop", SPOTS, subgoal), two, atol=1e-4)


def test_sac_trains_the_object_actor_with_a_critic_over_its_tokens() -> None:
    obs, goal = _inputs("tabletop", SPOTS[:4], SubGoal("put_in_bin", ("green",)))
    n = 16
    batch = Batch(obs.repeat(n, 1).numpy(), goal.repeat(n, 1).numpy(), np.zeros((n, 4), np.float32),
                  np.ones(n, np.float32), obs.repeat(n, 1).numpy(), np.zeros((n, 4), np.float32), np.zeros(n, np.float32))
    agent = SacAgent(obs.shape[1], goal.shape[1], SacConfig(architecture="object", actor_average_rate=0.5), "tabletop")
    before = [p.detach().clone() for p in agent.actor.net.parameters()]
    metrics = agent.update(batch)
    assert np.isfinite(list(metrics.values())).all()
    assert any(not torch.equal(a, b) for a, b in zip(before, agent.actor.net.parameters(), strict=True))
    resumed = SacAgent(obs.shape[1], goal.shape[1], SacConfig(architecture="object", actor_average_rate=0.5), "tabletop")
    resumed.load_state_dict(agent.state_dict())
    np.testing.assert_allclose(resumed.policy(obs, goal)[0].detach(), agent.policy(obs, goal)[0].detach())
    with pytest.raises(ValueError, match="unknown actor architecture"):
        SacAgent(obs.shape[1], goal.shape[1], SacConfig(architecture="transformer"), "tabletop")


def test_the_object_actor_acts_on_one_row_as_the_controller_asks(policy: ObjectActor) -> None:
    """The policy's controller hands the actor one observation, not a batch (the shipped tabletop actor crashed on it)."""
    obs, goal = _inputs("tabletop", SPOTS[:5], SubGoal("put_in_bin", ("blue",)))
    one = policy.act(obs[0].numpy(), goal[0].numpy())
    assert one.shape == (4,)
    np.testing.assert_allclose(one, policy.act(obs.numpy(), goal.numpy())[0], atol=1e-6)


@pytest.mark.slow
def test_in_a_scene_without_a_bin_the_shipped_actor_reads_the_bin_of_its_training_scene() -> None:
    """The tabletop actor always saw a bin; shown zeros for ``bin_target`` on the paper's two blocks (a bin spot right
    under the grip, which it never saw), it carried the block it was to put near red about for hundreds of control
    steps on 4 of MC-2's 20 starts from 3,000,000 and lost 2 (awake). Shown the tabletop's bin, it puts it near red
    within 120 steps (a let-go short of close re-plans once), half of them within 40: on every start awake, on all but
    3,000,003 with blocks at rest sleeping (red pushed away as the block came down beside it, on both); the paper's own
    actors and the desk keep their own bins."""
    from pathlib import Path

    from semgoal_bringup.experiments.episodes import make_agent
    from semgoal_core.vocabulary import SCENES
    from semgoal_policy.controller import SubgoalController

    tabletop = actor_io.models_dir() / "tabletop"
    assert SubgoalController("two_blocks", tabletop).bin_shown is SCENES["tabletop"].bin
    assert SubgoalController("desk_cleanup", tabletop).bin_shown is SCENES["desk_cleanup"].bin
    assert SubgoalController("two_blocks").bin_shown is None
    agent = make_agent("hierarchical", "two_blocks", actor_dir=Path(tabletop))
    outcomes = [agent.run("MC-2", 3_000_000 + start) for start in range(20)]
    solved = [outcome.steps for outcome in outcomes if outcome.success]
    assert len(solved) >= 19 and max(solved) <= 120 and statistics.median(solved) <= 40, [
        (outcome.seed, outcome.success, outcome.steps) for outcome in outcomes]
