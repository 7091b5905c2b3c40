"""`./semgoal eval-goals`: a row per family and, last, the JSON line."""

import json

from semgoal_bringup import goal_eval


def test_eval_goals_prints_a_row_per_family_and_the_json_line(capsys) -> None:
    assert goal_eval.main(["--scene", "two_blocks", "--families", "hold", "--episodes", "2", "--json"]) == 0
    captured = capsys.readouterr()
    result = json.loads(captured.out.strip().splitlines()[-1])
    assert set(result) == {"two_blocks/hold", "overall"} and 0.0 <= result["overall"] <= 1.0
    assert "two_blocks/hold" in captured.err and "of 2" in captured.err
