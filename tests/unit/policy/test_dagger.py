"""DAgger's parts: the expert labels the states the actor reached, the recorder keeps what the executive asked, and
fitting moves the actor toward the labels."""

import numpy as np
import pytest
import torch

from semgoal_core.layout import observation_size
from semgoal_policy.dagger import Aggregate, DaggerConfig, Recorder, collect_subgoals, fit, label
from semgoal_policy.expert_actor import ExpertActor
from semgoal_policy.object_actor import ObjectActor
from semgoal_sim.env import SubgoalEnv

SCENE = "tabletop"


@pytest.fixture(scope="module")
def reached() -> tuple[ObjectActor, Aggregate, float]:
    """An untrained actor drives four short sub-goal episodes (its normaliser fitted to their starts)."""
    torch.manual_seed(0)
    envs = [SubgoalEnv(SCENE, derived=("bin_target",)) for _ in range(2)]
    for env in envs:
        env.max_steps = 6
    actor = ObjectActor(SCENE, derived_size=2)
    actor.normaliser.update(np.stack([env.reset(seed=i)[0]["observation"] for i, env in enumerate(envs)]))
    states, success = collect_subgoals(envs, actor, 4, seed=600_000)
    return actor, states, success


def test_every_state_the_actor_reached_is_labelled_by_the_expert(reached) -> None:
    _, states, success = reached
    obs, goal, labels = states.arrays()
    assert len(states) == 4 * 6 and obs.shape[1] == observation_size(SCENE) + 2 and 0.0 <= success <= 1.0
    assert np.allclose(labels, ExpertActor(SCENE).act(obs[:, :observation_size(SCENE)], goal), atol=1e-6)
    assert np.allclose(label(SCENE, obs, goal), labels, atol=1e-6)


def test_fitting_moves_the_actor_toward_the_labels_and_keeps_its_normaliser(reached) -> None:
    actor, states, _ = reached
    obs, goal, labels = (torch.as_tensor(a) for a in states.arrays())

    def error() -> float:
        with torch.no_grad():
            return float(((torch.tanh(actor(obs, goal)[0]) - labels) ** 2).sum(-1).mean())

    before, statistics = error(), actor.normaliser.block.mean.clone()
    fit(actor, states, DaggerConfig(epochs=30, batch_size=8, lr=1e-3), np.random.default_rng(0))
    assert error() < 0.5 * before
    assert torch.equal(actor.normaliser.block.mean, statistics) and not actor.training


def test_the_recorder_answers_as_the_actor_and_keeps_each_question(reached) -> None:
    actor, states, _ = reached
    obs, goal, _ = states.arrays()
    recorder = Recorder(actor)
    assert np.array_equal(recorder.act(obs[0], goal[0]), actor.act(obs[0], goal[0]))
    recorder.act(obs[1], goal[1], np.zeros(4))
    assert np.array_equal(np.stack(recorder.obs), obs[:2]) and np.array_equal(np.stack(recorder.goal), goal[:2])


def test_an_aggregate_refuses_states_without_as_many_labels() -> None:
    with pytest.raises(ValueError, match="3 states, 3 goals and 2 labels"):
        Aggregate().add(np.zeros((3, 5)), np.zeros((3, 4)), np.zeros((2, 4)))
