"""`./semgoal eval-subgoals`: its JSON contract, the horizon and action mode it is given, refused arguments."""

import json

import pytest

from semgoal_bringup.experiments.training import eval_subgoals_main


def _run(capsys, *extra: str) -> dict:
    assert eval_subgoals_main(["--scene", "two_blocks", "--episodes", "2", "--envs", "2", "--json", *extra]) == 0
    return json.loads(capsys.readouterr().out.strip().splitlines()[-1])


def test_prints_one_json_object_with_a_rate_per_subgoal_type(capsys) -> None:
    result = _run(capsys, "--seed", "2000000")
    assert result["scene"] == "two_blocks" and result["episodes"] == 2 and result["horizon"] == 50
    assert result["action_mode"] == "mean"
    rates = result["per_subgoal"]
    assert list(rates) == ["pick", "put_near", "put_away", "put_on"]
    assert all(rate in (0.0, 0.5, 1.0) for rate in rates.values())
    assert result["overall"] == pytest.approx(sum(rates.values()) / 4)


def test_a_one_step_horizon_leaves_no_time_to_confirm_a_subgoal(capsys) -> None:
    """A sub-goal counts once its literals held for several steps in a row, so one step never does."""
    result = _run(capsys, "--horizon", "1")
    assert result["horizon"] == 1 and result["overall"] == 0.0


def test_misses_lists_every_failed_episode_with_its_seed_and_why(capsys) -> None:
    result = _run(capsys, "--horizon", "1", "--seed", "2000000", "--misses")
    misses = result["misses"]
    assert len(misses) == 2 * len(result["per_subgoal"])  # one step confirms nothing: every episode missed
    assert [m["seed"] for m in misses[:2]] == [2000000, 2000001] and misses[0]["kind"] == "pick"
    assert all(m["subgoal"].startswith(m["kind"]) and m["why"] and all(m["why"]) for m in misses)
    assert "misses" not in _run(capsys, "--horizon", "1")


def test_shields_put_the_policy_nodes_rules_on_top_of_the_actor(capsys) -> None:
    result = _run(capsys, "--shields", "--horizon", "20")
    assert result["shields"] is True and set(result["per_subgoal"]) == {"pick", "put_near", "put_away", "put_on"}
    assert _run(capsys, "--horizon", "20")["shields"] is False


def test_the_sampled_actor_is_seeded_so_a_run_repeats(capsys) -> None:
    first, again = (_run(capsys, "--action-mode", "sample", "--horizon", "20") for _ in range(2))
    assert first["action_mode"] == "sample" and first == again


@pytest.mark.parametrize("mode", ["mean", "sample"])
def test_one_type_alone_gives_what_it_gives_among_the_others(mode, capsys) -> None:
    """Its starts and its sampled noise are the type's own: alone, put_near meets the same starts with the same
    actions (ten steps miss every put near, each with its own distances)."""
    extra = ("--action-mode", mode, "--horizon", "10", "--misses")
    every, alone = _run(capsys, *extra), _run(capsys, *extra, "--types", "put_near")
    assert list(alone["per_subgoal"]) == ["put_near"]
    assert alone["per_subgoal"]["put_near"] == every["per_subgoal"]["put_near"]
    near = [miss for miss in every["misses"] if miss["kind"] == "put_near"]
    assert near and alone["misses"] == near


def test_a_type_the_scene_lacks_is_refused(capsys) -> None:
    with pytest.raises(SystemExit) as exit_info:
        eval_subgoals_main(["--scene", "two_blocks", "--types", "put_near,put_in_bin"])
    assert exit_info.value.code == 2
    assert "put_in_bin: not a sub-goal type of two_blocks (it has pick, put_near, put_away, put_on)" in capsys.readouterr().err


@pytest.mark.parametrize("flag", ["--episodes", "--horizon", "--envs"])
def test_counts_below_one_are_refused(flag, capsys) -> None:
    with pytest.raises(SystemExit) as exit_info:
        eval_subgoals_main(["--scene", "two_blocks", flag, "0"])
    assert exit_info.value.code == 2 and f"argument {flag}: must be a whole number of at least 1" in capsys.readouterr().err
