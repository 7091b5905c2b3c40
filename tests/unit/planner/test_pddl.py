"""The PDDL reader: valid domains and problems, and malformed input named by line and column."""

import random
from pathlib import Path

import pytest

from semgoal_planner.blocksworld import DOMAIN_PATH
from strips_planner import _reader
from strips_planner.pddl import Atom, Condition, PddlError, _UnlocatedError, parse_domain, parse_problem, parse_sexpr

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
    (DOMAIN_HEAD + " (:action a :parameters (?x) :effect (forall (?y))))", "3:38", "(forall (VARIABLES) EFFECT) takes"),
    (DOMAIN_HEAD + " (:action a :parameters (?x) :precondition (r ?x) :effect (q)))", "3:44", "unknown predicate"),
    (DOMAIN_HEAD + " (:action a :parameters (?x) :precondition (p ?y) :effect (q)))", "3:47", "unknown variable"),
    (DOMAIN_HEAD + " (:action a :parameters (?x) :precondition (p ?x ?x) :effect (q)))", "3:44", "takes 1 argument"),
    (DOMAIN_HEAD + " (:action a :parameters (?x) :effect (and (q) (assign (f) 1))))", "3:47", "'assign' is not supported here"),
    ("(define (domain d) (:requirements :fluents))", "1:20", "unsupported requirement"),
    (DOMAIN_HEAD + " (:action a :parameters (?x - thing) :effect (q)))", "3:26", "unknown type"),
    ("(define (domain d) (:requirements :adl)\n (:predicates (p))\n (:action a :parameters () :precondition (p)"
     " :effect (when (p))))", "3:54", "(when CONDITION EFFECT) takes"),
    (DOMAIN_HEAD + " (:action a :parameters (?x) :effect (or (q) (p ?x))))", "3:38", "'or' is not an effect"),
    (DOMAIN_HEAD + " (:derived (p ?x) (p ?y)))", "3:22", "unknown variable '?y'"),
    (DOMAIN_HEAD + " (:derived (p ?x ?y) (q)))", "3:12", "p takes 1 argument(s), its :derived head 2"),
    (DOMAIN_HEAD + " (:derived (p ?x)))", "3:2", "(:derived (PREDICATE ?x - type ...) CONDITION) takes a head"),
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
        assert _reader.sexpr(text) == parse_sexpr(text), path.name


def test_the_c_pass_agrees_with_the_python_pass_on_random_text() -> None:
    """Tokens, comments, `?` splits, Python's ASCII whitespace (0x1c-0x1f included) and every structural
    error (None from C where Python raises)."""
    pieces = ["(", ")", "?", ";", "\n", " ", "\t", "\x0b", "\x1c", "\x1f", "a", "B", "-", "x?y", "define", "?Z;"]
    rng = random.Random(0)
    for _ in range(20000):
        text = "".join(rng.choice(pieces) for _ in range(rng.randint(0, 12)))
        assert _reader.sexpr(text) == _python_pass(text), repr(text)


def test_non_ascii_text_is_left_to_the_python_pass() -> None:
    text = "; café\n(define (domain d) (:predicates (p)))"
    assert _reader.sexpr(text) is None
    assert parse_domain(text).predicates == {"p": ()}


def _outcome(read, *texts: str) -> tuple:
    """What ``read`` makes of the texts: every field of the domain or problem, or the error's class and words."""
    try:
        return ("read", vars(read(*texts)))
    except PddlError as error:
        return (type(error).__name__, str(error))


def _domain_and_problem(domain: str, problem: str):
    return parse_problem(problem, parse_domain(domain))


def _random_pddl(rng: random.Random) -> tuple[str, str]:
    """A small typed domain and problem where an atom may be wrong now and then: an unknown name, a wrong
    count, a wrong or wider type; or fine through a subtype, an ``either``, an equality, a negation with or
    without its requirement."""
    types = ["object", "t1", "t2", "t3"]

    def pick(good: list[str], bad: str) -> str:
        return bad if rng.random() < 0.02 else rng.choice(good)

    kind = lambda: pick([*types, "(either t1 t3)"], "nosuch")  # noqa: E731
    requirements = " ".join(rng.sample([":strips", ":typing", ":negative-preconditions", ":equality"], rng.randint(1, 4)))
    predicates = {f"p{i}": [kind() for _ in range(rng.randint(0, 2))] for i in range(3)}
    params = [(f"?v{i}", rng.choice(types[1:])) for i in range(rng.randint(0, 3))]
    terms = [*(v for v, _ in params), "c1", "c2"]

    def literal(negation: bool = True, equality: bool = True) -> str:
        name = pick([*predicates, *predicates, *["="] * equality], "nosuch")
        arity = 2 if name == "=" else len(predicates.get(name, [])) + (rng.choice([1, -1]) if rng.random() < 0.03 else 0)
        atom = f"({name} {' '.join(pick(terms, rng.choice(['?nosuch', 'nosuch'])) for _ in range(max(arity, 0)))})"
        return f"(not {atom})" if negation and rng.random() < 0.3 else atom

    def parameter(variable: str, kind: str) -> str:  # typed, untyped (object), through an either, or ill-typed
        form = rng.random()
        return variable if form < 0.15 else f"{variable} - (either t1 t3)" if form < 0.2 else \
            f"{variable} - {pick([kind], rng.choice(['nosuch', '-']))}"

    def fields() -> str:  # now and then a field left out, empty, twice, unknown, or a keyword without a value
        parameters = " ".join(parameter(v, k) for v, k in params) + (rng.choice([" -", " x", " - t1"])
                                                                       if rng.random() < 0.03 else "")
        parts = [f":parameters ({parameters})", f":precondition (and {' '.join(literal() for _ in range(3))})",
                 f":effect (and {' '.join(literal(equality=False) for _ in range(2))})"]
        odd = rng.random()
        if odd < 0.03:
            parts.pop(rng.randrange(3))
        elif odd < 0.06:
            parts[1] = ":precondition ()"
        elif odd < 0.08:
            parts.append(rng.choice([":effect (and)", ":duration 3", ":precondition"]))
        return " ".join(parts)

    decls = " ".join(f"({name} {' '.join(f'?a{j} - {k}' for j, k in enumerate(ks))})" for name, ks in predicates.items())
    domain = (f"(define (domain d) (:requirements {requirements}) (:types t1 t2 - t3 t3) "
              f"(:constants c1 - {rng.choice(types)} c2 - t1) (:predicates {decls}) "
              f"(:action a {fields()}) (:action b {fields()}))")
    terms[:] = ["o1", "o2", "c1"]
    init = " ".join(literal(negation=False, equality=False) for _ in range(3))
    problem = (f"(define (problem p) (:domain d) (:objects o1 - {rng.choice(types)} o2 - {kind()}) "
               f"(:init {init}) (:goal (and {' '.join(literal() for _ in range(2))})))")
    return domain, problem


def test_the_c_checks_read_every_domain_and_problem_as_python_alone_does(monkeypatch) -> None:
    """The C reader builds an atom, literal or action only where Python's checks would build the same one, without a
    warning: on random domains and problems (a third of them malformed somewhere) both read the same fields or
    raise the same error."""
    rng, outcomes = random.Random(1), []
    for _ in range(600):
        domain, problem = _random_pddl(rng)
        with_c = (_outcome(parse_domain, domain), _outcome(_domain_and_problem, domain, problem))
        with monkeypatch.context() as python_alone:
            for name in ("literal", "atom", "conjunction", "action"):
                python_alone.setattr(_reader, name, lambda *_: None)
            alone = (_outcome(parse_domain, domain), _outcome(_domain_and_problem, domain, problem))
        assert with_c == alone, (domain, problem)
        outcomes.append(with_c[1][0])
    assert outcomes.count("read") >= 30 and len(set(outcomes)) >= 2


def test_the_c_checks_read_the_shipped_domains_as_python_alone_does(monkeypatch) -> None:
    for path in sorted(FIXTURES.glob("*domain*.pddl")) + sorted(DOMAINS.glob("*.pddl")):
        with_c = _outcome(parse_domain, path.read_text())
        for name in ("literal", "conjunction", "action"):
            monkeypatch.setattr(_reader, name, lambda *_: None)
        assert _outcome(parse_domain, path.read_text()) == with_c, path.name
        monkeypatch.undo()


def test_a_type_that_is_its_own_supertype_is_refused() -> None:
    with pytest.raises(PddlError, match=r"1:\d+: type 'a' is its own supertype \(a - b - a\)"):
        parse_domain("(define (domain d) (:types a - b b - a) (:predicates (p ?x - a)))")


def test_the_c_checks_build_plain_literals_and_leave_the_rest_to_python() -> None:
    predicates, objects = {"on": ("block", "place"), "free": ()}, {"a": "block", "t": "table"}
    ancestors = {"block": frozenset({"block", "place", "object"}), "table": frozenset({"table", "place", "object"})}
    variables = {"?x": "block"}
    built = _reader.literal(["not", ["on", "?x", "t"]], predicates, variables, objects, ancestors, True)
    assert built == Condition(Atom("on", ("?x", "t")), positive=False) and type(built.atom) is Atom
    assert _reader.atom(["on", "a", "a"], predicates, objects, ancestors) == Atom("on", ("a", "a"))
    for expr, negation in [(["not", ["on", "?x", "t"]], False), (["on", "t", "a"], True), (["on", "?x"], True),
                           (["on", "?y", "t"], True), (["nosuch"], True), (["=", "?x", "a"], True),
                           (["or", ["free"]], True), (["not", ["and"]], True), (["on", ["a"], "t"], True)]:
        assert _reader.literal(expr, predicates, variables, objects, ancestors, negation) is None, expr
    assert _reader.atom(["on", "?x", "t"], predicates, objects, ancestors) is None
    both = ["and", ["free"], [], ["and", ["not", ["on", "?x", "t"]]]]
    assert _reader.conjunction(both, predicates, variables, objects, ancestors, True) == [
        Condition(Atom("free", ())), Condition(Atom("on", ("?x", "t")), positive=False)]
    for expr in (["and", ["free"], "free"], ["and", ["or", ["free"]]], both):
        assert _reader.conjunction(expr, predicates, variables, objects, ancestors, expr is not both) is None, expr
