"""The tabletop through the graph: towers and the bin planned, watched and done at rest by the four nodes, with the
scripted expert standing in for the actor the scene does not have yet, in the steps of the in-process episode; the
recorder's MCAP of each reads back (the `mcap` reader) and replays state for state."""

import pytest

from semgoal_bringup.experiments.episodes import HierarchicalAgent
from semgoal_bringup.experiments.graph_eval import run_via_ros
from semgoal_bringup.tools import replay
from semgoal_policy.expert_actor import EXPERT

TASKS, SEED = ["Tower-4", "Sort"], 3_000_000


@pytest.mark.timeout(600)
def test_tabletop_tasks_through_the_graph_take_the_in_process_steps(tmp_path) -> None:
    agent = HierarchicalAgent("tabletop", EXPERT)
    expected = [agent.run(task, SEED) for task in TASKS]
    assert all(outcome.success for outcome in expected), expected
    through_graph = list(run_via_ros(TASKS, 1, SEED, EXPERT, record=tmp_path))
    assert [(o.task, o.success, o.steps, o.replans) for o in through_graph] == \
        [(o.task, o.success, o.steps, o.replans) for o in expected]
    for task in TASKS:
        episode = replay.read(tmp_path / f"{task}-{SEED}.mcap")
        told = replay.summary(episode)
        assert episode.first.scene == "tabletop" and "put_on(" in told and "succeeded" in told, told
        reproduced, why = replay.verify(episode)
        assert reproduced, why
