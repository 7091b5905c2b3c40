"""The `./semgoal` dispatcher: grouped commands, the groups that were commands keep their old calls, and the
flat spellings of earlier releases still reach the same entries."""

import pytest

from semgoal_bringup.cli import ALIASES, COMMANDS, resolve, usage


@pytest.mark.parametrize("argv, target, rest", [
    (["eval", "goals", "--scene", "two_blocks"], "semgoal_bringup.experiments.goal_eval", ["--scene", "two_blocks"]),
    (["eval", "--tasks", "all"], "semgoal_bringup.experiments.evaluation", ["--tasks", "all"]),
    (["eval"], "semgoal_bringup.experiments.evaluation", []),
    (["train", "--recipe", "two_blocks"], "semgoal_bringup.experiments.training:train_main", ["--recipe", "two_blocks"]),
    (["train", "perception", "--images", "10"], "semgoal_bringup.experiments.perception_training", ["--images", "10"]),
    (["bench", "sim", "--json"], "semgoal_bench.sim", ["--json"]),
    (["eval-goals", "--scene", "x"], "semgoal_bringup.experiments.goal_eval", ["--scene", "x"]),
    (["bench-planner"], "semgoal_bench.planner", []),
    (["plan-pddl", "d", "p"], "strips_planner.plan_pddl", ["d", "p"]),
])
def test_commands_groups_and_old_spellings_reach_their_entries(argv, target, rest) -> None:
    (module, _), given = resolve(argv)
    assert (module, given) == (target, rest)


@pytest.mark.parametrize("argv", [["nope"], ["bench"], ["bench", "--json"], ["eval", "nothing"]])
def test_an_unknown_command_or_member_is_refused(argv) -> None:
    assert resolve(argv) is None


def test_every_alias_names_a_member_and_usage_lists_every_entry() -> None:
    assert all(sub in COMMANDS[group] for group, sub in ALIASES.values())
    text = usage()
    assert all(f"{group} {sub}" in text or f"{group} [{sub}]" in text for group, sub in ALIASES.values())
