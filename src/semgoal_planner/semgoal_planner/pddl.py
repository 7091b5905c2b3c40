"""A PDDL reader for STRIPS with :typing, :negative-preconditions, :equality, objects and constants.

Text -> s-expressions (every token keeps its line and column) -> :class:`Domain` / :class:`Problem`.
Anything outside that fragment (``or``, ``forall``, ``when``, numeric fluents) is refused with a
:class:`PddlError` that names the line and column, so a user knows what to rewrite.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

SUPPORTED_REQUIREMENTS = {":strips", ":typing", ":negative-preconditions", ":equality"}
ROOT_TYPE = "object"


class PddlError(ValueError):
    """Malformed or unsupported PDDL; the message starts with ``line:column``."""


Token = re.Match
"""A name or a parenthesis as matched in the (lower-cased) source: ``token[0]`` is its text, and its
offset gives line and column only when an error needs them."""


def _where(token: Token) -> str:
    source, offset = token.string, token.start()
    return f"{source.count(chr(10), 0, offset) + 1}:{offset - source.rfind(chr(10), 0, offset)}"


class SExpr(list):
    """A parenthesised list of tokens and sub-lists, remembering where it opened."""

    def __init__(self, items: list, start: Token) -> None:
        super().__init__(items)
        self.start = start


def _error(at: Token | SExpr, message: str) -> PddlError:
    token = at.start if isinstance(at, SExpr) else at
    return PddlError(f"{_where(token)}: {message}")


_TOKEN = re.compile(r"[()]|[^\s();]+")
_COMMENT = re.compile(r";[^\n]*")


def tokenize(text: str) -> list[Token]:
    text = text.lower()
    if ";" in text:  # blank comments out, keeping every offset
        text = _COMMENT.sub(lambda comment: " " * len(comment[0]), text)
    return list(_TOKEN.finditer(text))


def parse_sexpr(text: str) -> SExpr:
    """The single top-level s-expression of ``text``."""
    tokens = tokenize(text)
    if not tokens:
        raise PddlError("1:1: empty input: expected (define ...)")
    stack: list[tuple[Token, list]] = []
    result: SExpr | None = None
    for token in tokens:
        word = token[0]
        if result is not None:
            raise _error(token, f"unexpected {word!r} after the end of the definition")
        if word == "(":
            stack.append((token, []))
        elif word == ")":
            if not stack:
                raise _error(token, "unbalanced ')'")
            start, items = stack.pop()
            expr = SExpr(items, start)
            if stack:
                stack[-1][1].append(expr)
            else:
                result = expr
        elif not stack:
            raise _error(token, f"expected '(' but found {word!r}")
        else:
            stack[-1][1].append(token)
    if stack:
        raise _error(stack[-1][0], "'(' is never closed")
    assert result is not None
    return result


# -- the model -------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Atom:
    predicate: str
    args: tuple[str, ...]

    def __str__(self) -> str:
        return f"({' '.join((self.predicate, *self.args))})"


@dataclass(frozen=True)
class Condition:
    """A literal of a precondition or goal: an atom (or equality ``=``), possibly negated."""

    atom: Atom
    positive: bool = True


@dataclass(frozen=True)
class Action:
    name: str
    parameters: tuple[tuple[str, str], ...]
    """(variable, type) pairs."""
    precondition: tuple[Condition, ...]
    add: tuple[Atom, ...]
    delete: tuple[Atom, ...]


@dataclass
class Domain:
    name: str
    requirements: set[str] = field(default_factory=set)
    types: dict[str, str] = field(default_factory=lambda: {ROOT_TYPE: ""})
    """type -> parent type (``object`` is the root)."""
    constants: dict[str, str] = field(default_factory=dict)
    predicates: dict[str, tuple[str, ...]] = field(default_factory=dict)
    """name -> parameter types."""
    actions: list[Action] = field(default_factory=list)

    def is_subtype(self, sub: str, sup: str) -> bool:
        while sub:
            if sub == sup:
                return True
            sub = self.types.get(sub, "")
        return False


@dataclass
class Problem:
    name: str
    domain_name: str
    objects: dict[str, str]
    init: set[Atom]
    goal: tuple[Condition, ...]


# -- readers ---------------------------------------------------------------------------------------------
def _name(item, what: str) -> str:
    if isinstance(item, SExpr):
        raise _error(item, f"expected {what}, found a parenthesised list")
    return item[0]


def _typed_list(items: list, where: SExpr, variables: bool) -> list[tuple[str, str, Token]]:
    """``a b - t c`` -> [(a, t), (b, t), (c, object)], each with its token."""
    result, pending, i = [], [], 0
    while i < len(items):
        token = items[i]
        text = _name(token, "a name or '-'")
        if text == "-":
            if i + 1 >= len(items) or not pending:
                raise _error(token, "'-' must sit between names and their type")
            kind = _name(items[i + 1], "a type name")
            if kind == "(" or kind.startswith("("):
                raise _error(items[i + 1], "'either' types are not supported")
            result += [(name, kind, tok) for name, tok in pending]
            pending, i = [], i + 2
            continue
        if variables != text.startswith("?"):
            raise _error(token, f"expected a {'variable (?x)' if variables else 'name'}, found {text!r}")
        pending.append((text, token))
        i += 1
    return result + [(name, ROOT_TYPE, tok) for name, tok in pending]


def _check_type(domain: Domain, kind: str, token: Token) -> None:
    if kind not in domain.types:
        raise _error(token, f"unknown type {kind!r}")


def _atom(expr: SExpr, domain: Domain, variables: dict[str, str] | None, objects: dict[str, str]) -> Atom:
    if not expr:
        raise _error(expr, "empty atom ()")
    predicate = _name(expr[0], "a predicate name")
    args = tuple(_name(arg, "an argument") for arg in expr[1:])
    if predicate == "=":
        if ":equality" not in domain.requirements and variables is not None:
            raise _error(expr, "(= ...) needs :equality in the domain's :requirements")
        if len(args) != 2:
            raise _error(expr, f"(= ...) takes 2 arguments, got {len(args)}")
        expected: tuple[str, ...] = (ROOT_TYPE, ROOT_TYPE)
    elif predicate not in domain.predicates:
        raise _error(expr, f"unknown predicate {predicate!r}")
    else:
        expected = domain.predicates[predicate]
        if len(args) != len(expected):
            raise _error(expr, f"{predicate} takes {len(expected)} argument(s), got {len(args)}")
    for arg, kind, token in zip(args, expected, expr[1:], strict=True):
        scope = variables if arg.startswith("?") else objects
        if scope is None or arg not in scope:
            what = "variable" if arg.startswith("?") else "object or constant"
            raise _error(token, f"unknown {what} {arg!r}")
        if kind != ROOT_TYPE and not domain.is_subtype(scope[arg], kind):
            raise _error(token, f"{arg!r} is a {scope[arg]}, but {predicate} expects a {kind}")
    return Atom(predicate, args)


def _literals(expr: SExpr, domain: Domain, variables: dict[str, str] | None, objects: dict[str, str],
              what: str) -> list[Condition]:
    """A conjunction of (possibly negated) atoms; ``()`` is the empty conjunction."""
    if not expr:
        return []
    head = _name(expr[0], "a predicate or 'and'")
    if head == "and":
        return [c for part in expr[1:] for c in _literals(_sub(part, what), domain, variables, objects, what)]
    if head == "not":
        if len(expr) != 2:
            raise _error(expr, "(not ...) takes exactly one atom")
        inner = _sub(expr[1], what)
        if inner and _name(inner[0], "an atom") in ("and", "not", "or"):
            raise _error(inner, f"only atoms can be negated in a {what}")
        if (what == "precondition" and ":negative-preconditions" not in domain.requirements
                and inner and _name(inner[0], "") != "="):
            raise _error(expr, "negative preconditions need :negative-preconditions in :requirements")
        return [Condition(_atom(inner, domain, variables, objects), positive=False)]
    if head in ("or", "imply", "exists", "forall", "when", "increase", "decrease", "assign"):
        raise _error(expr, f"{head!r} is not STRIPS: only conjunctions of literals are supported")
    return [Condition(_atom(expr, domain, variables, objects))]


def _sub(item, what: str) -> SExpr:
    if not isinstance(item, SExpr):
        raise _error(item, f"expected a parenthesised {what} element, found {item[0]!r}")
    return item


def _sections(root: SExpr, kind: str) -> tuple[str, list[SExpr]]:
    if len(root) < 2 or _name(root[0], "define") != "define":
        raise _error(root, "expected (define ...)")
    header = _sub(root[1], f"({kind} NAME)")
    if len(header) != 2 or _name(header[0], kind) != kind:
        raise _error(header, f"expected ({kind} NAME)")
    return _name(header[1], f"a {kind} name"), [_sub(s, "section") for s in root[2:]]


def parse_domain(text: str) -> Domain:
    name, sections = _sections(parse_sexpr(text), "domain")
    domain = Domain(name)
    for section in sections:
        key = _name(section[0], "a section keyword") if section else ""
        body = section[1:]
        if key == ":requirements":
            domain.requirements = {_name(r, "a requirement") for r in body}
            unsupported = domain.requirements - SUPPORTED_REQUIREMENTS
            if unsupported:
                raise _error(section, f"unsupported requirement(s) {', '.join(sorted(unsupported))}; "
                                      f"supported: {', '.join(sorted(SUPPORTED_REQUIREMENTS))}")
        elif key == ":types":
            for child, parent, _ in _typed_list(body, section, variables=False):
                domain.types[child] = parent
                domain.types.setdefault(parent, ROOT_TYPE)
            domain.types[ROOT_TYPE] = ""
        elif key == ":constants":
            for const, kind, token in _typed_list(body, section, variables=False):
                _check_type(domain, kind, token)
                domain.constants[const] = kind
        elif key == ":predicates":
            for decl in body:
                decl = _sub(decl, "predicate declaration")
                pred = _name(decl[0], "a predicate name")
                params = _typed_list(decl[1:], decl, variables=True)
                for _, kind, token in params:
                    _check_type(domain, kind, token)
                domain.predicates[pred] = tuple(kind for _, kind, _ in params)
        elif key == ":action":
            domain.actions.append(_action(section, domain))
        else:
            raise _error(section, f"unsupported domain section {key or '()'!r}")
    return domain


def _action(section: SExpr, domain: Domain) -> Action:
    if len(section) < 2:
        raise _error(section, "(:action NAME ...) needs a name")
    name = _name(section[1], "an action name")
    fields: dict[str, SExpr] = {}
    items = section[2:]
    for key, value in zip(items[::2], items[1::2], strict=False):
        fields[_name(key, ":parameters, :precondition or :effect")] = _sub(value, "action field")
    if len(items) % 2:
        raise _error(items[-1], f"action {name}: a keyword without a value")
    unknown = set(fields) - {":parameters", ":precondition", ":effect"}
    if unknown:
        raise _error(section, f"action {name}: unsupported field(s) {', '.join(sorted(unknown))}")
    params = _typed_list(list(fields.get(":parameters", [])), section, variables=True)
    for _, kind, token in params:
        _check_type(domain, kind, token)
    variables = {var: kind for var, kind, _ in params}
    pre = _literals(fields.get(":precondition", SExpr([], section.start)), domain, variables, domain.constants,
                    "precondition")
    effect = _literals(fields.get(":effect", SExpr([], section.start)), domain, variables, domain.constants, "effect")
    if any(c.atom.predicate == "=" for c in effect):
        raise _error(section, f"action {name}: equality cannot be an effect")
    return Action(name, tuple((v, k) for v, k, _ in params), tuple(pre),
                  tuple(c.atom for c in effect if c.positive), tuple(c.atom for c in effect if not c.positive))


def parse_problem(text: str, domain: Domain) -> Problem:
    root = parse_sexpr(text)
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
                fact = _sub(fact, "initial fact")
                if fact and _name(fact[0], "") in ("not", "="):
                    raise _error(fact, "the initial state lists true atoms only")
                problem.init.add(_atom(fact, domain, None, problem.objects))
        elif key == ":goal":
            goal_section = section
        elif key == ":requirements":
            continue
        else:
            raise _error(section, f"unsupported problem section {key or '()'!r}")
    if goal_section is None or len(goal_section) != 2:
        raise _error(goal_section or root, "the problem needs one (:goal EXPRESSION)")
    problem.goal = tuple(_literals(_sub(goal_section[1], "goal"), domain, None, problem.objects, "goal"))
    return problem
