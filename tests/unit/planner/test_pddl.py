"""The PDDL reader: valid domains and problems, and malformed input named by line and column."""

import random
from pathlib import Path

import pytest

from semgoal_planner.blocksworld import DOMAIN_PATH
from strips_planner import _sexpr
from strips_planner.pddl import PddlError, _UnlocatedError, parse_domain, parse_problem, parse_sexpr

FIXTURES = Path(__file__).parent / "fixtures"
DOMAINS = Path(DOMAIN_PATH).parent


def test_reads_typed_domain_with_constants() -> None:
    domain = parse_domain((FIXTURES / "gripper-domain.pddl").read_text())
    assert domain.name == "gripper-typed"
    assert domain.constants == {"left": "gripper", "right": "gripper"}
    assert [a.name for a in domain.actions] == ["move", "pick", "drop"]
    assert domain.predicates["carry"] == ("ball", "gripper")


def test_reads_problem_with_objects_init_and_goal() -> None:
    domain = parse_domain((FIXTURES / "blocksworld-domain.pddl").read_text())
    problem = parse_problem((FIXTURES / "blocksworld-sussman.pddl").read_text(), domain)
    assert set(problem.objects) == {"a", "b", "c"}
    assert len(problem.init) == 6 and len(problem.goal) == 2


DOMAIN_HEAD = "(define (domain d) (:requirements :strips :typing)\n (:predicates (p ?x) (q))\n"


@pytest.mark.parametrize(("text", "where", "words"), [
    ("(define (domain d)", "1:1", "never closed"),
    ("; a comment (with a paren\n(define (domain d) ; another (\n ) x", "3:4", "after the end"),
    ("(define (domain d)))", "1:20", "after the end"),
    (DOMAIN_HEAD + " (:action a :parameters (?x) :effect (forall (?y) (p ?y))))", "3:38", "'forall' in an effect is not supported"),
    (DOMAIN_HEAD + " (:action a :parameters (?x) :precondition (r ?x) :effect (q)))", "3:44", "unknown predicate"),
    (DOMAIN_HEAD + " (:action a :parameters (?x) :precondition (p ?y) :effect (q)))", "3:47", "unknown variable"),
    (DOMAIN_HEAD + " (:action a :parameters (?x) :precondition (p ?x ?x) :effect (q)))", "3:44", "takes 1 argument"),
    (DOMAIN_HEAD + " (:action a :parameters (?x) :effect (and (q) (assign (f) 1))))", "3:47", "'assign' in an effect"),
    ("(define (domain d) (:requirements :fluents))", "1:20", "unsupported requirement"),
    (DOMAIN_HEAD + " (:action a :parameters (?x - thing) :effect (q)))", "3:26", "unknown type"),
    ("(define (domain d) (:requirements :adl)\n (:predicates (p))\n (:action a :parameters () :precondition (p)"
     " :effect (when (p) (not (p)))))", "3:54", "'when' in an effect is not supported"),
])
def test_malformed_domain_names_line_and_column(text: str, where: str, words: str) -> None:
    with pytest.raises(PddlError) as error:
        parse_domain(text)
    assert str(error.value).startswith(where) and words in str(error.value)


@pytest.mark.parametrize("requirement", [":adl", ":conditional-effects", ":quantified-preconditions",
                                         ":derived-predicates"])
def test_a_declared_requirement_that_the_domain_does_not_use_is_read(requirement: str) -> None:
    """Many IPC domains declare :adl and stay STRIPS: the reader refuses a construct where it is used, not the
    declaration."""
    domain = parse_domain(f"(define (domain d) (:requirements :strips {requirement}) (:predicates (p ?x) (q))"
                          " (:action a :parameters (?x) :precondition (p ?x) :effect (q)))")
    assert [a.name for a in domain.actions] == ["a"]


def test_malformed_problem_names_the_problem() -> None:
    domain = parse_domain((FIXTURES / "blocksworld-domain.pddl").read_text())
    with pytest.raises(PddlError, match="unknown object or constant 'z'"):
        parse_problem("(define (problem p) (:domain blocksworld) (:objects a) (:init (clear z)) (:goal (clear a)))", domain)
    with pytest.raises(PddlError, match="not 'blocksworld'"):
        parse_problem("(define (problem p) (:domain other) (:objects a) (:init) (:goal (clear a)))", domain)
    with pytest.raises(PddlError, match=":goal"):
        parse_problem("(define (problem p) (:domain blocksworld) (:objects a) (:init))", domain)


def _python_pass(text: str) -> list | None:
    """The reader's Python fast pass, None where it finds the text malformed."""
    try:
        return parse_sexpr(text)
    except (PddlError, _UnlocatedError):
        return None


def test_the_c_pass_reads_every_shipped_and_fixture_file_as_the_python_pass_does() -> None:
    files = sorted(FIXTURES.glob("*.pddl")) + sorted(DOMAINS.glob("*.pddl"))
    assert len(files) >= 10
    for path in files:
        text = path.read_text()
        assert _sexpr.sexpr(text) == parse_sexpr(text), path.name


def test_the_c_pass_agrees_with_the_python_pass_on_random_text() -> None:
    """Tokens, comments, `?` splits, Python's ASCII whitespace (0x1c-0x1f included) and every structural
    error (None from C where Python raises)."""
    pieces = ["(", ")", "?", ";", "\n", " ", "\t", "\x0b", "\x1c", "\x1f", "a", "B", "-", "x?y", "define", "?Z;"]
    rng = random.Random(0)
    for _ in range(20000):
        text = "".join(rng.choice(pieces) for _ in range(rng.randint(0, 12)))
        assert _sexpr.sexpr(text) == _python_pass(text), repr(text)


def test_non_ascii_text_is_left_to_the_python_pass() -> None:
    text = "; café\n(define (domain d) (:predicates (p)))"
    assert _sexpr.sexpr(text) is None
    assert parse_domain(text).predicates == {"p": ()}
