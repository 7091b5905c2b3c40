"""`./semgoal bench planner [--json] [--suite DIR]`: our planner beside pyperplan on blocksworld and the project's
tasks, or on a whole folder of PDDL benchmarks beside pyperplan and Fast Downward (``--suite``, bench/planner_suite.py).

pyperplan (GPL) is installed by this benchmark into a throwaway venv (``.bench/pyperplan``), never
imported by the product. Each (planner, problem, search) runs in its own subprocess under a time limit
and times parse + ground + search in-process, ``--repeats`` times; the median is reported, with the
ratio pyperplan / ours, overall and per phase (parse + ground, timed again in a process of its own without searches
between its runs; search, the heuristic's set-up included), so a row shows where the time goes. pyperplan has no
negative preconditions, so the project's scene domains run on our planner only (against the 5 ms target).
"""

from __future__ import annotations

import argparse
import functools
import json
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from semgoal_bench.planner_suite import PLANNERS, bench_python, run_suite, table
from semgoal_core.arguments import count, counts, names, seconds
from semgoal_planner.blocksworld import DOMAIN_PATH, problem

COMBOS = (("bfs", "blind"), ("astar", "hmax"), ("astar", "lmcut"), ("gbfs", "hff"))
SIZES = (4, 6, 8, 10, 12)
PHASES = ("parse_ground", "search")

RUNNERS = Path(__file__).resolve().parent / "runners"
OURS_RUNNER = RUNNERS / "time_ours.py"
PYPERPLAN_RUNNER = RUNNERS / "time_pyperplan.py"  # not pyperplan.py: the script's folder comes first on sys.path



def run_one(python: str, runner: Path, domain: Path, prob: Path, search: str, heuristic: str, repeats: int,
            timeout: float) -> dict:
    """The whole runs' figures, and parse + ground's from a process of their own (:func:`parse_ground_alone`)."""
    result = _whole_runs(python, runner, domain, prob, search, heuristic, repeats, timeout)
    if not result["status"].startswith("error"):
        fronts = parse_ground_alone(python, runner, domain, prob, repeats, timeout)
        result.update(parse_ground_ms=_median_ms(fronts), parse_ground_runs=fronts)
    return result


@functools.cache
def parse_ground_alone(python: str, runner: Path, domain: Path, prob: Path, repeats: int, timeout: float
                       ) -> tuple[float, ...]:
    """Each of ``repeats`` parse + ground runs (seconds) in a fresh process without searches between them, once per
    planner and problem whatever the searches run on it: a search
    leaves its memory freed behind it, and the next run's parse + ground paid for that (our 0.45 ms to parse and ground
    blocksworld 10 before a breadth-first search, 0.69 and 0.62 ms after it: the median is a run's own cost)."""
    out = subprocess.run([python, str(runner), str(domain), str(prob), "none", "none", str(repeats)],
                         capture_output=True, text=True, timeout=timeout, check=True).stdout
    return tuple(json.loads(out.strip().splitlines()[-1])["front_seconds"])


def _whole_runs(python: str, runner: Path, domain: Path, prob: Path, search: str, heuristic: str, repeats: int,
                timeout: float) -> dict:
    try:
        out = subprocess.run([python, str(runner), str(domain), str(prob), search, heuristic, str(repeats)],
                             capture_output=True, text=True, timeout=timeout, check=True).stdout
    except subprocess.TimeoutExpired as error:  # the parse + ground times it printed before its search ran out
        fronts = [float(line.split()[1]) for line in (error.stdout or b"").decode().splitlines() if line.startswith("front ")]
        return {"length": None, "median_ms": None, "status": f"timeout ({timeout:.0f} s)",
                "parse_ground_ms": _median_ms(fronts) if fronts else None, "parse_ground_runs": fronts}
    except subprocess.CalledProcessError as error:
        return {"length": None, "median_ms": None, "status": f"error: {error.stderr.strip().splitlines()[-1]}"}
    data = json.loads(out.strip().splitlines()[-1])
    search_s = [total - front for total, front in zip(data["seconds"], data["front_seconds"], strict=True)]
    return {"length": data["length"], "median_ms": _median_ms(data["seconds"]), "status": "ok",
            "parse_ground_ms": _median_ms(data["front_seconds"]), "search_ms": _median_ms(search_s),
            "parse_ground_runs": data["front_seconds"],
            "plan": data.get("plan")}


def _median_ms(seconds: list[float]) -> float:
    return round(statistics.median(seconds) * 1000, 3)


def project_tasks(repeats: int) -> dict[str, dict]:
    """Each task planned from a typical start state with breadth-first search, in this process."""
    from semgoal_core.tasks import TASKS
    from semgoal_core.vocabulary import Literal
    from semgoal_planner.goals import parse_goal
    from semgoal_planner.semantic import SemanticPlanner

    starts = {"MA-2": [Literal("close", ("red", "green"))],
              "Swap-2": [Literal("close", ("red", "green")), Literal("above", ("green", "red"))],
              "MA-3": [Literal("close", p) for p in (("red", "green"), ("red", "blue"), ("green", "blue"))]}
    rows = {}
    for name, task in TASKS.items():
        state = starts.get(name, [])
        planner = SemanticPlanner(task.scene)
        goal = parse_goal(name, task.scene, task.blocks, state)
        times = []
        for _ in range(repeats):
            start = time.perf_counter()
            steps = planner.plan(task.blocks, state, goal)
            times.append(time.perf_counter() - start)
        rows[name] = {"length": len(steps), "median_ms": round(statistics.median(times) * 1000, 3)}
    return rows


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="semgoal bench planner", description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeats", type=count, help="runs per measurement, the median kept (default: 3; 1 with --suite)")
    parser.add_argument("--timeout", type=seconds, default=60.0, help="seconds per planner, problem and search")
    parser.add_argument("--sizes", type=counts, default=list(SIZES))
    parser.add_argument("--suite", type=Path, help="a folder of PDDL domains in the IPC layout: coverage, validity "
                        "and whole-process times instead of the blocksworld series")
    parser.add_argument("--per-domain", type=count, default=6, help="with --suite: the first N problems of each domain")
    parser.add_argument("--domains", type=names, help="with --suite: only these comma-separated domain folders")
    parser.add_argument("--planners", type=names, default="ours,pyperplan,fast-downward",
                        help=f"with --suite: any of {', '.join(PLANNERS)}")
    parser.add_argument("--search", default="lazy/hff+lmcount", help="with --suite: SEARCH/HEURISTIC (lazy/hff+lmcount: "
                        "ours beside Fast Downward's lama-first, the same pair in a lazy search)")
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args(argv)
    if args.suite:
        planners = args.planners
        if not args.suite.is_dir() or set(planners) - set(PLANNERS):
            parser.error(f"--suite {args.suite}: not a folder" if not args.suite.is_dir() else
                         f"--planners: unknown {', '.join(sorted(set(planners) - set(PLANNERS)))}")
        search, _, heuristic = args.search.partition("/")
        progress = None if args.json else functools.partial(print, flush=True)
        result = run_suite(args.suite, planners, args.per_domain, args.timeout, search, heuristic or "blind",
                           repeats=args.repeats or 1, domains=set(args.domains) if args.domains else None,
                           progress=progress)
        if not args.json:
            print(table(result))
        keys = ("search", "problems", "coverage", "invalid_plans", "errors", "median_ratio_to_ours", "left_out")
        print(json.dumps(result if args.json else {k: result[k] for k in keys}))
        return 0
    args.repeats = args.repeats or 3
    pyperplan = str(bench_python("pyperplan"))
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for n in args.sizes:
            prob = Path(tmp) / f"bw-{n}.pddl"
            prob.write_text(problem(n, seed=1))
            for search, heuristic in COMBOS:
                ours = run_one(sys.executable, OURS_RUNNER, DOMAIN_PATH, prob, search, heuristic, args.repeats, args.timeout)
                theirs = run_one(pyperplan, PYPERPLAN_RUNNER, DOMAIN_PATH, prob, search, heuristic, args.repeats, args.timeout)
                ratio, bound = speedup(ours, theirs, args.timeout)
                rows.append({"problem": f"blocksworld-{n}", "search": f"{search}/{heuristic}", "ours": ours,
                             "pyperplan": theirs, "speedup": ratio, "speedup_bound": bound,
                             **{f"{phase}_speedup": phase_speedup(ours, theirs, phase) for phase in PHASES}})
                if not args.json:
                    print(f"bw-{n:<3d} {search:5s}/{heuristic:6s} ours {_cell(ours)}  pyperplan {_cell(theirs)}  "
                          f"speedup {_ratio_cell(ratio, bound)}  (parse+ground {_ratio_cell(rows[-1]['parse_ground_speedup'], '')}, "
                          f"search {_ratio_cell(rows[-1]['search_speedup'], '')})", flush=True)
    tasks = project_tasks(max(args.repeats, 20))
    if not args.json:
        for name, row in tasks.items():
            print(f"{name:7s} bfs plan length {row['length']}  {row['median_ms']:.2f} ms (ours; pyperplan: no negative preconditions)")
    bounds: dict[str, set[str]] = {}
    for row in rows:
        if row["speedup"] and row["speedup_bound"]:
            bounds.setdefault(row["search"], set()).add(row["speedup_bound"])
    summary = {"median_speedup": _medians_by_search(rows, "speedup"),
               **{f"median_{phase}_speedup": _medians_by_search(rows, f"{phase}_speedup") for phase in PHASES},
               "medians_with_bounds": {k: sorted(v) for k, v in bounds.items()},
               "same_length_optimal": all(r["ours"]["length"] == r["pyperplan"]["length"] for r in rows
                                          if r["search"] != "gbfs/hff" and r["ours"]["length"] and r["pyperplan"]["length"]),
               "max_task_ms": max(r["median_ms"] for r in tasks.values())}
    print(json.dumps({"blocksworld": rows, "tasks": tasks, "summary": summary}) if args.json else json.dumps(summary))
    return 0


def speedup(ours: dict, theirs: dict, timeout_s: float) -> tuple[float | None, str]:
    """pyperplan's time over ours, with a bound where one planner ran out of time: "lower" when only
    pyperplan did (its time is at least the limit, so the ratio is at least limit / ours), "upper" when
    only ours did. None when neither finished or one failed otherwise."""
    limit_ms = timeout_s * 1000
    if ours["median_ms"] and theirs["median_ms"]:
        return round(theirs["median_ms"] / ours["median_ms"], 1), ""
    if ours["median_ms"] and theirs["status"].startswith("timeout"):
        return round(limit_ms / ours["median_ms"], 1), "lower"
    if theirs["median_ms"] and ours["status"].startswith("timeout"):
        return round(theirs["median_ms"] / limit_ms, 2), "upper"
    return None, ""


def phase_speedup(ours: dict, theirs: dict, phase: str) -> float | None:
    """pyperplan's time over ours in one phase: search (with the heuristic's set-up) where both planners finished;
    parse + ground wherever both got through it, over as many runs of each as the one with fewer had (a process's
    first run is its slowest: a first run is compared with a first)."""
    if phase == "parse_ground":
        runs = min(len(ours.get("parse_ground_runs", [])), len(theirs.get("parse_ground_runs", [])))
        if not runs:
            return None
        return round(_median_ms(theirs["parse_ground_runs"][:runs]) / _median_ms(ours["parse_ground_runs"][:runs]), 1)
    if ours["status"] != "ok" or theirs["status"] != "ok" or not ours["search_ms"]:
        return None
    return round(theirs["search_ms"] / ours["search_ms"], 1)


def _medians_by_search(rows: list[dict], key: str) -> dict[str, float]:
    values: dict[str, list[float]] = {}
    for row in rows:
        if row[key]:
            values.setdefault(row["search"], []).append(row[key])
    return {search: round(statistics.median(v), 2) for search, v in values.items()}


def _ratio_cell(ratio: float | None, bound: str) -> str:
    return "-" if ratio is None else f"{ {'lower': '>=', 'upper': '<='}.get(bound, '')}{ratio}"


def _cell(result: dict) -> str:
    if result["status"] != "ok":
        return f"{result['status']:>21s}"
    return f"len {result['length']!s:>3s} {result['median_ms']:10.2f} ms"
