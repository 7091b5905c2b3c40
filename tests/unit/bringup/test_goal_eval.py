"""`./semgoal eval-goals`: a row per family and, last, the JSON line."""

import json

import pytest

from semgoal_bringup.experiments import goal_eval


@pytest.mark.slow
def test_eval_goals_prints_a_row_per_family_and_the_json_line(capsys) -> None:
    assert goal_eval.main(["--scene", "two_blocks", "--families", "hold", "--episodes", "2", "--json"]) == 0
    captured = capsys.readouterr()
    result = json.loads(captured.out.strip().splitlines()[-1])
    assert set(result) == {"two_blocks/hold", "overall", "fell_off"} and 0.0 <= result["overall"] <= 1.0
    assert result["fell_off"] == {"two_blocks/hold": 0.0}
    assert "two_blocks/hold" in captured.err and "of 2" in captured.err


@pytest.mark.slow
def test_eval_goals_checks_the_goal_again_after_lingering(capsys) -> None:
    assert goal_eval.main(["--scene", "two_blocks", "--families", "stack", "--episodes", "2", "--linger", "25",
                           "--json"]) == 0
    captured = capsys.readouterr()
    result = json.loads(captured.out.strip().splitlines()[-1])
    assert set(result["linger_holds"]) == {"two_blocks/stack"} and 0.0 <= result["linger_holds"]["two_blocks/stack"] <= 1
    assert "holds 25 steps on" in captured.err


@pytest.mark.slow
def test_eval_goals_runs_another_actor_in_process_only(capsys) -> None:
    from semgoal_policy.actor import models_dir

    actor = str(models_dir() / "two_blocks")
    assert goal_eval.main(["--scene", "two_blocks", "--families", "hold", "--episodes", "1", "--model-dir", actor,
                           "--json"]) == 0
    assert set(json.loads(capsys.readouterr().out.strip().splitlines()[-1])) == {"two_blocks/hold", "overall", "fell_off"}
    with pytest.raises(SystemExit):
        goal_eval.main(["--scene", "two_blocks", "--model-dir", actor, "--via-ros"])
