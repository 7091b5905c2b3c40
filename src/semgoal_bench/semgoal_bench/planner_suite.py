"""`./semgoal bench planner --suite DIR`: planners on a folder of PDDL benchmarks, as a user would run them.

Every planner runs as a whole process, the way its own command line is used (``./semgoal plan-pddl``,
``pyperplan``, Fast Downward's ``fast-downward.py``), under the time limit; the wall-clock time of that process is
what is compared, start-up included. Every plan is checked by the lifted validator (:mod:`semgoal_bench.validate_plan`).
pyperplan (GPL) and Fast Downward (GPL, the ``up-fast-downward`` wheel) are installed into throwaway venvs under
``.bench/``, never product dependencies; a planner that does not install is left out with the reason.

Searches are named as ours are. Fast Downward runs ``astar/H`` as ``astar(H())`` and ``gbfs/hff`` as its
``lama-first`` alias, its usual satisficing configuration.
"""

from __future__ import annotations

import functools
import os
import re
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(os.environ.get("SEMGOAL_ROOT") or Path.cwd())
"""The checkout (``tools/env.sh`` sets SEMGOAL_ROOT): the throwaway venvs live in its ``.bench/``."""
BENCH_VENVS = ROOT / ".bench"
PINS = {"pyperplan": "pyperplan==2.1", "fast-downward": "up-fast-downward==1.0.0"}
PLANNERS = ("ours", "pyperplan", "fast-downward")


@dataclass(frozen=True)
class Run:
    status: str
    """"solved", "unsolvable", "timeout" or "error: ..." (the last line the planner wrote)."""
    seconds: float
    plan: tuple[str, ...] | None = None


@dataclass(frozen=True)
class Planner:
    name: str
    command: Callable[[Path, Path, str, str, Path], list[str]]
    """(domain, problem, search, heuristic, work folder) -> the command line."""
    plan: Callable[[subprocess.CompletedProcess, Path, Path], tuple[str, ...] | None]
    """(the finished process, problem, work folder) -> the plan's steps, or None when it found none."""
    unsolvable: tuple[int, ...] = (1,)


def plan_lines(text: str) -> tuple[str, ...]:
    """A plan's actions, a line each, as planners print them: comments (``; cost = 9``) and blank lines left out."""
    return tuple(line for line in text.split("\n") if line and not line.startswith(";"))


def _ours() -> Planner:
    def command(domain: Path, problem: Path, search: str, heuristic: str, _: Path) -> list[str]:
        return [str(ROOT / "semgoal"), "plan-pddl", "--search", search, "--heuristic", heuristic, str(domain), str(problem)]

    def plan(done: subprocess.CompletedProcess, _: Path, __: Path) -> tuple[str, ...] | None:
        return plan_lines(done.stdout) if done.returncode == 0 else None

    return Planner("ours", command, plan)


def _pyperplan(python: Path) -> Planner:
    def command(domain: Path, problem: Path, search: str, heuristic: str, work: Path) -> list[str]:
        copy = work / problem.name  # pyperplan writes its plan beside the problem
        shutil.copy(problem, copy)
        # pyperplan's one greedy search evaluates every state it generates: it stands in for lazy too, and with one
        # heuristic at a time hFF stands in for hFF and the landmark count taking turns
        return [str(python.parent / "pyperplan"), "-l", "error", "-s", {"gbfs": "gbf", "lazy": "gbf"}.get(search, search),
                "-H", {"hff+lmcount": "hff"}.get(heuristic, heuristic), str(domain), str(copy)]

    def plan(done: subprocess.CompletedProcess, problem: Path, work: Path) -> tuple[str, ...] | None:
        found = work / f"{problem.name}.soln"
        return tuple(found.read_text().split("\n")[:-1]) if done.returncode == 0 and found.exists() else None

    return Planner("pyperplan", command, plan, unsolvable=(0,))


def _fast_downward(python: Path) -> Planner:
    driver = next(python.parents[1].glob("lib/python3*/site-packages/up_fast_downward/downward/fast-downward.py"))

    def command(domain: Path, problem: Path, search: str, heuristic: str, work: Path) -> list[str]:
        files = ["--plan-file", str(work / "plan"), str(domain), str(problem)]
        if search in ("gbfs", "lazy") and heuristic in ("hff", "hff+lmcount"):
            return [str(python), str(driver), "--alias", "lama-first", *files]
        if search != "astar":
            raise ValueError(f"fast-downward: no configuration for {search}/{heuristic} (astar/H, or gbfs or lazy with "
                             "hff or hff+lmcount)")
        return [str(python), str(driver), *files, "--search", f"astar({heuristic}())"]

    def plan(done: subprocess.CompletedProcess, _: Path, work: Path) -> tuple[str, ...] | None:
        found = work / "plan"
        if done.returncode != 0 or not found.exists():
            return None
        return plan_lines(found.read_text())

    return Planner("fast-downward", command, plan, unsolvable=(11, 12))


def bench_python(name: str) -> Path:
    """The Python of a planner's throwaway venv, made on first use; RuntimeError saying why it did not install."""
    venv = BENCH_VENVS / name
    python = venv / "bin" / "python"
    if not python.exists():
        subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
        done = subprocess.run([str(python), "-m", "pip", "install", "-q", PINS[name]], capture_output=True, text=True)
        if done.returncode != 0:
            shutil.rmtree(venv)
            raise RuntimeError(f"pip install {PINS[name]} failed: {(done.stderr.strip().splitlines() or ['?'])[-1]}")
    return python


def install(name: str) -> Planner:
    """The planner by name, installed where it needs to be."""
    if name == "ours":
        return _ours()
    return {"pyperplan": _pyperplan, "fast-downward": _fast_downward}[name](bench_python(name))


def run(planner: Planner, domain: Path, problem: Path, search: str, heuristic: str, timeout: float) -> Run:
    """One whole planner process on one problem, timed by the wall clock."""
    with tempfile.TemporaryDirectory() as folder:
        work = Path(folder)
        command = planner.command(domain, problem, search, heuristic, work)
        start = time.perf_counter()
        # a session of its own, so that a time-out kills the planner's children too (Fast Downward's driver
        # runs its search as a child, which would otherwise go on using a core)
        process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=work,
                                   start_new_session=True)
        try:
            stdout, stderr = process.communicate(timeout=timeout)
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)
            process.communicate()
            return Run("timeout", timeout)
        seconds = time.perf_counter() - start
        done = subprocess.CompletedProcess(command, process.returncode, stdout, stderr)
        plan = planner.plan(done, problem, work)
    if plan is not None:
        return Run("solved", seconds, plan)
    if done.returncode in planner.unsolvable:
        return Run("unsolvable", seconds)
    last = (done.stderr.strip() or done.stdout.strip() or f"exit {done.returncode}").splitlines()[-1]
    return Run(f"error: {last}", seconds)


def suite_problems(folder: Path, per_domain: int, domains: set[str] | None = None) -> list[tuple[str, Path, Path]]:
    """(domain name, domain file, problem file) of a benchmark folder in the IPC layout: a folder per domain, each
    problem beside ``domain.pddl`` or its own domain file (``domain_p01.pddl`` or ``domain-p01.pddl`` for
    ``p01.pddl``, ``p01-domain.pddl`` for ``p01.pddl`` or ``p01-airport4.pddl``); the first ``per_domain`` problems
    of each, in natural order (``probBLOCKS-4-0`` before ``probBLOCKS-10-0``)."""
    found = []
    for domain_dir in sorted(d for d in folder.iterdir() if d.is_dir() and (domains is None or d.name in domains)):
        problems = sorted((p for p in domain_dir.glob("*.pddl") if "domain" not in p.name), key=_natural)[:per_domain]
        for problem_path in problems:
            name, prefix = problem_path.name, problem_path.stem.split("-")[0]
            for candidate in (f"domain_{name}", f"domain-{name}", f"{prefix}-domain.pddl", "domain.pddl"):
                if (domain_dir / candidate).exists():
                    found.append((domain_dir.name, domain_dir / candidate, problem_path))
                    break
    return found


def _natural(path: Path) -> list:
    return [int(part) if part.isdigit() else part for part in re.split(r"(\d+)", path.name)]


@functools.cache
def _parsed(domain_path: Path, problem_path: Path) -> tuple:
    """A problem and its domain, parsed once however many planners' plans are checked against them."""
    from strips_planner.pddl import parse_domain, parse_problem

    domain = parse_domain(domain_path.read_text())
    return domain, parse_problem(problem_path.read_text(), domain)


def validity(domain_path: Path, problem_path: Path, plan: tuple[str, ...] | None) -> str | None:
    """"" for a valid plan (or none), else why not: the plan is run on the lifted actions (validate_plan.py); None
    where the validator cannot read the task (PDDL outside our reader's fragment, which another planner solved)."""
    from semgoal_bench.validate_plan import invalid_step, read_plan
    from strips_planner.pddl import PddlUnsupportedError

    if plan is None:
        return ""
    try:
        parsed = _parsed(domain_path, problem_path)
    except PddlUnsupportedError:
        return None
    return invalid_step(*parsed, read_plan("\n".join(plan))) or ""


def run_suite(folder: Path, planners: list[str], per_domain: int, timeout: float, search: str, heuristic: str,
              repeats: int = 1, domains: set[str] | None = None, progress: Callable[[str], None] | None = None) -> dict:
    """Every planner on every problem (whole processes, the median wall time of ``repeats`` runs), every plan
    validated: per domain the problems solved, the invalid plans, median seconds, and each other planner's
    time over ours on the problems both solved; every run as a row of ``runs``."""
    installed: dict[str, Planner] = {}
    left_out: dict[str, str] = {}
    for name in planners:
        try:
            installed[name] = install(name)
        except (RuntimeError, StopIteration) as error:
            left_out[name] = str(error) or "its driver was not found in the installed package"
    rows: dict[str, dict] = {}
    records: list[dict] = []
    ratios: dict[str, list[float]] = {p: [] for p in installed if p != "ours"}
    for domain_name, domain_path, problem_path in suite_problems(folder, per_domain, domains):
        row = rows.setdefault(domain_name, {"problems": 0, **{p: {"solved": 0, "invalid": [], "seconds": [],
                                                                  "failed": [], "unchecked": []} for p in installed}})
        row["problems"] += 1
        results = {}
        for name, planner in installed.items():
            runs = [run(planner, domain_path, problem_path, search, heuristic, timeout) for _ in range(repeats)]
            result = Run(runs[-1].status, statistics.median(r.seconds for r in runs), runs[-1].plan)
            reason = validity(domain_path, problem_path, result.plan)
            cell = row[name]
            if reason:
                cell["invalid"].append(f"{problem_path.name}: {reason}")
            elif result.status == "solved":
                cell["solved"] += 1
                if reason is None:
                    cell["unchecked"].append(problem_path.name)
                cell["seconds"].append(result.seconds)
                results[name] = result.seconds
            elif result.status.startswith("error"):
                cell["failed"].append(f"{problem_path.name}: {result.status}")
            records.append({"domain": domain_name, "problem": problem_path.name, "planner": name, "status": result.status,
                            "seconds": round(result.seconds, 4), "length": None if result.plan is None else len(result.plan),
                            "invalid": reason})
            if progress:
                progress(f"{domain_name}/{problem_path.name} {name}: {result.status} {result.seconds:.3f} s"
                         + (f" INVALID {reason}" if reason else ""))
        for name in ratios:
            if name in results and "ours" in results:
                ratios[name].append(results[name] / results["ours"])
                row.setdefault("ratio_to_ours", {}).setdefault(name, []).append(results[name] / results["ours"])
    for row in rows.values():
        for name in installed:
            times = row[name].pop("seconds")
            row[name]["median_s"] = round(statistics.median(times), 3) if times else None
        row["ratio_to_ours"] = {n: round(statistics.median(r), 2) for n, r in row.get("ratio_to_ours", {}).items()}
    return {"search": f"{search}/{heuristic}", "timeout_s": timeout, "repeats": repeats, "left_out": left_out,
            "domains": rows, "runs": records, "problems": sum(row["problems"] for row in rows.values()),
            "coverage": {p: sum(row[p]["solved"] for row in rows.values()) for p in installed},
            "invalid_plans": {p: sum(len(row[p]["invalid"]) for row in rows.values()) for p in installed},
            "errors": {p: sum(len(row[p]["failed"]) for row in rows.values()) for p in installed},
            "unchecked_plans": {p: sum(len(row[p]["unchecked"]) for row in rows.values()) for p in installed},
            "median_ratio_to_ours": {n: round(statistics.median(r), 2) for n, r in ratios.items() if r}}


def table(result: dict) -> str:
    """The suite's result as rows a person reads: solved/problems, invalid plans and median seconds per planner."""
    lines = []
    for name, row in result["domains"].items():
        cells = "  ".join(f"{p} {row[p]['solved']}/{row['problems']}"
                          f"{' ' + str(len(row[p]['invalid'])) + ' INVALID' if row[p]['invalid'] else ''}"
                          f"{' (' + str(len(row[p]['unchecked'])) + ' unchecked)' if row[p]['unchecked'] else ''}"
                          f" {row[p]['median_s'] if row[p]['median_s'] is not None else '-'} s"
                          for p in row if p not in ("problems", "ratio_to_ours"))
        ratios = "  ".join(f"{p}/ours {r}x" for p, r in row["ratio_to_ours"].items())
        lines.append(f"{name:22s} {cells}  {ratios}")
    for name, reason in result["left_out"].items():
        lines.append(f"{name}: left out: {reason}")
    return "\n".join(lines)
