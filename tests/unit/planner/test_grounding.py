"""Grounding against a naive reference (every binding, then a relaxed fixpoint), and the C exploration's and
grounder's refusal of malformed input."""

import itertools
import time
from pathlib import Path

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from semgoal_planner.blocksworld import DOMAIN_PATH, problem
from strips_planner import _explore, _ground
from strips_planner.grounding import Task, ground
from strips_planner.pddl import Atom, Domain, Problem, parse_domain, parse_problem

FIXTURES = Path(__file__).parent / "fixtures"
CASES = [("blocksworld-domain", "blocksworld-sussman"), ("gripper-domain", "gripper-4balls"),
         ("logistics-domain", "logistics-p1"), ("keys-domain", "keys-vault")]


def naive_ground(domain: Domain, prob: Problem) -> tuple:
    """The task as plain sets: every binding over the objects of each parameter's type, kept when its
    static preconditions hold in the initial state, then the candidates and atoms a relaxed exploration
    (positive preconditions only) reaches, found by iterating to a fixpoint."""
    fluent = {a.predicate for action in domain.actions for a in (*action.add, *action.delete)}
    static = {a for a in prob.init if a.predicate not in fluent}
    candidates = []
    for action in domain.actions:
        pools = [[o for o in sorted(prob.objects) if domain.is_subtype(prob.objects[o], kind)]
                 for _, kind in action.parameters]
        for values in itertools.product(*pools):
            binding = dict(zip((v for v, _ in action.parameters), values, strict=True))

            def bound(atom: Atom, binding=binding) -> Atom:
                return Atom(atom.predicate, tuple(binding.get(a, a) for a in atom.args))

            pre, pre_neg, static_ok = set(), set(), True
            for cond in action.precondition:
                atom = bound(cond.atom)
                if atom.predicate == "=":
                    static_ok &= (atom.args[0] == atom.args[1]) == cond.positive
                elif atom.predicate not in fluent:
                    static_ok &= (atom in static) == cond.positive
                else:
                    (pre if cond.positive else pre_neg).add(atom)
            if static_ok:
                candidates.append((f"({' '.join((action.name, *values))})", pre, pre_neg,
                                   set(map(bound, action.add)), set(map(bound, action.delete))))
    reached = {a for a in prob.init if a.predicate in fluent}
    fired: set[int] = set()
    while new := [i for i, c in enumerate(candidates) if i not in fired and c[1] <= reached]:
        fired.update(new)
        reached.update(*(candidates[i][3] for i in new))
    operators = [(name, pre & reached, pre_neg & reached, add, (delete - add) & reached)
                 for i, (name, pre, pre_neg, add, delete) in enumerate(candidates) if i in fired]
    goal = {c.atom for c in prob.goal if c.positive} & reached  # an unreached one makes the task unsolvable
    goal_neg = {c.atom for c in prob.goal if not c.positive} & reached
    return sorted(reached), {a for a in prob.init if a.predicate in fluent}, goal, goal_neg, operators


def as_sets(task: Task) -> tuple:
    def atoms(mask: int) -> set[Atom]:
        return set(task.atoms(mask))

    operators = [(str(op), atoms(op.pre), atoms(op.pre_neg), atoms(op.add), atoms(op.delete)) for op in task.operators]
    return list(task.facts), atoms(task.init), atoms(task.goal), atoms(task.goal_neg), operators


def grounded(domain_text: str, problem_text: str) -> tuple[Task, tuple]:
    domain = parse_domain(domain_text)
    prob = parse_problem(problem_text, domain)
    return ground(domain, prob), naive_ground(domain, prob)


@pytest.mark.parametrize(("domain", "problem_name"), CASES)
def test_grounding_matches_the_naive_reference_on_standard_domains(domain: str, problem_name: str) -> None:
    task, expected = grounded((FIXTURES / f"{domain}.pddl").read_text(), (FIXTURES / f"{problem_name}.pddl").read_text())
    assert as_sets(task) == expected
    assert not task.unsolvable_reason


@pytest.mark.parametrize(("blocks", "seed"), [(n, seed) for n in (1, 2, 3, 5, 7, 9) for seed in range(2)])
def test_grounding_matches_the_naive_reference_on_blocksworld(blocks: int, seed: int) -> None:
    task, expected = grounded(DOMAIN_PATH.read_text(), problem(blocks, seed))
    assert as_sets(task) == expected
    assert len(task.facts) > 64 or blocks < 7  # masks of more than one word, too


def test_a_goal_atom_no_operator_reaches_makes_the_task_unsolvable() -> None:
    vault = (FIXTURES / "keys-vault.pddl").read_text().replace("(has master)", "(lies k1 hall)")
    task, expected = grounded((FIXTURES / "keys-domain.pddl").read_text(), vault)  # keys are taken, never put down
    assert as_sets(task) == expected
    assert task.unsolvable_reason == "goal (lies k1 hall) is not reachable from the initial state"


CORRIDOR_DOMAIN = """(define (domain corridor) (:requirements :strips)
  (:predicates (at ?x ?r) (door ?a ?b) (open ?a ?b))
  (:action unlock :parameters (?a ?b) :precondition (door ?a ?b) :effect (open ?a ?b))
  (:action stride :parameters (?x ?a ?b ?c) :precondition (and (at ?x ?a) (open ?a ?b) (open ?b ?c))
                  :effect (and (at ?x ?c) (not (at ?x ?a)))))"""


def corridor(rooms: int) -> str:
    """A walker in room 0 of a corridor, every door closed: it strides two rooms at a time, so only the even
    rooms are ever reached; no parameter has a type or a static precondition to narrow it."""
    doors = " ".join(f"(door r{i} r{i + 1}) (door r{i + 1} r{i})" for i in range(rooms - 1))
    return (f"(define (problem c) (:domain corridor) (:objects w {' '.join(f'r{i}' for i in range(rooms))})"
            f" (:init (at w r0) {doors}) (:goal (at w r{rooms - 2})))")


def test_grounding_follows_what_is_reachable_never_every_combination() -> None:
    """200 rooms: 201^4 bindings of stride to enumerate, of which 397 are reachable (from each even room but the
    first and the last, 4; from r0, 2; from r198, 3) beside the 398 unlocks. Enumerating first would take hours."""
    domain = parse_domain(CORRIDOR_DOMAIN)
    start = time.perf_counter()
    task = ground(domain, parse_problem(corridor(200), domain))
    assert time.perf_counter() - start < 1.0
    names = [op.name for op in task.operators]
    assert names.count("unlock") == 398 and names.count("stride") == 397
    assert {a.args[1] for a in task.facts if a.predicate == "at"} == {f"r{i}" for i in range(0, 200, 2)}


def test_grounding_matches_the_naive_reference_on_a_small_corridor() -> None:
    task, expected = grounded(CORRIDOR_DOMAIN, corridor(7))
    assert as_sets(task) == expected


TYPES = ("object", "t0", "t1")


@st.composite
def random_tasks(draw) -> tuple[str, str]:
    """A random STRIPS domain and problem: predicates of arity 0-3, typed parameters, a typed constant,
    equality and negative preconditions; predicates no effect mentions are static."""
    arity = draw(st.lists(st.integers(0, 3), min_size=1, max_size=4))
    objects = draw(st.lists(st.sampled_from(TYPES), min_size=1, max_size=4))
    names = [f"o{i}" for i in range(len(objects))]

    def atom(args: list[str]) -> str:
        predicate = draw(st.integers(0, len(arity) - 1))
        return f"(p{predicate} {' '.join(draw(st.sampled_from(args)) for _ in range(arity[predicate]))})"

    def literal(args: list[str]) -> str:
        """An atom, or one time in five an equality; negated half the time."""
        equality = draw(st.integers(0, 4)) == 0
        text = f"(= {draw(st.sampled_from(args))} {draw(st.sampled_from(args))})" if equality else atom(args)
        return f"(not {text})" if draw(st.booleans()) else text

    actions = []
    for a in range(draw(st.integers(1, 3))):
        params = [f"?v{i}" for i in range(draw(st.integers(0, 3)))]
        args = [*params, "c0"]
        typed = " ".join(f"{v} - {draw(st.sampled_from(TYPES))}" for v in params)
        pre = " ".join(literal(args) for _ in range(draw(st.integers(0, 3))))
        effects = [atom(args) for _ in range(draw(st.integers(1, 3)))]
        effect = " ".join(e if draw(st.booleans()) else f"(not {e})" for e in effects)
        actions.append(f"(:action a{a} :parameters ({typed}) :precondition (and {pre}) :effect (and {effect}))")
    predicates = " ".join(f"(p{i} {' '.join(f'?x{j}' for j in range(n))})" for i, n in enumerate(arity))
    domain = (f"(define (domain random) (:requirements :strips :typing :negative-preconditions :equality)"
              f" (:types t0 t1) (:constants c0 - t0) (:predicates {predicates}) {' '.join(actions)})")
    everything = [*names, "c0"]
    init = " ".join(atom(everything) for _ in range(draw(st.integers(0, 6))))
    goal = " ".join(literal(everything) for _ in range(draw(st.integers(1, 3))))
    problem_text = (f"(define (problem r) (:domain random) (:objects {' '.join(f'{o} - {t}' for o, t in zip(names, objects, strict=True))})"
                    f" (:init {init}) (:goal (and {goal})))")
    return domain, problem_text


@settings(max_examples=150, deadline=None)
@given(random_tasks())
def test_grounding_matches_the_naive_reference_on_random_domains(texts: tuple[str, str]) -> None:
    task, expected = grounded(*texts)
    assert as_sets(task) == expected
    domain = parse_domain(texts[0])
    prob = parse_problem(texts[1], domain)
    fluent = {a.predicate for action in domain.actions for a in (*action.add, *action.delete)}
    facts = set(task.facts)
    static_false = any((c.atom.args[0] == c.atom.args[-1] if c.atom.predicate == "=" else c.atom in prob.init) != c.positive
                       for c in prob.goal if c.atom.predicate not in fluent)
    unreached = any(c.positive and c.atom not in facts for c in prob.goal if c.atom.predicate in fluent)
    assert bool(task.unsolvable_reason) == (static_false or unreached)


SHAPE = {"predicates": ("on",), "objects": ("a", "b"), "width": 3, "init": [], "goal": [], "goal_neg": []}
MOVE = ("move", 2, [(0, 1)], [(0, 0, 1)], [], [(0, 1, 0)], [(0, 0, 1)])


@pytest.mark.parametrize(("change", "error", "words"), [
    ({"width": 0}, ValueError, "width"),
    ({"init": [(1, 0, 1)]}, ValueError, "predicate index"),
    ({"init": [(0, 0, 2)]}, ValueError, "in range"),
    ({"init": [(0, 0, 1, 1)]}, ValueError, "at most 3"),
    ({"goal": [("on", 0, 1)]}, TypeError, "integer"),
    ({"actions": [("move", 2, [(0,)], [], [], [], [])]}, ValueError, "2 object indices"),
    ({"actions": [("move", 2, [(0, 1)], [(0, 0, 2)], [], [], [])]}, ValueError, "argument codes"),
    ({"actions": [("move", 2, [(0, 1)], [(0, 0, ~2)], [], [], [])]}, ValueError, "argument codes"),
    ({"actions": [("move", -1, [], [], [], [], [])]}, ValueError, "nparams"),
    ({"actions": [("move", 2, ((0, 1),), [], [], [], [])]}, TypeError, "list"),
    ({"atom_type": list}, TypeError, "tuple types"),
])
def test_the_c_grounder_refuses_malformed_input_with_a_message(change: dict, error: type, words: str) -> None:
    arguments = {**SHAPE, "actions": [MOVE], **change}
    with pytest.raises(error, match=words):
        _ground.ground(**arguments)


def test_the_c_grounder_builds_masks_and_constants() -> None:
    """A constant argument (~object) and a delete effect that the operator also adds."""
    toggle = ("toggle", 1, [(0,), (1,)], [(0, 0, ~1)], [], [(0, 0, 0)], [(0, 0, 0), (0, 0, ~1)])
    facts, init, goal, goal_neg, unreached, operators = _ground.ground(
        **{**SHAPE, "init": [(0, 0, 1), (0, 1, 1)], "goal": [(0, 1, 0), (0, 1, 1)], "actions": [toggle]})
    assert facts == [("on", ("a", "a")), ("on", ("a", "b")), ("on", ("b", "b"))]
    assert (init, goal, goal_neg, unreached) == (0b110, 0b100, 0, [0])  # (on b a) is never reached
    assert operators == [("toggle", ("a",), 0b010, 0, 0b001, 0b010, ()), ("toggle", ("b",), 0b100, 0, 0b100, 0, ())]


# explore(npredicates, nobjects, width, init, schemas): a schema is (types, joined, filters, adds)
MOVE_SCHEMA = ((None, None), [(0, 0, 1)], [(False, -1, 0, 1)], [(0, 1, 0)])


@pytest.mark.parametrize(("arguments", "error", "words"), [
    ((1, 2, 0, [], [MOVE_SCHEMA]), ValueError, "width"),
    ((1, 2, 40, [], [MOVE_SCHEMA]), ValueError, "width"),
    ((1, 2, 3, [(1, 0, 1)], [MOVE_SCHEMA]), ValueError, "initial atom"),
    ((1, 2, 3, [(0, 0, 2)], [MOVE_SCHEMA]), ValueError, "initial atom"),
    ((1, 2, 3, [(0, "a", 1)], [MOVE_SCHEMA]), TypeError, "integer"),
    ((1, 2, 3, [], [((None,), [(0, 0, 1)], [], [])]), ValueError, "precondition"),
    ((1, 2, 3, [], [((None, None), [(0, 0, ~2)], [], [])]), ValueError, "precondition"),
    ((1, 2, 3, [], [((None, None), [(0, 0, 1)], [(True, -1, 0)], [])]), ValueError, "filter"),
    ((1, 2, 3, [], [((None, None), [(0, 0, 1)], [(True,)], [])]), ValueError, "filter"),
    ((1, 2, 3, [], [((None, (0, 5)), [(0, 0, 1)], [], [])]), ValueError, "out of range"),
    ((1, 2, 3, [], [((None,) * 33, [], [], [])]), ValueError, "at most 32"),
    ((1, 2, 3, [], [([None], [], [], [])]), TypeError, "tuple"),
])
def test_the_c_exploration_refuses_malformed_input_with_a_message(arguments: tuple, error: type, words: str) -> None:
    with pytest.raises(error, match=words):
        _explore.explore(*arguments)


def test_the_c_exploration_joins_checks_and_ranges_free_parameters() -> None:
    """move(x, y) needs on(x, y) and x != y, and adds on(y, x); mark(z), of a type {b, c}, needs nothing and adds
    marked(z): from on(a, b) and on(c, c), move(a, b), then move(b, a); on(c, c) is ruled out by the inequality."""
    move = ((None, None), [(0, 0, 1)], [(False, -1, 0, 1)], [(0, 1, 0)])
    mark = (((1, 2),), [], [], [(1, 0)])
    assert _explore.explore(2, 3, 3, [(0, 0, 1), (0, 2, 2)], [move, mark]) == [[(0, 1), (1, 0)], [(1,), (2,)]]


RANDOM_SEARCH_S = 5.0
"""How long each search of a random task may run before the task is drawn again."""


@settings(max_examples=150, deadline=None)
@given(random_tasks())
def test_lmcut_stays_admissible_on_random_domains(texts: tuple[str, str]) -> None:
    """Whatever ties LM-cut breaks among costliest preconditions, A* with it finds plans as short as
    breadth-first search, and its estimate at the start never exceeds that length. A drawn task whose state space
    neither search exhausts in :data:`RANDOM_SEARCH_S` (a ternary predicate over five objects can have 2^125 states)
    is drawn again, not waited on."""
    from strips_planner.heuristics import heuristic
    from strips_planner.planner import solve_task

    task, _ = grounded(*texts)
    searched = [solve_task(task, "bfs", seconds=RANDOM_SEARCH_S), solve_task(task, "astar", "lmcut", seconds=RANDOM_SEARCH_S)]
    assume(not any(result.stats.timed_out for result in searched))
    shortest, astar = (result.plan for result in searched)
    assert (shortest is None) == (astar is None)
    if shortest is not None:
        assert len(astar) == len(shortest)
        assert heuristic(task, "lmcut")(task.init) <= len(shortest)


def test_an_actions_templates_name_parameters_by_position_and_constants_by_complement() -> None:
    """``(move ?x ?y)`` with a constant ``home``: a fluent, a static and an equality precondition, positive and not."""
    from strips_planner.pddl import Condition

    number, index = {"at": 0, "road": 1}, {"home": 0, "a": 1}
    precondition = (Condition(Atom("at", ("?x",))), Condition(Atom("road", ("?x", "home"))),
                    Condition(Atom("road", ("?y", "?x")), positive=False), Condition(Atom("=", ("?x", "?y")), False))
    joined, filters, pre, pre_neg, add, delete = _ground.templates(
        precondition, (Atom("at", ("?y",)),), (Atom("at", ("?x",)),), {"?x": 0, "?y": 1}, index, number, 1)
    assert joined == [(0, 0), (1, 0, ~0)] and pre == [(0, 0)] and pre_neg == []
    assert filters == [(False, 1, 1, 0), (False, -1, 0, 1)]
    assert add == [(0, 1)] and delete == [(0, 0)]
    with pytest.raises(KeyError):  # an object the problem lacks
        _ground.templates((), (Atom("at", ("nowhere",)),), (), {}, index, number, 1)
    with pytest.raises(TypeError):
        _ground.templates((), (("at", ["?x"]),), (), {"?x": 0}, index, number, 1)
