"""In-process task episodes and the Table 1 reports (the shipped actors, a few episodes)."""

import csv
import json
import subprocess
from pathlib import Path

import numpy as np
import pytest

from semgoal_bringup.experiments import evaluation
from semgoal_bringup.experiments.episodes import make_agent
from semgoal_core.tasks import TASK_STEP_BUDGET, get_task

ROOT = Path(__file__).parents[3]


def test_hierarchical_episode_is_reproducible_and_bounded() -> None:
    agent = make_agent("hierarchical", "two_blocks")
    first, again = agent.run("MA-2", 3_000_000), agent.run("MA-2", 3_000_000)
    assert first == again and 0 < first.steps <= TASK_STEP_BUDGET
    with pytest.raises(ValueError, match="three_blocks"):
        agent.run("MC-3", 0)


def test_parse_tasks() -> None:
    assert evaluation.parse_tasks("all") == ["MC-2", "MA-2", "Swap-2", "MC-3", "MA-3", "DC-2", "DC-3", "DC-4"]
    assert evaluation.parse_tasks("swap-2, dc-4") == ["Swap-2", "DC-4"]
    with pytest.raises(KeyError, match="unknown task"):
        evaluation.parse_tasks("MC-2,XX-1")


@pytest.mark.slow
def test_eval_writes_table_csv_and_chart(tmp_path, capsys) -> None:
    code = evaluation.main(["--tasks", "MA-2", "--episodes", "2", "--seeds", "1", "--json", "--out", str(tmp_path)])
    assert code == 0
    summary = json.loads(capsys.readouterr().out.strip().splitlines()[-1])
    assert set(summary) == {"MA-2"} and 0.0 <= summary["MA-2"]["hierarchical"] <= 1.0
    table = (tmp_path / "table1.md").read_text()
    assert "Hierarchical Semantic (paper) | 3 | 2000k | 50 | 100" in table and "**hierarchical (ours)** | 1 |" in table
    rows = list(csv.DictReader((tmp_path / "table1.csv").open()))
    assert {(r["source"], r["task"]) for r in rows} == {("paper", "MA-2"), ("ours", "MA-2")}
    assert (tmp_path / "table1.png").stat().st_size > 5000


@pytest.mark.slow
def test_every_figure_of_a_results_file_traces_to_a_commit(tmp_path) -> None:
    """The table's JSON, CSV and markdown name the commit that produced them: this checkout's HEAD."""
    assert evaluation.main(["--tasks", "MC-2", "--episodes", "1", "--seeds", "1", "--out", str(tmp_path)]) == 0
    head = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "HEAD"], capture_output=True, text=True).stdout.strip()
    record = json.loads((tmp_path / "table1.json").read_text())["provenance"]
    assert record["commit"] == head and record["seed"] == evaluation.DEFAULT_SEED
    assert set(record["versions"]) >= {"mujoco", "torch", "numpy"} and "--tasks MC-2" in record["command"]
    ours = [r for r in csv.DictReader((tmp_path / "table1.csv").open()) if r["source"] == "ours"]
    assert ours and {r["commit"] for r in ours} == {head}
    assert f"Produced by commit {head[:12]} (" in (tmp_path / "table1.md").read_text()
    assert subprocess.run(["git", "-C", str(ROOT), "cat-file", "-e", f"{head}^{{commit}}"]).returncode == 0


def test_extra_training_seeds_follow_the_shipped_actor(tmp_path) -> None:
    for folder in ("two_blocks", "seeds/two_blocks/seed22", "seeds/two_blocks/seed21", "seeds/two_blocks/seed23-partial"):
        (tmp_path / folder).mkdir(parents=True)
        if not folder.endswith("partial"):
            (tmp_path / folder / "actor.json").write_text("{}")
    names = [d.relative_to(tmp_path).as_posix() for d in evaluation.actor_dirs("hierarchical", "two_blocks", 3, tmp_path)]
    assert names == ["two_blocks", "seeds/two_blocks/seed21", "seeds/two_blocks/seed22"]
    assert len(evaluation.actor_dirs("hierarchical", "two_blocks", 1, tmp_path)) == 1


def test_a_pool_file_names_the_pooled_training_seeds(tmp_path) -> None:
    for folder in ("desk_cleanup", "seeds/desk_cleanup/seed21", "seeds/desk_cleanup/seed25", "seeds/desk_cleanup/seed26"):
        (tmp_path / folder).mkdir(parents=True)
        (tmp_path / folder / "actor.json").write_text("{}")
    pool = tmp_path / "seeds/desk_cleanup/pool.json"
    pool.write_text(json.dumps({"actors": ["seed25", "seed26"], "with_shipped": False}))
    names = [d.relative_to(tmp_path).as_posix() for d in evaluation.actor_dirs("hierarchical", "desk_cleanup", 3, tmp_path)]
    assert names == ["seeds/desk_cleanup/seed25", "seeds/desk_cleanup/seed26"]
    pool.write_text(json.dumps({"actors": ["seed25", "seed27"], "with_shipped": False}))
    with pytest.raises(FileNotFoundError, match="seed27"):
        evaluation.actor_dirs("hierarchical", "desk_cleanup", 3, tmp_path)


@pytest.mark.parametrize("scene", ["two_blocks", "three_blocks", "desk_cleanup"])
def test_one_training_seed_is_the_shipped_actor(scene) -> None:
    """``--seeds 1`` evaluates what ships: the pool's first actor has the shipped weights."""
    from semgoal_policy.actor import models_dir

    first = evaluation.actor_dirs("hierarchical", scene, 1, models_dir())[0]
    assert (first / "actor.pt").read_bytes() == (models_dir() / scene / "actor.pt").read_bytes()


@pytest.mark.slow
def test_table_splits_rows_by_training_seed(tmp_path, capsys) -> None:
    """Two "seeds" that are the same shipped actor: pooled and per-seed rates must all agree."""
    from semgoal_policy.actor import models_dir

    shipped = models_dir() / "two_blocks"
    models = tmp_path / "models"
    (models / "seeds" / "two_blocks").mkdir(parents=True)
    (models / "two_blocks").symlink_to(shipped)
    (models / "seeds" / "two_blocks" / "seed9").symlink_to(shipped)
    argv = ["--tasks", "MA-2", "--episodes", "2", "--seeds", "2", "--jobs", "1", "--models", str(models), "--json"]
    assert evaluation.main([*argv, "--out", str(tmp_path)]) == 0
    rate = json.loads(capsys.readouterr().out.strip().splitlines()[-1])["MA-2"]["hierarchical"]
    table = (tmp_path / "table1.md").read_text()
    assert "**hierarchical (ours)** | 2 |" in table and "by training seed" in table
    per_seed = [line for line in table.splitlines() if line.startswith(("| shipped |", "| seed9 |"))]
    assert [line.split(" | ")[0] for line in per_seed] == ["| shipped", "| seed9"]
    assert {line.split(" | ")[-1] for line in per_seed} == {f"{100 * rate:.0f} |"}


@pytest.mark.slow
def test_eval_refuses_unknown_agents_and_missing_actors(tmp_path, capsys) -> None:
    with pytest.raises(SystemExit):
        evaluation.main(["--tasks", "MC-2", "--agents", "oracle"])
    assert evaluation.main(["--tasks", "MC-2", "--episodes", "1", "--models", str(tmp_path)]) == 2
    assert "no exported hierarchical actor" in capsys.readouterr().err


@pytest.mark.parametrize("args", [["--agents", "flat-semantic"], ["--via-ros"]])
def test_eval_keeps_blocks_awake_only_for_the_hierarchy_in_process(args: list[str], capsys) -> None:
    with pytest.raises(SystemExit):
        evaluation.main(["--tasks", "MC-2", "--awake", *args])
    assert "--awake runs the hierarchical agent in process" in capsys.readouterr().err


def test_eval_runs_the_graph_in_one_process_only_through_the_graph(capsys) -> None:
    with pytest.raises(SystemExit):
        evaluation.main(["--tasks", "MC-2", "--composed"])
    assert "--composed runs the graph's nodes in one process: add --via-ros" in capsys.readouterr().err


def test_wilson_interval_stays_wide_at_the_extremes() -> None:
    low, high = evaluation.wilson_interval(10, 10)
    assert high == 1.0 and 0.69 < low < 0.73  # 10 of 10 still admits ~72 %
    assert evaluation.wilson_interval(0, 50)[1] > 0.05
    low, high = evaluation.wilson_interval(25, 50)
    assert low < 0.5 < high and high - low == pytest.approx(0.27, abs=0.01)


def test_training_steps_read_in_thousands() -> None:
    """A run stops at the first whole batch of episodes past its budget: 300480 steps is a 300k run."""
    assert evaluation._steps_text({300_000, 300_480}) == "300k"
    assert evaluation._steps_text({300_000, 600_000}) == "300k-600k"


def test_the_graphs_episodes_are_compared_with_the_same_starts_in_process(capsys) -> None:
    from semgoal_bringup.experiments.episodes import Outcome

    in_process, via_ros = evaluation.Row("hierarchical"), evaluation.Row(evaluation.VIA_ROS)
    for seed, steps in ((7, 120), (8, 95)):
        in_process.add("shipped", Outcome("Tower-4", seed, True, steps))
    via_ros.add("shipped", Outcome("Tower-4", 7, True, 120), first_step_observed=False)
    via_ros.add("shipped", Outcome("Tower-4", 8, True, 96), first_step_observed=False)
    via_ros.add("shipped", Outcome("Tower-4", 9, False, 600), first_step_observed=False)
    counts = evaluation.compare_with_graph([in_process, via_ros], ["Tower-4"], "shipped", evaluation.TRUTH)
    assert counts == {"Tower-4": {"same": 1, "episodes": 3}}
    said = capsys.readouterr().err
    assert "1 of 3 episodes ended as in process" in said
    assert "seed 8: via ROS succeeded after 96 steps, in process succeeded after 95 steps" in said
    assert "seed 9: not run in process" in said


def test_a_pool_standing_in_for_the_shipped_actor_is_compared_by_its_first_actor(capsys) -> None:
    """three_blocks' pool runs the shipped actor as ``seed102`` in process (its ``pool.json`` without ``shipped``, the
    shipped actor first): the graph's ``shipped`` episodes are compared with it, not reported as never run."""
    from semgoal_bringup.experiments.episodes import Outcome

    in_process, via_ros = evaluation.Row("hierarchical"), evaluation.Row(evaluation.VIA_ROS)
    in_process.add("seed102", Outcome("MC-3", 7, True, 63))
    in_process.add("seed101", Outcome("MC-3", 7, True, 80))
    via_ros.add("shipped", Outcome("MC-3", 7, True, 63), first_step_observed=False)
    assert evaluation.compare_with_graph([in_process, via_ros], ["MC-3"], "shipped", evaluation.TRUTH) == {
        "MC-3": {"same": 1, "episodes": 1}}
    assert "not run in process" not in capsys.readouterr().err


def test_a_block_knocked_off_the_table_is_traced_to_the_edge_the_step_and_the_robots_step() -> None:
    """An in-process episode records the first block that left the table: which, over which edge, when and during
    which robot step; the miss says so, and ``--misses`` lists it per agent, training seed, task and start."""
    from semgoal_bringup.experiments.episodes import Outcome

    agent = make_agent("hierarchical", "two_blocks")

    def knock_red_off(world) -> None:  # a hand sweeping red over the table's near edge at the fifth control step
        if world.step_count == 5:
            world.set_block_pose("red", np.array([0.98, 0.63, 0.3]))

    start = get_task("MA-2").initial_state(3_000_000)[0]
    outcome = agent.run_goals(start, ("MA-2",), 3_000_000, label="MA-2", on_step=knock_red_off)
    assert not outcome.success and outcome.fell_off
    assert outcome.fall.block == "red" and outcome.fall.step == 5 and outcome.fall.during
    assert outcome.why.startswith("a block ended off the table: red went over the table's near edge at (0.98, 0.63) "
                                  "at control step 5, during ")
    row = evaluation.Row("hierarchical")
    row.add("shipped", outcome)
    row.add("shipped", Outcome("MA-2", 3_000_001, True, 80))
    assert evaluation.missed_in_process([row], ["MA-2"]) == [
        f"missed: hierarchical shipped MA-2 from seed 3000000: {outcome.why}"]


def test_an_episode_out_of_steps_names_the_goals_literals_still_unmet() -> None:
    start = get_task("MA-2").initial_state(3_000_000)[0]
    outcome = make_agent("hierarchical", "two_blocks").run_goals(start, ("MA-2",), 3_000_000, budget=3, label="MA-2")
    assert not outcome.success and outcome.unmet == ("not close(red,green)",)
    assert outcome.why.endswith(": not close(red,green) did not hold at the end")


def test_the_starts_the_graph_missed_from_the_camera_are_named(capsys) -> None:
    from semgoal_bringup.experiments.episodes import Outcome
    from semgoal_bringup.graph import Sight

    in_process, via_ros = evaluation.Row("hierarchical"), evaluation.Row(evaluation.VIA_ROS)
    for seed, success in ((7, True), (8, False), (9, False)):
        via_ros.add("expert", Outcome("Clean-8", seed, success, 600 if not success else 377), first_step_observed=False)
    assert evaluation.compare_with_graph([in_process, via_ros], ["Clean-8"], "expert", Sight("camera")) == {}
    said = capsys.readouterr().err
    assert "2 start(s) missed" in said and "Clean-8 from seed 8: failed after 600 steps" in said and "seed 7" not in said


@pytest.mark.slow
def test_a_table_of_tasks_the_paper_has_not_is_not_called_table_1(tmp_path) -> None:
    code = evaluation.main(["--tasks", "Tower-3", "--episodes", "1", "--models", "expert", "--jobs", "1",
                            "--out", str(tmp_path)])
    assert code == 0
    table = (tmp_path / "table1.md").read_text()
    assert table.startswith("# Task completion (%)") and "Table 1" not in table and "not the paper's" in table
