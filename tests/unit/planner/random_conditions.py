"""Random ADL conditions over a two-object world, and their truth read straight off their text: the tests of ADL
conditions and of conditional effects compare grounding with them."""

from strips_planner.pddl import Atom


def random_condition(rng, depth: int, variables: list[str]) -> str:
    """A random ADL condition over p/1 and q/2 (both changed by actions) and r/1 (static)."""
    if depth == 0 or rng.random() < 0.3:
        head = rng.choice(["p", "q", "r", "="])
        args = [rng.choice(variables) for _ in range(1 if head in ("p", "r") else 2)]
        atom = f"({head} {' '.join(args)})"
        return f"(not {atom})" if rng.random() < 0.4 else atom
    kind = rng.choice(["and", "or", "not", "imply", "forall", "exists"])
    if kind in ("and", "or"):
        return f"({kind} {' '.join(random_condition(rng, depth - 1, variables) for _ in range(rng.randint(1, 3)))})"
    if kind == "not":
        return f"(not {random_condition(rng, depth - 1, variables)})"
    if kind == "imply":
        return f"(imply {random_condition(rng, depth - 1, variables)} {random_condition(rng, depth - 1, variables)})"
    bound = f"?v{depth}"
    return f"({kind} ({bound}) {random_condition(rng, depth - 1, [*variables, bound])})"


def evaluate_text(expr: list, binding: dict[str, str], truth) -> bool:
    """The condition's truth read straight off its text (objects a and b), apart from the reader and grounding."""
    head, args = expr[0], expr[1:]
    if head in ("and", "or"):
        return (all if head == "and" else any)(evaluate_text(a, binding, truth) for a in args)
    if head == "not":
        return not evaluate_text(args[0], binding, truth)
    if head == "imply":
        return not evaluate_text(args[0], binding, truth) or evaluate_text(args[1], binding, truth)
    if head in ("forall", "exists"):
        values = (evaluate_text(args[1], {**binding, args[0][0]: o}, truth) for o in "ab")
        return (all if head == "forall" else any)(values)
    names = [binding.get(a, a) for a in args]
    return names[0] == names[1] if head == "=" else truth(Atom(head, tuple(names)))
