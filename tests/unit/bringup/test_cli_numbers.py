"""Every command refuses a count, seed or time limit out of range before it starts work: exit 2 with the option
and the reason, never a traceback further on (a negative seed deep in numpy, a mean of no episodes)."""

import pytest

from semgoal_bringup.cli import main

REFUSED = [
    (["expert", "--task", "DC-3", "--episodes", "0"], "--episodes"),
    (["expert", "--task", "DC-3", "--seed", "-1"], "--seed"),
    (["render", "--task", "DC-3", "--seed", "-5", "--out", "x.png"], "--seed"),
    (["eval", "--tasks", "DC-2", "--seed", "-1"], "--seed"),
    (["eval", "--tasks", "DC-2", "--jobs", "0"], "--jobs"),
    (["eval", "--tasks", "DC-2", "--episodes", "-2"], "--episodes"),
    (["eval", "subgoals", "--scene", "two_blocks", "--episodes", "0"], "--episodes"),
    (["eval", "goals", "--scene", "two_blocks", "--ros-episodes", "0"], "--ros-episodes"),
    (["eval", "arms", "--task", "DC-4", "--episodes", "0"], "--episodes"),
    (["eval", "together", "--task", "DC-4", "--jobs", "-1"], "--jobs"),
    (["bench", "sim", "--steps", "0"], "--steps"),
    (["bench", "graph", "--episodes", "0"], "--episodes"),
    (["bench", "eval", "--episodes", "0"], "--episodes"),
    (["bench", "planner", "--sizes", "4,x"], "--sizes"),
    (["bench", "planner", "--timeout", "nan"], "--timeout"),
    (["bench", "policy", "--repeats", "0"], "--repeats"),
    (["goal", "DC-3", "--wait", "--timeout", "-1"], "--timeout"),
    (["train", "dagger", "--scene", "two_blocks", "--epochs", "0"], "--epochs"),
    (["sweep", "--recipe", "two_blocks", "--seeds", "1", "--workers", "0"], "--workers"),
    (["study", "run", "protocol.yaml", "--participant", "P1", "--row", "-7"], "--row"),
]


@pytest.mark.parametrize(("argv", "option"), REFUSED, ids=[" ".join(argv) for argv, _ in REFUSED])
def test_a_number_out_of_range_exits_2_naming_the_option(argv: list[str], option: str, capsys) -> None:
    with pytest.raises(SystemExit) as stopped:
        main(argv)
    error = capsys.readouterr().err
    assert stopped.value.code == 2 and f"argument {option}: must be" in error, error


@pytest.mark.parametrize(("argv", "words"), [
    (["render", "--task", "DC-9", "--out", "x.png"], "unknown task 'DC-9'"),
    (["model-card", "/nonexistent"], "no exported actor (actor.json) in /nonexistent"),
    (["eval", "subgoals", "--scene", "two_blocks", "--model-dir", "/nonexistent"], "no exported actor in /nonexistent"),
    (["sweep", "--recipe", "nonexistent", "--seeds", "1"], "no recipe 'nonexistent'"),
    (["train", "--recipe", "two_blocks", "--steps", "-5"], "setting steps = -5 is out of its range [1, ∞)"),
    (["train", "--recipe", "two_blocks", "--lr", "nan"], "setting sac.lr = nan is out of its range (0, ∞)"),
    (["train", "--recipe", "two_blocks", "--demo-fraction", "1.5"], "setting demo_fraction = 1.5 is out of its range [0, 1]"),
])
def test_a_name_or_folder_that_is_not_there_exits_2_with_the_reason(argv: list[str], words: str, capsys) -> None:
    with pytest.raises(SystemExit) as stopped:
        main(argv)
    assert stopped.value.code == 2 and words in capsys.readouterr().err


def test_a_file_that_is_not_mcap_is_refused_by_replay(tmp_path, capsys) -> None:
    garbage = tmp_path / "run.mcap"
    garbage.write_text("not a recording\n")
    assert main(["replay", str(garbage)]) == 2
    assert "run.mcap: not a valid MCAP file" in capsys.readouterr().err
