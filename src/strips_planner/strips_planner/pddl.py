"""A PDDL reader for STRIPS with :typing, :negative-preconditions, :equality, :action-costs, objects and constants,
ADL's conditions (``or``, ``imply``, ``forall``, ``exists``) in preconditions and goals, its conditional and
universal effects (``when``, ``forall`` in an effect), and derived predicates (``:derived``).

Text -> s-expressions -> :class:`Domain` / :class:`Problem`. Anything outside that fragment (numeric fluents other
than ``total-cost``) is refused with a :class:`PddlError` that names the line and column, so a
user knows what to rewrite.

Action costs follow the IPC's ``:action-costs``: ``(increase (total-cost) N)`` or ``(increase (total-cost)
(f ?x ...))`` in an effect, with ``(= (f a ...) N)`` in ``:init``; they count when the problem says
``(:metric minimize (total-cost))``, and an action without an increase then costs 0.

Valid input is read fast: the C module ``_reader`` turns the text into plain lists of plain strings (Python's
own pass does where the text is not ASCII), and checks and builds each plainly valid atom and literal, and each
plainly valid STRIPS action whole (the rest Python checks). Only when that first pass finds an error is the text
read again with every token and list knowing its line and column, and the same check, now located, raises the
:class:`PddlError`.
"""

from __future__ import annotations

import bisect
import re
from collections.abc import Callable
from typing import NamedTuple, TypeVar

from strips_planner import _reader
from strips_planner.collector import collector_paused

SUPPORTED_REQUIREMENTS = {":strips", ":typing", ":negative-preconditions", ":equality", ":action-costs"}
CHECKED_PER_CONSTRUCT = {":adl", ":disjunctive-preconditions", ":existential-preconditions", ":universal-preconditions",
                         ":quantified-preconditions", ":conditional-effects", ":derived-predicates"}
"""Requirements read per construct: many IPC domains declare ``:adl`` and stay STRIPS; what the reader does not take
is refused where it is used, with its place."""
TOTAL_COST = "total-cost"
ROOT_TYPE = "object"
EITHER = "either("
"""Prefix of a union type's name: ``(either a b)`` is read as the type ``either(a,b)``."""


class PddlError(ValueError):
    """Malformed or unsupported PDDL; the message starts with ``line:column``."""


class PddlUnsupportedError(PddlError):
    """Valid PDDL outside the fragment this reader plans for (``or``, ``forall``, ``:functions``, ...)."""


class _UnlocatedError(Exception):
    """An error found on the fast pass, which does not know where tokens are: read again, located."""

    def __init__(self, message: str, unsupported: bool = False) -> None:
        super().__init__(message)
        self.unsupported = unsupported


class Located(str):
    """A token of the located pass: its text, and ``where`` it starts as ``line:column``."""

    where: str


class SExpr(list):
    """A parenthesised list of the located pass, remembering ``where`` it opened."""

    where: str


def _error(at: str | list, message: str, unsupported: bool = False) -> Exception:
    where = getattr(at, "where", None)
    if where is None:
        return _UnlocatedError(message, unsupported)
    return (PddlUnsupportedError if unsupported else PddlError)(f"{where}: {message}")


def _unsupported(at: str | list, message: str) -> Exception:
    return _error(at, message, unsupported=True)


_TOKEN = re.compile(r"[()]|\?[^\s()?;]*|[^\s()?;]+")
"""Parentheses, then names; a ``?`` always starts a new token, as other PDDL readers have it
(zenotravel writes ``(aircraft?a)``)."""
_COMMENT = re.compile(r";[^\n]*")


def parse_sexpr(text: str, located: bool = False) -> list:
    """The single top-level s-expression of ``text``, in lower case; with ``located``, its tokens are
    :class:`Located` and its lists :class:`SExpr`."""
    text = text.lower()
    if ";" in text:  # blank comments out, keeping every offset
        text = _COMMENT.sub(lambda comment: " " * len(comment[0]), text)
    tokens: list[str] = _located_tokens(text) if located else _TOKEN.findall(text)
    if not tokens:
        raise _error(_at("1:1"), "empty input: expected (define ...)")
    stack: list[tuple[str, list]] = []
    result: list | None = None
    for token in tokens:
        if result is not None:
            raise _error(token, f"unexpected {token!r} after the end of the definition")
        if token == "(":
            stack.append((token, SExpr() if located else []))
        elif token == ")":
            if not stack:
                raise _error(token, "unbalanced ')'")
            start, items = stack.pop()
            if located:
                items.where = start.where
            if stack:
                stack[-1][1].append(items)
            else:
                result = items
        elif not stack:
            raise _error(token, f"expected '(' but found {token!r}")
        else:
            stack[-1][1].append(token)
    if stack:
        raise _error(stack[-1][0], "'(' is never closed")
    assert result is not None
    return result


def _located_tokens(text: str) -> list[Located]:
    """Every token with its line and column, the lines found once (an error late in a long problem is
    located in one pass, not one per token)."""
    line_starts = [0, *(newline.end() for newline in re.finditer("\n", text))]
    tokens = []
    for match in _TOKEN.finditer(text):
        offset = match.start()
        line = bisect.bisect_right(line_starts, offset)
        tokens.append(_at(f"{line}:{offset - line_starts[line - 1] + 1}", match[0]))
    return tokens


def _at(where: str, text: str = "") -> Located:
    token = Located(text)
    token.where = where
    return token


Parsed = TypeVar("Parsed")


def _read(text: str, reader: Callable[[list], Parsed]) -> Parsed:
    """``reader`` on the fast pass; on an error, on the located pass, which raises it located."""
    try:
        root = _reader.sexpr(text)
        return reader(parse_sexpr(text) if root is None else root)
    except _UnlocatedError:
        try:
            return reader(parse_sexpr(text, located=True))
        except _UnlocatedError as error:  # an error site without a token: report it unlocated
            raise (PddlUnsupportedError if error.unsupported else PddlError)(f"?:?: {error}") from None


# -- the model -------------------------------------------------------------------------------------------
class Atom(NamedTuple):
    """A predicate over arguments (variables, objects or constants). A named tuple: grounding builds
    thousands of them."""

    predicate: str
    args: tuple[str, ...]

    def __str__(self) -> str:
        return f"({' '.join((self.predicate, *self.args))})"


class Condition(NamedTuple):
    """A literal of a precondition or goal: an atom (or equality ``=``), possibly negated."""

    atom: Atom
    positive: bool = True


class Effect(NamedTuple):
    """A conditional or universal effect: for every binding of ``variables``, where ``condition`` holds in the state
    the action is applied in (None: always), ``literal`` holds after it (a negative one is deleted)."""

    variables: tuple[tuple[str, str], ...]
    """(variable, type) pairs its ``forall``s bind."""
    condition: Condition | tuple | None
    """A formula of :mod:`strips_planner.adl` (its ``when``s' conditions, joined by ``and``)."""
    literal: Condition


class Axiom(NamedTuple):
    """A derived predicate's rule (``:derived``): ``predicate`` holds of ``parameters`` in every state where
    ``condition`` does (a formula of :mod:`strips_planner.adl`); a derived atom no rule makes true is false."""

    predicate: str
    parameters: tuple[tuple[str, str], ...]
    condition: Condition | tuple


class Action(NamedTuple):
    name: str
    parameters: tuple[tuple[str, str], ...]
    """(variable, type) pairs."""
    precondition: tuple[Condition, ...]
    add: tuple[Atom, ...]
    delete: tuple[Atom, ...]
    cost: int | Atom = 0
    """What it adds to ``total-cost``: a number, or a function term whose value ``:init`` gives."""
    condition: tuple | None = None
    """What the precondition asks beyond its literals (``or``, ``imply``, ``forall``, ``exists``): a formula of
    :mod:`strips_planner.adl`, compiled away at grounding; None for STRIPS."""
    effects: tuple[Effect, ...] = ()
    """Its effects under a ``when`` or a ``forall`` (the others are :attr:`add` and :attr:`delete`)."""


class Domain:
    """A domain as it is read: filled in section by section."""

    def __init__(self, name: str) -> None:
        self.name = name
        self.requirements: set[str] = set()
        self.types: dict[str, str] = {ROOT_TYPE: ""}
        """type -> parent type (``object`` is the root)."""
        self.constants: dict[str, str] = {}
        self.predicates: dict[str, tuple[str, ...]] = {}
        """name -> parameter types."""
        self.functions: dict[str, tuple[str, ...]] = {}
        """Numeric functions (``total-cost``, ``road-length``): name -> parameter types."""
        self.actions: list[Action] = []
        self.axioms: list[Axiom] = []
        """The derived predicates' rules, in the order read."""
        self.warnings: list[str] = []
        """What the reader let through that strict PDDL refuses (an undeclared requirement)."""
        self.ancestors: dict[str, frozenset[str]] = {ROOT_TYPE: frozenset((ROOT_TYPE,))}
        """type -> it and its supertypes, once ``:types`` is read: the C reader's subtype check."""

    @property
    def derived(self) -> set[str]:
        """The predicates a ``:derived`` rule defines."""
        return {axiom.predicate for axiom in self.axioms}

    def is_subtype(self, sub: str, sup: str) -> bool:
        """Whether every object of type ``sub`` is one of type ``sup`` (``either`` types: unions)."""
        if sub.startswith(EITHER):
            return all(self.is_subtype(member, sup) for member in either_members(sub))
        if sup.startswith(EITHER):
            return any(self.is_subtype(sub, member) for member in either_members(sup))
        while sub:
            if sub == sup:
                return True
            sub = self.types.get(sub, "")
        return False


class Problem:
    """A problem as it is read, or as the scene planner states one."""

    def __init__(self, name: str, domain_name: str, objects: dict[str, str], init: set[Atom],
                 goal: tuple[Condition, ...]) -> None:
        self.name, self.domain_name, self.objects, self.init, self.goal = name, domain_name, objects, init, goal
        self.values: dict[Atom, int] = {}
        """The functions' values from ``:init``: ``(= (road-length a b) 7)``."""
        self.minimise_cost = False
        """``(:metric minimize (total-cost))``: plans are judged by cost, not length."""
        self.goal_condition: tuple | None = None
        """What the goal asks beyond its literals (as :attr:`Action.condition`)."""


# -- readers ---------------------------------------------------------------------------------------------
def _name(item: str | list, what: str) -> str:
    if isinstance(item, list):
        raise _error(item, f"expected {what}, found a parenthesised list")
    return item


def _typed_list(items: list, where: list, variables: bool) -> list[tuple[str, str, str]]:
    """``a b - t c`` -> [(a, t), (b, t), (c, object)], each with its token."""
    result, pending, i = [], [], 0
    while i < len(items):
        token = items[i]
        text = _name(token, "a name or '-'")
        if text == "-":
            if i + 1 >= len(items) or not pending:
                raise _error(token, "'-' must sit between names and their type")
            kind = _either(items[i + 1]) if isinstance(items[i + 1], list) else items[i + 1]
            result += [(name, kind, tok) for name, tok in pending]
            pending, i = [], i + 2
            continue
        if variables != text.startswith("?"):
            raise _error(token, f"expected a {'variable (?x)' if variables else 'name'}, found {text!r}")
        pending.append((text, token))
        i += 1
    return result + [(name, ROOT_TYPE, tok) for name, tok in pending]


def _either(expr: list) -> str:
    """``(either a b)`` -> the union type's name, ``either(a,b)``."""
    if len(expr) < 2 or _name(expr[0], "'either'") != "either":
        raise _error(expr, "a type is a name or (either TYPE ...)")
    return f"{EITHER}{','.join(sorted(_name(member, 'a type name') for member in expr[1:]))})"


def _lineage(types: dict[str, str], kind: str, section: list) -> list[str]:
    """``kind`` and its supertypes up to the root; a type that is its own supertype is refused."""
    lineage = []
    while kind:
        if kind in lineage:
            raise _error(section, f"type {kind!r} is its own supertype ({' - '.join((*lineage, kind))})")
        lineage.append(kind)
        kind = types.get(kind, "")
    return lineage


def either_members(kind: str) -> list[str]:
    return kind[len(EITHER):-1].split(",")


def _check_type(domain: Domain, kind: str, token: str) -> None:
    """Refuse an unknown type; an ``either`` of known types becomes a type of its own (its objects: those of
    any member), so grounding lists its objects like any other type's."""
    members = either_members(kind) if kind.startswith(EITHER) else [kind]
    for member in members:
        if member not in domain.types:
            raise _error(token, f"unknown type {member!r}")
    domain.types.setdefault(kind, ROOT_TYPE)


def _atom(expr: list, domain: Domain, variables: dict[str, str] | None, objects: dict[str, str],
          functions: bool = False) -> Atom:
    """A predicate's atom, checked against its declaration; with ``functions``, a numeric function's term.
    Called for every atom of a domain and a problem, so the checks are inline."""
    if not expr:
        raise _error(expr, "empty atom ()")
    predicate = expr[0]
    if isinstance(predicate, list):
        _name(predicate, "a function name" if functions else "a predicate name")  # raises
    args = tuple(expr[1:])
    if predicate in _COMPARISONS or (predicate == "=" and any(isinstance(arg, list) for arg in args)):
        raise _unsupported(expr, f"numeric conditions ({predicate} ...) are not supported: only action costs "
                                 "are numeric here")
    if predicate == "=" and not functions:
        if not domain.requirements & {":equality", ":adl"} and variables is not None:
            _warn(domain, "(= ...) is used without :equality in the domain's :requirements")
        if len(args) != 2:
            raise _error(expr, f"(= ...) takes 2 arguments, got {len(args)}")
        expected: tuple[str, ...] = (ROOT_TYPE, ROOT_TYPE)
    else:
        expected = (domain.functions if functions else domain.predicates).get(predicate)
        if expected is None:
            raise _error(expr, f"unknown {'function' if functions else 'predicate'} {predicate!r}")
        if len(args) != len(expected):
            raise _error(expr, f"{predicate} takes {len(expected)} argument(s), got {len(args)}")
    for arg, kind in zip(args, expected, strict=True):
        if isinstance(arg, list):
            _name(arg, "an argument")  # raises
        scope = variables if arg[0] == "?" else objects
        if scope is None or arg not in scope:
            what = "variable" if arg[0] == "?" else "object or constant"
            raise _error(arg, f"unknown {what} {arg!r}")
        if kind != ROOT_TYPE and scope[arg] != kind and not domain.is_subtype(scope[arg], kind):
            raise _error(arg, f"{arg!r} is a {scope[arg]}, but {predicate} expects a {kind}")
    return Atom(predicate, args)


_COMPARISONS = frozenset((">", "<", ">=", "<="))
"""Numeric fluents' comparisons, which a predicate's name never is."""
_NOT_STRIPS = frozenset(("or", "imply", "exists", "forall", "when", "increase", "decrease", "assign"))
_ADL_CONDITIONS = frozenset(("or", "imply", "exists", "forall"))
"""What a precondition or a goal may say beyond a conjunction of literals (:mod:`strips_planner.adl`)."""
_NEGATION = frozenset((":negative-preconditions", ":adl"))
_reader.bind(Atom, Condition, _NOT_STRIPS | {"and", "not", "="}, ROOT_TYPE)


def _conditions(expr: list, domain: Domain, variables: dict[str, str] | None, objects: dict[str, str],
                what: str) -> tuple[list[Condition], tuple | None]:
    """A precondition or goal: the literals of its top-level conjunction, and the rest as one ADL formula (None
    where there is none)."""
    if not expr:
        return [], None
    plain = _reader.conjunction(expr, domain.predicates, variables, objects, domain.ancestors,
                                _negation_allowed(domain, what))
    if plain is not None:
        return plain, None
    parts = _conjuncts(expr, what)
    literals = [_literal(part, domain, variables, objects, what) for part in parts if not _is_adl(part)]
    rest = tuple(_formula(part, domain, variables, objects, what) for part in parts if _is_adl(part))
    return literals, (("and", rest) if len(rest) > 1 else rest[0]) if rest else None


def _conjuncts(expr: list, what: str) -> list[list]:
    if expr[0] != "and":
        return [expr]
    return [c for part in expr[1:] if _sub(part, what) for c in _conjuncts(part, what)]


def _is_adl(expr: list) -> bool:
    """Whether ``expr`` needs more than a literal: an ADL connective, or a ``not`` over one (or over ``and``)."""
    head = expr[0] if expr else None
    if head == "not" and len(expr) == 2 and isinstance(expr[1], list) and expr[1]:
        return expr[1][0] in _ADL_CONDITIONS or expr[1][0] in ("and", "not")
    return head in _ADL_CONDITIONS


def _formula(expr: list, domain: Domain, variables: dict[str, str] | None, objects: dict[str, str],
             what: str):
    """An ADL condition in negation normal form (:mod:`strips_planner.adl`)."""
    from strips_planner.adl import negated

    head = _name(expr[0], "a predicate or a connective") if expr else ""
    args = [_sub(part, what) for part in expr[1:]] if head in ("and", "or", "not", "imply") else []
    if head in ("and", "or"):
        return (head, tuple(_formula(part, domain, variables, objects, what) for part in args))
    if head == "not":
        if len(args) != 1:
            raise _error(expr, "(not ...) takes exactly one condition")
        return negated(_formula(args[0], domain, variables, objects, what))
    if head == "imply":
        if len(args) != 2:
            raise _error(expr, "(imply A B) takes two conditions")
        return ("or", (negated(_formula(args[0], domain, variables, objects, what)),
                       _formula(args[1], domain, variables, objects, what)))
    if head in ("forall", "exists"):
        if len(expr) != 3:
            raise _error(expr, f"({head} (VARIABLES) CONDITION) takes a variable list and a condition")
        bound = _variables(list(_sub(expr[1], f"{head}'s variables")), expr, domain)
        scope = {**(variables or {}), **{var: kind for var, kind, _ in bound}}
        return (head, tuple((var, kind) for var, kind, _ in bound),
                _formula(_sub(expr[2], what), domain, scope, objects, what))
    return _literal(expr, domain, variables, objects, what)


def _literal(expr: list, domain: Domain, variables: dict[str, str] | None, objects: dict[str, str],
             what: str) -> Condition:
    """An atom or a negated one (``expr`` is not empty): built in C where it is plainly valid, else checked
    here, where every error is worded."""
    fast = _reader.literal(expr, domain.predicates, variables, objects, domain.ancestors,
                           _negation_allowed(domain, what))
    if fast is not None:
        return fast
    head = _name(expr[0], "a predicate or 'and'")
    if head == "not":
        if len(expr) != 2:
            raise _error(expr, "(not ...) takes exactly one atom")
        inner = _sub(expr[1], what)
        if inner and inner[0] in _NOT_STRIPS:
            raise _unsupported(inner, f"{inner[0]!r} under a not is not supported in a {what}")
        if inner and _name(inner[0], "an atom") in ("and", "not", "or"):
            raise _error(inner, f"only atoms can be negated in a {what}")
        if (what == "precondition" and not domain.requirements & _NEGATION
                and inner and inner[0] != "="):
            _warn(domain, "negative preconditions are used without :negative-preconditions in :requirements")
        return Condition(_atom(inner, domain, variables, objects), positive=False)
    if head in _NOT_STRIPS:
        if what == "effect":
            raise _error(expr, f"{head!r} is not an effect: effects are literals, and, forall, when and an action's "
                               "own (increase (total-cost) ...)")
        raise _unsupported(expr, f"{head!r} is not supported in a {what}: it takes literals, and, or, not, imply, "
                                 "forall and exists")
    return Condition(_atom(expr, domain, variables, objects))


def _negation_allowed(domain: Domain, what: str) -> bool:
    """Whether a ``(not ...)`` goes without a warning: anywhere but in a precondition, or with its requirement."""
    return what != "precondition" or bool(domain.requirements & _NEGATION)


def _warn(domain: Domain, message: str) -> None:
    """Note what other planners accept silently (Fast Downward reads both undeclared requirements)."""
    message = f"{message}; read as if declared"
    if message not in domain.warnings:
        domain.warnings.append(message)


def _cost(expr: list, domain: Domain, variables: dict[str, str]) -> int | Atom:
    """The amount of ``(increase (total-cost) AMOUNT)``: a non-negative integer or a function term."""
    if len(expr) != 3 or _sub(expr[1], "(total-cost)") != [TOTAL_COST]:
        raise _unsupported(expr, "numeric effects other than (increase (total-cost) ...) are not supported")
    amount = expr[2]
    if not isinstance(amount, list):
        return _number(amount)
    if amount and amount[0] == TOTAL_COST:
        raise _error(amount, "an action's cost cannot be (total-cost) itself")
    return _atom(amount, domain, variables, domain.constants, functions=True)


def _number(token: str | list) -> int:
    text = _name(token, "a number")
    try:
        value = float(text)
    except ValueError:
        raise _error(token, f"expected a number, found {text!r}") from None
    if value < 0 or value != int(value):
        raise _unsupported(token, f"action costs are non-negative integers, not {text}")
    return int(value)


def _sub(item: str | list, what: str) -> list:
    if not isinstance(item, list):
        raise _error(item, f"expected a parenthesised {what} element, found {item!r}")
    return item


def _sections(root: list, kind: str) -> tuple[str, list[list]]:
    if len(root) < 2 or _name(root[0], "define") != "define":
        raise _error(root, "expected (define ...)")
    header = _sub(root[1], f"({kind} NAME)")
    if len(header) != 2 or _name(header[0], kind) != kind:
        raise _error(header, f"expected ({kind} NAME)")
    return _name(header[1], f"a {kind} name"), [_sub(s, "section") for s in root[2:]]


@collector_paused
def parse_domain(text: str) -> Domain:
    return _read(text, _domain)


def _domain(root: list) -> Domain:
    name, sections = _sections(root, "domain")
    domain = Domain(name)
    for section in sections:
        key = _name(section[0], "a section keyword") if section else ""
        body = section[1:]
        if key == ":requirements":
            domain.requirements = {_name(r, "a requirement") for r in body}
            unsupported = domain.requirements - SUPPORTED_REQUIREMENTS - CHECKED_PER_CONSTRUCT
            if unsupported:
                raise _unsupported(section, f"unsupported requirement(s) {', '.join(sorted(unsupported))}; "
                                      f"supported: {', '.join(sorted(SUPPORTED_REQUIREMENTS))}")
        elif key == ":types":
            for child, parent, token in _typed_list(body, section, variables=False):
                if parent.startswith(EITHER):
                    raise _unsupported(token, f"type {child!r}: an (either ...) supertype is not supported")
                domain.types[child] = parent
                domain.types.setdefault(parent, ROOT_TYPE)
            domain.types[ROOT_TYPE] = ""
            domain.ancestors = {kind: frozenset(_lineage(domain.types, kind, section)) for kind in domain.types}
        elif key == ":constants":
            for const, kind, token in _typed_list(body, section, variables=False):
                _check_type(domain, kind, token)
                domain.constants[const] = kind
        elif key == ":predicates":
            for decl in body:
                decl = _sub(decl, "predicate declaration")
                pred = _name(decl[0], "a predicate name")
                params = _variables(decl[1:], decl, domain)
                domain.predicates[pred] = tuple(kind for _, kind, _ in params)
        elif key == ":functions":
            _functions(body, domain)
        elif key == ":action":
            domain.actions.append(_action(section, domain))
        elif key == ":derived":
            domain.axioms.append(_axiom(section, domain))
        else:
            raise (_unsupported if key else _error)(section, f"unsupported domain section {key or '()'!r}")
    derived = domain.derived
    for action in domain.actions:
        changed = {a.predicate for a in (*action.add, *action.delete, *(e.literal.atom for e in action.effects))}
        if changed & derived:
            raise PddlError(f"?:?: action {action.name} changes {', '.join(sorted(changed & derived))}, which a "
                            ":derived rule defines: derived predicates follow from the state, no action sets them")
    return domain


def _axiom(section: list, domain: Domain) -> Axiom:
    """``(:derived (PREDICATE ?x - type ...) CONDITION)``; the predicate declared by it where ``:predicates`` did not."""
    if len(section) != 3:
        raise _error(section, "(:derived (PREDICATE ?x - type ...) CONDITION) takes a head and a condition")
    head = _sub(section[1], "derived predicate's head")
    name = _name(head[0], "a predicate name") if head else ""
    if not name:
        raise _error(head, "a derived predicate's head names its predicate: (:derived (PREDICATE ?x ...) ...)")
    params = _variables(head[1:], head, domain)
    kinds = tuple(kind for _, kind, _ in params)
    declared = domain.predicates.setdefault(name, kinds)
    if len(declared) != len(kinds):
        raise _error(head, f"{name} takes {len(declared)} argument(s), its :derived head {len(kinds)}")
    variables = {var: kind for var, kind, _ in params}
    condition = _formula(_sub(section[2], "condition"), domain, variables, domain.constants, "condition")
    return Axiom(name, tuple((var, kind) for var, kind, _ in params), condition)


def _variables(items: list, where: list, domain: Domain) -> list[tuple[str, str, str]]:
    """``?a ?b - t ?c``: each variable with its type (checked to be the domain's) and its token."""
    variables = _typed_list(items, where, variables=True)
    for _, kind, token in variables:
        _check_type(domain, kind, token)
    return variables


def _functions(body: list, domain: Domain) -> None:
    """``(total-cost) - number (road-length ?a ?b - location) - number``: numeric functions only."""
    i = 0
    while i < len(body):
        decl = _sub(body[i], "function declaration")
        name = _name(decl[0], "a function name") if decl else ""
        if not name:
            raise _error(decl, "empty function declaration ()")
        params = _variables(decl[1:], decl, domain)
        i += 1
        if i < len(body) and body[i] == "-":
            if i + 1 >= len(body) or body[i + 1] != "number":
                raise _unsupported(body[i], f"function {name!r}: only number-valued functions are supported")
            i += 2
        domain.functions[name] = tuple(kind for _, kind, _ in params)


def _action(section: list, domain: Domain) -> Action:
    plain = _reader.action(section, domain.predicates, domain.constants, domain.ancestors, domain.types,
                           _negation_allowed(domain, "precondition"))
    if plain is not None:  # a STRIPS action, read in one C call
        return Action(*plain)
    if len(section) < 2:
        raise _error(section, "(:action NAME ...) needs a name")
    name = _name(section[1], "an action name")
    fields: dict[str, list] = {}
    items = section[2:]
    for key, value in zip(items[::2], items[1::2], strict=False):
        fields[_name(key, ":parameters, :precondition or :effect")] = _sub(value, "action field")
    if len(items) % 2:
        raise _error(items[-1], f"action {name}: a keyword without a value")
    unknown = set(fields) - {":parameters", ":precondition", ":effect"}
    if unknown:
        raise _unsupported(section, f"action {name}: unsupported field(s) {', '.join(sorted(unknown))}")
    params = _variables(list(fields.get(":parameters", [])), section, domain)
    variables = {var: kind for var, kind, _ in params}
    pre, condition = _conditions(fields.get(":precondition", []), domain, variables, domain.constants,
                                 "precondition")
    effect_expr, costs = _without_increase(fields.get(":effect", []))
    effects: list[Effect] = []
    plain = _reader.conjunction(effect_expr, domain.predicates, variables, domain.constants, domain.ancestors,
                                True) if effect_expr else []
    if plain is None:  # under a when or a forall, or an error to word
        _effect(effect_expr, domain, variables, (), None, effects)
        plain = [effect.literal for effect in effects if not effect.variables and effect.condition is None]
        effects = [effect for effect in effects if effect.variables or effect.condition is not None]
    if len(costs) > 1:
        raise _unsupported(costs[1], f"action {name}: more than one (increase (total-cost) ...)")
    add, delete = [], []
    for literal in (*plain, *(effect.literal for effect in effects)):
        if literal.atom.predicate == "=":
            raise _error(section, f"action {name}: equality cannot be an effect")
    for literal in plain:
        (add if literal.positive else delete).append(literal.atom)
    return Action(name, tuple((v, k) for v, k, _ in params), tuple(pre), tuple(add), tuple(delete),
                  _cost(costs[0], domain, variables) if costs else 0, condition, tuple(effects))


def _effect(expr: list, domain: Domain, variables: dict[str, str], bound: tuple[tuple[str, str], ...],
            condition: Condition | tuple | None, out: list[Effect]) -> None:
    """The literals of an effect into ``out``, each with the ``forall`` variables (``bound``) and the ``when``
    conditions (``condition``) it is under."""
    if not expr:
        return
    plain = _reader.conjunction(expr, domain.predicates, variables, domain.constants, domain.ancestors, True)
    if plain is not None:
        out += [Effect(bound, condition, literal) for literal in plain]
        return
    head = expr[0]
    if head == "and":
        for part in expr[1:]:
            _effect(_sub(part, "effect"), domain, variables, bound, condition, out)
    elif head == "forall":
        if len(expr) != 3:
            raise _error(expr, "(forall (VARIABLES) EFFECT) takes a variable list and an effect")
        new = _variables(list(_sub(expr[1], "forall's variables")), expr, domain)
        _effect(_sub(expr[2], "effect"), domain, {**variables, **{var: kind for var, kind, _ in new}},
                (*bound, *((var, kind) for var, kind, _ in new)), condition, out)
    elif head == "when":
        if len(expr) != 3:
            raise _error(expr, "(when CONDITION EFFECT) takes a condition and an effect")
        inner = _formula(_sub(expr[1], "condition"), domain, variables, domain.constants, "condition")
        _effect(_sub(expr[2], "effect"), domain, variables, bound,
                inner if condition is None else ("and", (condition, inner)), out)
    elif head in ("increase", "decrease", "assign"):
        raise _unsupported(expr, f"{head!r} is not supported here: only an action's own (increase (total-cost) ...), "
                                 "at the top of its effect")
    else:
        out.append(Effect(bound, condition, _literal(expr, domain, variables, domain.constants, "effect")))


def _without_increase(effect: list) -> tuple[list, list[list]]:
    """The effect without its ``(increase ...)`` parts, and those parts."""
    if effect and effect[0] == "increase":
        return [], [effect]
    if not effect or effect[0] != "and":
        return effect, []
    kept, increases = [effect[0]], []
    for part in effect[1:]:
        (increases if isinstance(part, list) and part and part[0] == "increase" else kept).append(part)
    return kept, increases


@collector_paused
def parse_problem(text: str, domain: Domain) -> Problem:
    return _read(text, lambda root: _problem(root, domain))


def _problem(root: list, domain: Domain) -> Problem:
    name, sections = _sections(root, "problem")
    problem = Problem(name, "", dict(domain.constants), set(), ())
    goal_section = None
    for section in sections:
        key = _name(section[0], "a section keyword") if section else ""
        if key == ":domain":
            problem.domain_name = _name(section[1], "a domain name") if len(section) > 1 else ""
            if problem.domain_name != domain.name:
                raise _error(section, f"problem is for domain {problem.domain_name!r}, not {domain.name!r}")
        elif key == ":objects":
            for obj, kind, token in _typed_list(section[1:], section, variables=False):
                _check_type(domain, kind, token)
                problem.objects[obj] = kind
        elif key == ":init":
            for fact in section[1:]:
                atom = _reader.atom(fact, domain.predicates, problem.objects, domain.ancestors)
                if atom is not None:
                    problem.init.add(atom)
                    continue
                fact = _sub(fact, "initial fact")
                head = _name(fact[0], "") if fact else ""
                if head == "=" and len(fact) == 3 and isinstance(fact[1], list):
                    _value(fact, domain, problem)
                    continue
                if head == "=" and any(isinstance(arg, list) for arg in fact[1:]):
                    raise _unsupported(fact, "numeric fluents ((= (f) n) in :init) are not supported")
                if head in ("not", "="):
                    raise _error(fact, "the initial state lists true atoms only")
                problem.init.add(_atom(fact, domain, None, problem.objects))
        elif key == ":goal":
            goal_section = section
        elif key == ":metric":
            if section[1:] != ["minimize", [TOTAL_COST]]:
                raise _unsupported(section, "the only metric supported is (:metric minimize (total-cost))")
            problem.minimise_cost = True
        elif key == ":requirements":
            continue
        else:
            raise (_unsupported if key else _error)(section, f"unsupported problem section {key or '()'!r}")
    if goal_section is None or len(goal_section) != 2:
        raise _error(goal_section or root, "the problem needs one (:goal EXPRESSION)")
    goal, problem.goal_condition = _conditions(_sub(goal_section[1], "goal"), domain, None, problem.objects, "goal")
    problem.goal = tuple(goal)
    derived = sorted({str(atom) for atom in problem.init if atom.predicate in domain.derived})
    if derived:
        raise PddlError(f"?:?: {derived[0]} is in :init, but a :derived rule defines {derived[0][1:].split()[0]}: "
                        "derived atoms follow from the state")
    return problem


def _value(fact: list, domain: Domain, problem: Problem) -> None:
    """``(= (f a ...) N)`` in ``:init``: a function's value (``total-cost`` starts at 0 and is not stored)."""
    function = _name(fact[1][0], "a function name") if fact[1] else ""
    if function not in domain.functions:
        raise _unsupported(fact, f"numeric fluents ((= ({function}) n) in :init) need {function!r} in :functions")
    term = _atom(fact[1], domain, None, problem.objects, functions=True)
    value = _number(fact[2])
    if function != TOTAL_COST:
        problem.values[term] = value
