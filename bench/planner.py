"""`./semgoal bench-planner [--json] [--suite DIR]`: our planner beside pyperplan on blocksworld and the project's
tasks, or on a whole folder of PDDL benchmarks (``--suite``: coverage, every plan validated).

pyperplan (GPL) is installed by this benchmark into a throwaway venv (``.bench/pyperplan``), never
imported by the product. Each (planner, problem, search) runs in its own subprocess under a time limit
and times parse + ground + search in-process, ``--repeats`` times; the median is reported, with the
ratio pyperplan / ours, overall and per phase (parse + ground; search, the heuristic's set-up included),
so a row shows where the time goes. pyperplan has no negative preconditions, so the project's scene domains run
on our planner only (against the 5 ms target).
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

from semgoal_planner.blocksworld import DOMAIN_PATH, problem

PYPERPLAN = "pyperplan==2.1"
VENV = Path(__file__).resolve().parents[1] / ".bench" / "pyperplan"
COMBOS = (("bfs", "blind"), ("astar", "hmax"), ("astar", "lmcut"), ("gbfs", "hff"))
SIZES = (4, 6, 8, 10, 12)
PHASES = ("parse_ground", "search")

RUNNERS = Path(__file__).resolve().parent / "runners"
OURS_RUNNER = RUNNERS / "ours.py"
PYPERPLAN_RUNNER = RUNNERS / "pyperplan.py"


def ensure_pyperplan() -> Path:
    python = VENV / "bin" / "python"
    if not python.exists():
        subprocess.run([sys.executable, "-m", "venv", str(VENV)], check=True)
        subprocess.run([str(python), "-m", "pip", "install", "-q", PYPERPLAN], check=True)
    return python


def run_one(python: str, runner: Path, domain: Path, prob: Path, search: str, heuristic: str, repeats: int,
            timeout: float) -> dict:
    try:
        out = subprocess.run([python, str(runner), str(domain), str(prob), search, heuristic, str(repeats)],
                             capture_output=True, text=True, timeout=timeout, check=True).stdout
    except subprocess.TimeoutExpired:
        return {"length": None, "median_ms": None, "status": f"timeout ({timeout:.0f} s)"}
    except subprocess.CalledProcessError as error:
        return {"length": None, "median_ms": None, "status": f"error: {error.stderr.strip().splitlines()[-1]}"}
    data = json.loads(out.strip().splitlines()[-1])
    search_s = [total - front for total, front in zip(data["seconds"], data["front_seconds"], strict=True)]
    return {"length": data["length"], "median_ms": _median_ms(data["seconds"]), "status": "ok",
            "parse_ground_ms": _median_ms(data["front_seconds"]), "search_ms": _median_ms(search_s),
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


def suite_problems(folder: Path, per_domain: int) -> list[tuple[str, Path, Path]]:
    """(domain name, domain file, problem file) of a benchmark folder in the IPC layout: a folder per domain,
    each problem beside ``domain.pddl`` or its own ``domain_<problem>.pddl``; the first ``per_domain`` problems."""
    found = []
    for domain_dir in sorted(d for d in folder.iterdir() if d.is_dir()):
        problems = sorted(p for p in domain_dir.glob("*.pddl") if not p.name.startswith("domain"))[:per_domain]
        for problem_path in problems:
            own = domain_dir / f"domain_{problem_path.name}"
            domain_path = own if own.exists() else domain_dir / "domain.pddl"
            if domain_path.exists():
                found.append((domain_dir.name, domain_path, problem_path))
    return found


@functools.cache
def _parsed(domain_path: Path, problem_path: Path):
    """A problem and its domain, parsed once however many planners' plans are checked against them."""
    from semgoal_planner.pddl import parse_domain, parse_problem

    domain = parse_domain(domain_path.read_text())
    return domain, parse_problem(problem_path.read_text(), domain)


def validity(domain_path: Path, problem_path: Path, plan: list[str] | None) -> str:
    """"" for a valid plan (or none), else why not: the plan is run on the lifted actions (validate_plan.py)."""
    from bench.validate_plan import invalid_step, read_plan

    if plan is None:
        return ""
    return invalid_step(*_parsed(domain_path, problem_path), read_plan("\n".join(plan))) or ""


def run_suite(folder: Path, planners: list[str], per_domain: int, timeout: float, search: str, heuristic: str) -> dict:
    """Every planner on every problem of the suite (one run each, whole process under ``timeout``), every plan
    validated: per domain the problems solved, the invalid plans and the median time ratio to ours."""
    pythons = {"ours": (sys.executable, OURS_RUNNER)}
    if "pyperplan" in planners:
        pythons["pyperplan"] = (str(ensure_pyperplan()), PYPERPLAN_RUNNER)
    domains: dict[str, dict] = {}
    for name, domain_path, problem_path in suite_problems(folder, per_domain):
        row = domains.setdefault(name, {"problems": 0, **{p: {"solved": 0, "invalid": [], "ms": []} for p in pythons}})
        row["problems"] += 1
        for planner, (python, runner) in pythons.items():
            result = run_one(python, runner, domain_path, problem_path, search, heuristic, 1, timeout)
            if result["status"] != "ok" or result["length"] is None:
                continue
            reason = validity(domain_path, problem_path, result["plan"])
            if reason:
                row[planner]["invalid"].append(f"{problem_path.name}: {reason}")
                continue
            row[planner]["solved"] += 1
            row[planner]["ms"].append(result["median_ms"])
    for row in domains.values():
        for planner in pythons:
            times = row[planner].pop("ms")
            row[planner]["median_ms"] = round(statistics.median(times), 2) if times else None
    coverage = {p: sum(row[p]["solved"] for row in domains.values()) for p in pythons}
    invalid = {p: sum(len(row[p]["invalid"]) for row in domains.values()) for p in pythons}
    return {"search": f"{search}/{heuristic}", "timeout_s": timeout, "domains": domains,
            "problems": sum(row["problems"] for row in domains.values()), "coverage": coverage, "invalid_plans": invalid}


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="semgoal bench-planner", description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--timeout", type=float, default=60.0, help="seconds per planner, problem and search")
    parser.add_argument("--sizes", default=",".join(map(str, SIZES)))
    parser.add_argument("--suite", type=Path, help="a folder of PDDL domains in the IPC layout: coverage and "
                        "validity instead of the blocksworld series")
    parser.add_argument("--per-domain", type=int, default=6, help="with --suite: the first N problems of each domain")
    parser.add_argument("--planners", default="ours,pyperplan", help="with --suite: ours, pyperplan")
    parser.add_argument("--search", default="gbfs/hff", help="with --suite: SEARCH/HEURISTIC")
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args(argv)
    if args.suite:
        if not args.suite.is_dir():
            parser.error(f"--suite {args.suite}: not a folder")
        search, _, heuristic = args.search.partition("/")
        result = run_suite(args.suite, args.planners.split(","), args.per_domain, args.timeout, search, heuristic or "blind")
        if not args.json:
            for name, row in result["domains"].items():
                cells = "  ".join(f"{p} {row[p]['solved']}/{row['problems']} ({len(row[p]['invalid'])} invalid)"
                                  for p in row if p != "problems")
                print(f"{name:24s} {cells}")
        print(json.dumps(result) if args.json else json.dumps({k: result[k] for k in ("problems", "coverage", "invalid_plans")}))
        return 0
    pyperplan = str(ensure_pyperplan())
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for n in map(int, args.sizes.split(",")):
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
    """pyperplan's time over ours in one phase (parse + ground, or search with the heuristic's set-up),
    where both planners finished."""
    if ours["status"] != "ok" or theirs["status"] != "ok" or not ours[f"{phase}_ms"]:
        return None
    return round(theirs[f"{phase}_ms"] / ours[f"{phase}_ms"], 1)


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
