"""The planning pipeline: parse -> ground -> search -> plan, with the search and heuristic by name."""

from __future__ import annotations

import time

from strips_planner.grounding import Operator, Task, ground
from strips_planner.heuristics import GREEDY_ONLY, HEURISTICS
from strips_planner.pddl import PddlUnsupportedError, parse_domain, parse_problem
from strips_planner.search import DEFAULT_HEURISTIC, SEARCHES, SearchStats, search


class PlanResult:
    def __init__(self, plan: list[Operator] | None, reason: str = "", stats: SearchStats | None = None,
                 seconds: float = 0.0, cost: int | None = None) -> None:
        self.plan = plan
        """None: no plan exists, or none was found in the search's time (``stats.timed_out``)."""
        self.reason, self.stats, self.seconds = reason, stats or SearchStats(), seconds
        self.cost = cost
        """The plan's total-cost where the problem minimises it; None where every action costs 1."""
        self.warnings: list[str] = []
        """What the reader let through that strict PDDL refuses."""


def check_choice(search: str, heuristic: str | None) -> str:
    """The heuristic to use; a ValueError naming the valid values for an unknown one."""
    if search not in SEARCHES:
        raise ValueError(f"unknown search {search!r}; valid: {', '.join(SEARCHES)}")
    heuristic = heuristic or DEFAULT_HEURISTIC[search]
    names = heuristic.split("+")
    for name in names:
        if name not in HEURISTICS:
            raise ValueError(f"unknown heuristic {name!r}; valid: {', '.join(HEURISTICS)}, or several joined by '+' "
                             "for gbfs and lazy")
    if len(set(names)) < len(names):
        raise ValueError(f"{heuristic!r} names a heuristic twice")
    greedy = search in ("gbfs", "lazy")
    if not greedy and (len(names) > 1 or set(names) & set(GREEDY_ONLY)):
        raise ValueError(f"{heuristic!r} guides only the greedy searches (gbfs, lazy), not {search}")
    return heuristic


def solve_task(task: Task, search_name: str = "bfs", heuristic: str | None = None, seconds: float = 0.0) -> PlanResult:
    """Search ``task`` for at most ``seconds`` (0: no limit); with conditional effects A*'s default is hmax, and
    LM-cut is refused with :class:`PddlUnsupportedError` (its cuts would no longer be admissible)."""
    if heuristic is None and task.conditional_effects and "lmcut" in DEFAULT_HEURISTIC.get(search_name, ""):
        heuristic = "hmax"
    heuristic = check_choice(search_name, heuristic)
    if task.conditional_effects and "lmcut" in heuristic.split("+"):
        raise PddlUnsupportedError(f"?:?: lmcut does not take conditional effects (this task has "
                                   f"{task.conditional_effects}); hmax keeps A*'s plans optimal")
    start = time.perf_counter()
    if task.unsolvable_reason:
        return PlanResult(None, task.unsolvable_reason, seconds=time.perf_counter() - start)
    stats = SearchStats()
    plan = search(task, search_name, heuristic, stats, seconds)
    reason = ("" if plan is not None else f"no plan found in {seconds:g} s ({stats.expanded:,} states expanded)"
              if stats.timed_out else "no state reachable from the initial state satisfies the goal")
    cost = stats.cost if plan is not None and task.costs is not None else None
    return PlanResult(plan, reason, stats, time.perf_counter() - start, cost)


def solve_pddl(domain_text: str, problem_text: str, search: str = "bfs", heuristic: str | None = None) -> PlanResult:
    """Parse, ground and search; raises :class:`~strips_planner.pddl.PddlError` on bad PDDL."""
    domain = parse_domain(domain_text)
    task = ground(domain, parse_problem(problem_text, domain))
    result = solve_task(task, search, heuristic)
    result.warnings = domain.warnings
    return result
