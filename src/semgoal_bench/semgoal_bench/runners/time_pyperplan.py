"""Times pyperplan (GPL: run in its own throwaway venv, never imported by the product) on one PDDL task; SEARCH
``none``: parse + ground alone (as time_ours.py).

    .bench/pyperplan/bin/python .../runners/time_pyperplan.py DOMAIN PROBLEM SEARCH HEURISTIC REPEATS   -> one JSON line
"""

import gc
import json
import logging
import sys
import time

from pyperplan.planner import HEURISTICS, SEARCHES, _ground, _parse, _search

NO_SEARCH = "none"


def main(domain: str, problem: str, search: str, heuristic_name: str, repeats: str) -> None:
    logging.disable(logging.CRITICAL)
    search = {"gbfs": "gbf"}.get(search, search)
    heuristic = None if search in ("bfs", NO_SEARCH) else HEURISTICS[heuristic_name]
    times, front, plan = [], [], None
    gc.collect()  # what importing left, collected before the first timed run, not inside whichever run it lands in
    for _ in range(int(repeats)):
        start = time.perf_counter()
        task = _ground(_parse(domain, problem))
        front.append(time.perf_counter() - start)
        print(f"front {front[-1]}", flush=True)  # kept where the search runs out of time
        if search != NO_SEARCH:
            plan = _search(task, SEARCHES[search], heuristic and heuristic(task))
        times.append(time.perf_counter() - start)
    steps = None if plan is None else [op.name for op in plan]
    print(json.dumps({"length": None if plan is None else len(plan), "plan": steps, "seconds": times,
                      "front_seconds": front}))


if __name__ == "__main__":
    main(*sys.argv[1:6])
