"""Times our planner on one PDDL task in this process; semgoal_bench/planner.py runs it once per (problem, search),
and once with SEARCH ``none``: parse + ground alone, as no search's memory, freed behind it, is paid for by the next
run's parse + ground.

    python src/semgoal_bench/semgoal_bench/runners/time_ours.py DOMAIN PROBLEM SEARCH HEURISTIC REPEATS   -> one JSON line

Each run's parse + ground time is also printed as it is known (``front SECONDS``), so a search that runs out of
time still leaves its parse + ground figure.
"""

import gc
import json
import sys
import time

from strips_planner.grounding import ground
from strips_planner.pddl import parse_domain, parse_problem
from strips_planner.planner import solve_task

NO_SEARCH = "none"


def main(domain_path: str, problem_path: str, search: str, heuristic: str, repeats: str) -> None:
    times, front, result = [], [], None
    gc.collect()  # what importing left, collected before the first timed run, not inside whichever run it lands in
    for _ in range(int(repeats)):
        start = time.perf_counter()  # both runners read the files inside the timing, as pyperplan's parser does
        domain = parse_domain(_read(domain_path))
        task = ground(domain, parse_problem(_read(problem_path), domain))
        front.append(time.perf_counter() - start)
        print(f"front {front[-1]}", flush=True)
        if search != NO_SEARCH:
            result = solve_task(task, search, heuristic)
        times.append(time.perf_counter() - start)
    plan = None if result is None or result.plan is None else [f"({' '.join((op.name, *op.args))})" for op in result.plan]
    print(json.dumps({"length": None if plan is None else len(plan), "plan": plan, "seconds": times,
                      "front_seconds": front}))


def _read(path: str) -> str:
    """As pyperplan's parser reads a file (``open`` with UTF-8), not through the locale's encoding."""
    with open(path, encoding="utf-8") as file:
        return file.read()


if __name__ == "__main__":
    main(*sys.argv[1:6])
