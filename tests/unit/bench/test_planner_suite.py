"""`./semgoal bench-planner --suite DIR`: a folder of PDDL domains in the IPC layout, whole processes, every plan validated."""

import shutil
import time
from pathlib import Path

import pytest

from semgoal_bench.planner_suite import Planner, install, run, run_suite, suite_problems, validity

FIXTURES = Path(__file__).parents[1] / "planner" / "fixtures"


def _suite(tmp_path: Path) -> Path:
    for domain, problems in (("blocksworld", ["blocksworld-sussman"]), ("gripper", ["gripper-4balls"]),
                             ("logistics", ["logistics-p1"])):
        folder = tmp_path / domain
        folder.mkdir()
        shutil.copy(FIXTURES / f"{domain}-domain.pddl", folder / "domain.pddl")
        for i, name in enumerate(problems, 1):
            shutil.copy(FIXTURES / f"{name}.pddl", folder / f"p{i:02d}.pddl")
    own = tmp_path / "own-domains"  # the other IPC layouts: a domain file per problem
    own.mkdir()
    shutil.copy(FIXTURES / "gripper-domain.pddl", own / "domain_p01.pddl")
    shutil.copy(FIXTURES / "gripper-4balls.pddl", own / "p01.pddl")
    shutil.copy(FIXTURES / "gripper-domain.pddl", own / "p02-domain.pddl")  # airport's
    shutil.copy(FIXTURES / "gripper-4balls.pddl", own / "p02-gripper-4.pddl")
    shutil.copy(FIXTURES / "gripper-domain.pddl", own / "domain-p03.pddl")  # organic-synthesis's
    shutil.copy(FIXTURES / "gripper-4balls.pddl", own / "p03.pddl")
    shutil.copy(FIXTURES / "gripper-domain.pddl", own / "p04-domain.pddl")  # parcprinter's
    shutil.copy(FIXTURES / "gripper-4balls.pddl", own / "p04.pddl")
    return tmp_path


def test_the_suite_layout_pairs_each_problem_with_its_domain(tmp_path) -> None:
    found = suite_problems(_suite(tmp_path), per_domain=6)
    assert [(d, dom.name, p.name) for d, dom, p in found] == [
        ("blocksworld", "domain.pddl", "p01.pddl"), ("gripper", "domain.pddl", "p01.pddl"),
        ("logistics", "domain.pddl", "p01.pddl"), ("own-domains", "domain_p01.pddl", "p01.pddl"),
        ("own-domains", "p02-domain.pddl", "p02-gripper-4.pddl"), ("own-domains", "domain-p03.pddl", "p03.pddl"),
        ("own-domains", "p04-domain.pddl", "p04.pddl")]


@pytest.mark.slow
@pytest.mark.parametrize("search", ["gbfs", "lazy"])
def test_every_problem_is_solved_and_every_plan_validated(tmp_path, search: str) -> None:
    result = run_suite(_suite(tmp_path), ["ours"], per_domain=6, timeout=60, search=search, heuristic="hff")
    assert result["problems"] == 7 and result["coverage"] == {"ours": 7} and result["invalid_plans"] == {"ours": 0}
    assert result["errors"] == {"ours": 0}
    assert all(row["ours"]["median_s"] > 0 for row in result["domains"].values())


@pytest.mark.slow
def test_a_plan_an_unsolvable_task_and_a_refusal_are_told_apart(tmp_path) -> None:
    domain, problem = FIXTURES / "blocksworld-domain.pddl", FIXTURES / "blocksworld-sussman.pddl"
    ours = install("ours")
    solved = run(ours, domain, problem, "astar", "lmcut", 60)
    assert solved.status == "solved" and len(solved.plan) == 6 and solved.seconds > 0
    unsolvable = tmp_path / "unsolvable.pddl"
    unsolvable.write_text(problem.read_text().replace("(:goal (and", "(:goal (and (on a a)"))
    assert run(ours, domain, unsolvable, "gbfs", "hff", 60).status == "unsolvable"
    assert run(ours, domain, FIXTURES / "gripper-4balls.pddl", "gbfs", "hff", 60).status.startswith("error: ")


def test_an_invalid_plan_is_named(tmp_path) -> None:
    domain, problem = FIXTURES / "blocksworld-domain.pddl", FIXTURES / "blocksworld-sussman.pddl"
    assert validity(domain, problem, None) == ""
    assert validity(domain, problem, ["(fly a)"]) == "step 1 (fly a): no such action with 1 arguments"
    assert validity(domain, problem, ["(pickup a)"]).startswith("step 1 (pickup a): precondition")  # c lies on a
    assert validity(domain, problem, []).startswith("the goal")


def test_a_plan_for_a_task_the_validator_cannot_read_is_unchecked_not_invalid(tmp_path) -> None:
    """Another planner may solve what our reader refuses (numeric fluents): its plan is counted as unchecked."""
    domain = tmp_path / "domain.pddl"
    domain.write_text((FIXTURES / "blocksworld-domain.pddl").read_text().replace(
        "(:predicates", "(:requirements :numeric-fluents) (:predicates", 1))
    assert validity(domain, FIXTURES / "blocksworld-sussman.pddl", ["(pickup c)"]) is None


@pytest.mark.slow
def test_pyperplan_and_fast_downward_run_beside_ours_and_their_plans_are_checked(tmp_path) -> None:
    """The two reference planners install into .bench/ (pinned) and run as whole processes; on this small suite
    each solves everything with a valid plan, and their times are set beside ours."""
    result = run_suite(_suite(tmp_path), ["ours", "pyperplan", "fast-downward"], per_domain=6, timeout=60,
                       search="astar", heuristic="lmcut")
    assert result["left_out"] == {}
    assert result["coverage"] == {"ours": 7, "pyperplan": 7, "fast-downward": 7}
    assert result["invalid_plans"] == {"ours": 0, "pyperplan": 0, "fast-downward": 0}
    assert set(result["median_ratio_to_ours"]) == {"pyperplan", "fast-downward"}


@pytest.mark.slow
def test_a_time_out_ends_the_planner_and_its_children(tmp_path) -> None:
    """Fast Downward's driver runs its search as a child; a time-out must end both, or the search goes on
    using a core and skews every later time."""
    marker = tmp_path / "child.pid"
    spawner = Planner("spawner", lambda *_: ["bash", "-c", f"sleep 300 & echo $! > {marker}; wait"],
                      lambda *_: None)
    domain, problem = FIXTURES / "blocksworld-domain.pddl", FIXTURES / "blocksworld-sussman.pddl"
    assert run(spawner, domain, problem, "gbfs", "hff", 1).status == "timeout"
    child = int(marker.read_text())
    deadline = time.monotonic() + 5
    while Path(f"/proc/{child}").exists() and "Z" not in Path(f"/proc/{child}/stat").read_text().rsplit(")", 1)[1][:3]:
        assert time.monotonic() < deadline, "the planner's child outlived the time-out"
        time.sleep(0.05)
