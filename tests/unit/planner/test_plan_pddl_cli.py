"""The `./semgoal plan-pddl` contract: a plan line per action and exit 0, `unsolvable` and exit 1, exit 2
with a message on bad PDDL or a missing file."""

import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from strips_planner.plan_pddl import main as plan_pddl_main

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
    binary = tmp_path / "image.pddl"
    binary.write_bytes(b"\x89PNG\r\n\x1a\n\xff")
    assert plan_pddl_main([KEYS, str(binary)]) == 2
    assert "image.pddl: not UTF-8 text (byte 0x89 at offset 0)" in capsys.readouterr().err
    assert plan_pddl_main([KEYS, str(tmp_path)]) == 2
    assert "Is a directory" in capsys.readouterr().err


def test_a_goal_that_holds_at_the_start_is_an_empty_plan(tmp_path: Path, capsys) -> None:
    problem = tmp_path / "there.pddl"
    problem.write_text((FIXTURES / "keys-vault.pddl").read_text().replace("(and (at vault) (has master) (not (locked r2)))", "(at hall)"))
    assert plan_pddl_main([KEYS, str(problem)]) == 0
    assert capsys.readouterr().out == "; the goal holds in the initial state: an empty plan\n"


TOKENS_DOMAIN = """(define (domain Hops) (:requirements :strips)
  (:predicates (at ?x) (link ?x ?y) (PLANE?a))   ; '?' starts a token; names in any case
  (:action hop :parameters (?from ?to) :precondition (and (at?from) (link ?from?to))
   :effect (and (at ?to) (not (at ?from)))))"""
TOKENS_PROBLEM = """(define (problem p1) (:domain HOPS) (:objects a b c)
  (:init (AT a) (link a b) (link b c)) (:goal (at c)))"""


def test_a_question_mark_starts_a_token_and_names_ignore_case(tmp_path: Path, capsys) -> None:
    """zenotravel writes ``(aircraft?a)``: read as ``aircraft ?a``, as other PDDL readers do."""
    (tmp_path / "d.pddl").write_text(TOKENS_DOMAIN)
    (tmp_path / "p.pddl").write_text(TOKENS_PROBLEM)
    assert plan_pddl_main([str(tmp_path / "d.pddl"), str(tmp_path / "p.pddl")]) == 0
    assert capsys.readouterr().out.splitlines() == ["(hop a b)", "(hop b c)"]


@pytest.mark.parametrize("construct, snippet", [
    ("cost", ":effect (when (link ?to ?from) (increase (total-cost) 1))))"),
    ("requirement", "(:requirements :strips :numeric-fluents)"),
    ("derived", "(:derived (plane ?x) (not (plane ?x)))"),
])
def test_valid_but_unsupported_pddl_exits_3_naming_the_construct(tmp_path: Path, capsys, construct: str,
                                                                 snippet: str) -> None:
    domain = TOKENS_DOMAIN
    if construct == "cost":
        domain = domain.replace(":effect (and (at ?to) (not (at ?from)))))", snippet)
    elif construct == "requirement":
        domain = domain.replace("(:requirements :strips)", snippet)
    else:
        domain = domain.replace("(:action", snippet + " (:action")
    (tmp_path / "d.pddl").write_text(domain)
    (tmp_path / "p.pddl").write_text(TOKENS_PROBLEM)
    assert plan_pddl_main([str(tmp_path / "d.pddl"), str(tmp_path / "p.pddl")]) == 3
    err = capsys.readouterr().err
    assert "unsupported PDDL" in err and {"cost": "'increase'", "requirement": ":numeric-fluents",
                                          "derived": "depend on their own negation"}[construct] in err


EITHER_DOMAIN = """(define (domain depotish) (:requirements :typing)
  (:types crate hoist place - object)
  (:predicates (at ?x - (either crate hoist) ?p - place) (free ?p - place))
  (:action shift :parameters (?x - (either crate hoist) ?from ?to - place)
   :precondition (and (at ?x ?from) (free ?to)) :effect (and (at ?x ?to) (free ?from) (not (at ?x ?from)) (not (free ?to)))))"""
EITHER_PROBLEM = """(define (problem p) (:domain depotish) (:objects c - crate h - hoist a b d - place)
  (:init (at c a) (at h b) (free d)) (:goal (and (at c d) (at h a))))"""


def test_either_types_take_objects_of_any_member_type(tmp_path: Path, capsys) -> None:
    """storage's ``(either ...)`` parameters: planned, and the plan checks out step by step."""
    from semgoal_bench.validate_plan import invalid_step, read_plan
    from strips_planner.pddl import parse_domain, parse_problem

    (tmp_path / "d.pddl").write_text(EITHER_DOMAIN)
    (tmp_path / "p.pddl").write_text(EITHER_PROBLEM)
    assert plan_pddl_main([str(tmp_path / "d.pddl"), str(tmp_path / "p.pddl")]) == 0
    plan = read_plan(capsys.readouterr().out)
    domain = parse_domain(EITHER_DOMAIN)
    assert len(plan) == 2 and invalid_step(domain, parse_problem(EITHER_PROBLEM, domain), plan) is None
    assert invalid_step(domain, parse_problem(EITHER_PROBLEM, domain), [("shift", "a", "b", "d")]) is not None


@pytest.mark.slow
def test_the_command_starts_without_ros_or_numpy(tmp_path: Path) -> None:
    """`./semgoal plan-pddl` runs an isolated interpreter without site on the planner library's sources (about 0.05 s in
    all instead of 0.25 s): it needs no sourced environment, and the planner loads neither ROS nor numpy, nor
    the modules it avoids for start-up's sake (argparse, dataclasses)."""
    (tmp_path / "d.pddl").write_text(TOKENS_DOMAIN)
    (tmp_path / "p.pddl").write_text(TOKENS_PROBLEM)
    root = Path(__file__).resolve().parents[3]
    done = subprocess.run([str(root / "semgoal"), "plan-pddl", str(tmp_path / "d.pddl"), str(tmp_path / "p.pddl")],
                          env={"PATH": "/usr/bin:/bin"}, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines() == ["(hop a b)", "(hop b c)"]
    loaded = subprocess.run(
        [sys.executable, "-I", "-S", "-c", "import sys; sys.path.insert(0, sys.argv[1]); from strips_planner.plan_pddl "
         "import main; main(sys.argv[2:]); print(' '.join(sys.modules))", str(root / "src" / "strips_planner"),
         str(tmp_path / "d.pddl"), str(tmp_path / "p.pddl")], capture_output=True, text=True, check=True).stdout
    modules = {name.split(".")[0] for name in loaded.split("\n")[-2].split()}
    assert "strips_planner" in modules  # the planner library alone: nothing of semgoal, ROS or the venv
    assert not {m for m in modules if m.startswith("semgoal")} and not modules & {"numpy", "rclpy", "site", "argparse", "dataclasses"}


@pytest.mark.parametrize("argv, words", [
    ([KEYS], "give a DOMAIN and a PROBLEM file, not 1"),
    ([KEYS, KEYS, KEYS], "not 3"),
    ([KEYS, KEYS, "--search"], "--search needs a value"),
    ([KEYS, KEYS, "--search", "dfs"], "unknown search 'dfs'; valid: bfs, astar, gbfs"),
    ([KEYS, KEYS, "--heuristic=ff"], "unknown heuristic 'ff'; valid: blind, hmax, hff, lmcut"),
    ([KEYS, KEYS, "--fast"], "unknown option '--fast'"),
])
def test_a_bad_command_line_exits_2_with_the_usage_and_what_is_wrong(argv: list[str], words: str, capsys) -> None:
    assert plan_pddl_main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("usage: semgoal plan-pddl DOMAIN PROBLEM") and words in err


def test_help_names_every_search_heuristic_and_exit_code(capsys) -> None:
    assert plan_pddl_main(["--help"]) == 0
    out = capsys.readouterr().out
    assert all(word in out for word in ("bfs", "astar", "gbfs", "blind", "hmax", "hff", "lmcut", "--stats", "3 unsupported",
                                        "--time-limit", "4 no plan"))


def test_options_come_in_either_spelling_and_anywhere(capsys) -> None:
    problem = str(FIXTURES / "keys-vault.pddl")
    assert plan_pddl_main(["--search=astar", KEYS, "--heuristic", "hmax", problem, "--stats"]) == 0
    captured = capsys.readouterr()
    assert len(captured.out.splitlines()) == 9 and captured.err.startswith("expanded ")


def test_a_time_limit_stops_a_long_search_with_exit_4(tmp_path: Path, capsys) -> None:
    """Breadth-first search on twelve blocks runs for minutes; the limit stops it within its signal checks."""
    from semgoal_planner.blocksworld import DOMAIN_PATH, problem

    (tmp_path / "p.pddl").write_text(problem(12, seed=1))
    handler, started = signal.getsignal(signal.SIGALRM), time.perf_counter()
    assert plan_pddl_main([str(DOMAIN_PATH), str(tmp_path / "p.pddl"), "--time-limit", "0.3"]) == 4
    assert time.perf_counter() - started < 3.0
    assert "no plan within the time limit of 0.3 s" in capsys.readouterr().err
    assert signal.getsignal(signal.SIGALRM) is handler  # a test runner's own alarm keeps working


def test_a_time_limit_stops_a_long_grounding_too(tmp_path: Path, capsys) -> None:
    """Five parameters over 80 objects, a static condition on the last one bound failing every join: grounding's
    exploration alone runs for tens of seconds, and checks for the alarm as the search does."""
    objects = [f"o{i}" for i in range(80)]
    (tmp_path / "d.pddl").write_text(
        "(define (domain slow-join) (:requirements :strips :negative-preconditions) (:predicates (p ?x) (s ?x) (done))"
        " (:action a :parameters (?a ?b ?c ?d ?e) :precondition (and (p ?a) (p ?b) (p ?c) (p ?d) (p ?e) (not (s ?e)))"
        " :effect (done)))")
    (tmp_path / "p.pddl").write_text(
        f"(define (problem slow) (:domain slow-join) (:objects {' '.join(objects)})"
        f" (:init {' '.join(f'(p {o}) (s {o})' for o in objects)}) (:goal (done)))")
    started = time.perf_counter()
    assert plan_pddl_main([str(tmp_path / "d.pddl"), str(tmp_path / "p.pddl"), "--time-limit", "0.3"]) == 4
    assert time.perf_counter() - started < 3.0
    assert "no plan within the time limit of 0.3 s" in capsys.readouterr().err


@pytest.mark.parametrize("value", ["0", "-1", "nan", "soon"])
def test_a_time_limit_must_be_a_positive_number(value: str, capsys) -> None:
    assert plan_pddl_main([KEYS, str(FIXTURES / "keys-vault.pddl"), "--time-limit", value]) == 2
    assert "--time-limit takes a positive number of seconds" in capsys.readouterr().err


def test_a_time_limit_that_is_not_reached_changes_nothing(capsys) -> None:
    assert plan_pddl_main([KEYS, str(FIXTURES / "keys-vault.pddl"), "--time-limit=60"]) == 0
    assert len(capsys.readouterr().out.splitlines()) == 9


def test_lmcut_on_conditional_effects_exits_3_and_astar_takes_hmax_by_default(capsys) -> None:
    briefcase = [str(FIXTURES / "briefcase-domain.pddl"), str(FIXTURES / "briefcase-3.pddl"), "--search", "astar"]
    assert plan_pddl_main([*briefcase, "--heuristic", "lmcut"]) == 3
    assert "lmcut does not take conditional effects" in capsys.readouterr().err
    assert plan_pddl_main(briefcase) == 0
    assert len(capsys.readouterr().out.splitlines()) == 8
