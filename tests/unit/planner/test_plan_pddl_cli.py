"""The `./semgoal plan-pddl` contract: a plan line per action and exit 0, `unsolvable` and exit 1, exit 2
with a message on bad PDDL or a missing file."""

from pathlib import Path

import pytest

from semgoal_planner.cli import plan_pddl_main

FIXTURES = Path(__file__).parent / "fixtures"
KEYS = str(FIXTURES / "keys-domain.pddl")


@pytest.mark.parametrize(("search", "heuristic"), [("bfs", "blind"), ("astar", "lmcut"), ("astar", "hmax"), ("gbfs", "hff")])
def test_a_plan_is_printed_one_action_per_line_in_lower_case(search: str, heuristic: str, capsys) -> None:
    code = plan_pddl_main([KEYS, str(FIXTURES / "keys-vault.pddl"), "--search", search, "--heuristic", heuristic])
    lines = capsys.readouterr().out.splitlines()
    assert code == 0
    assert lines[0] == "(move hall r1)" and lines[-1] == "(take master vault)"
    assert search == "gbfs" or len(lines) == 9


def test_an_unsolvable_problem_prints_unsolvable_and_exits_1(tmp_path: Path, capsys) -> None:
    problem = tmp_path / "stuck.pddl"  # keys are never put down, so k1 cannot lie in the hall again
    problem.write_text((FIXTURES / "keys-vault.pddl").read_text().replace("(has master)", "(lies k1 hall)"))
    assert plan_pddl_main([KEYS, str(problem)]) == 1
    captured = capsys.readouterr()
    assert captured.out == "unsolvable\n"
    assert "(lies k1 hall) is not reachable" in captured.err


def test_bad_pddl_and_missing_files_exit_2_with_a_message(tmp_path: Path, capsys) -> None:
    broken = tmp_path / "broken.pddl"
    broken.write_text("(define (domain keys)\n  (:predicates (at ?r)")
    assert plan_pddl_main([str(broken), str(FIXTURES / "keys-vault.pddl")]) == 2
    assert "bad PDDL: 2:3: '(' is never closed" in capsys.readouterr().err
    assert plan_pddl_main([KEYS, str(tmp_path / "absent.pddl")]) == 2
    assert "absent.pddl" in capsys.readouterr().err
