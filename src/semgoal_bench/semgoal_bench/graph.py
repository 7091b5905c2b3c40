"""`./semgoal bench graph [--task T] [--episodes N] [--pixels] [--json]`: the four-node graph's speed, both modes.

Lockstep: control steps per second of wall time, end to end (sim -> predicates -> planner -> policy ->
sim, over DDS), over N episodes of the task, beside the same episodes in one process (no ROS) as the
peer: the ratio is what the graph costs; and the same episodes again, each recorded as MCAP.
The CPU the graph's processes spend per control step (user and system, every thread) is measured beside the CPU of
the same episodes in one process: unlike steps per second, it does not move with what else the machine runs.
Realtime: the sim steps at 25 Hz on its timer; the client
records when each world state arrives (:func:`arrival_timing`: the rate, and the steps late by more
than half a period). With ``--pixels`` the same lockstep episodes run again with the planner and the policy on
the RGB-D camera (the sim rendering every step, perception_node in place of predicate_node): steps/s from
pixels beside ground truth (and, with ``--composed`` too, with those nodes in one process). Figures are medians over
episodes; the last line is JSON with ``--json``.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import statistics
import time
from collections.abc import Collection, Iterator
from itertools import pairwise
from typing import NamedTuple

from semgoal_bringup.experiments.episodes import make_agent
from semgoal_bringup.graph import TRUTH, Sight, running_graph
from semgoal_core.arguments import count, natural, seconds
from semgoal_core.tasks import TASK_STEP_BUDGET, get_task
from semgoal_ros.interfaces import IN_PROCESS_VARIABLE

REALTIME_HZ = 25.0


class Run(NamedTuple):
    """One episode: its control steps, wall seconds, and the CPU seconds it cost (the graph's processes, or this one)."""

    steps: int
    wall_s: float
    cpu_s: float


def descendants_cpu_s(exclude: Collection[int] = ()) -> float:
    """CPU seconds (user + system) spent so far by this process's descendants that are still running: the graph's
    node processes; ``exclude``: process ids left out (others', whose ending would take their CPU out of the sum)."""
    import psutil

    total = 0.0
    for process in psutil.Process().children(recursive=True):
        if process.pid in exclude:
            continue
        with contextlib.suppress(psutil.NoSuchProcess):  # ended meanwhile
            times = process.cpu_times()
            total += times.user + times.system
    return total


def lockstep(task: str, episodes: int, seed: int, sight: Sight = TRUTH, record: bool = True,
             composed: bool = False) -> tuple[list[Run], list[Run]]:
    """Each episode (:class:`Run`) through the graph seeing by ``sight``, unrecorded and (with
    ``record``) recorded as MCAP (into a scratch folder, as ``eval --via-ros --record`` does): each start once of
    each kind, in turns on the same running graph, so that the ratio does not depend on a graph's start or on
    what else the machine does. ``composed``: the graph's nodes in one process (:mod:`semgoal_bringup.composed`)."""
    import tempfile
    from pathlib import Path

    plain, recorded = [], []
    with tempfile.TemporaryDirectory() as scratch, \
            running_graph(task, seed, client_name="semgoal_bench", watch=False, sight=sight, composed=composed) as client:
        for i in range(episodes):
            kinds = ((plain, None), (recorded, Path(scratch) / f"{i}.mcap")) if record else ((plain, None),)
            for runs, path in kinds:
                with client.recording(path):
                    client.must_reset(task, seed + i)
                    cpu = descendants_cpu_s()
                    result = client.execute(task, max_steps=TASK_STEP_BUDGET)
                    cpu = descendants_cpu_s() - cpu
                runs.append(Run(result.control_steps, result.wall_s, cpu))
    return plain, recorded


def in_process(task: str, episodes: int, seed: int) -> list[Run]:
    agent = make_agent("hierarchical", get_task(task).scene)
    runs = []
    for i in range(episodes):
        started, cpu = time.perf_counter(), time.process_time()
        outcome = agent.run(task, seed + i)
        runs.append(Run(outcome.steps, time.perf_counter() - started, time.process_time() - cpu))
    return runs


def rate(runs: list[Run]) -> float:
    """The median episode's control steps per second."""
    return statistics.median(run.steps / run.wall_s for run in runs if run.wall_s > 0)


def cpu_ms_per_step(runs: list[Run]) -> float:
    """CPU milliseconds per control step over all the episodes."""
    return 1000 * sum(run.cpu_s for run in runs) / max(1, sum(run.steps for run in runs))


def realtime(task: str, seed: int, seconds: float) -> dict[str, float]:
    """Arrival jitter of world states while the graph solves the task at 25 Hz."""
    arrivals: list[tuple[int, float]] = []
    with running_graph(task, seed, mode="realtime", client_name="semgoal_bench") as client:
        client.world_listeners.append(lambda msg: arrivals.append((int(msg.step), time.perf_counter())))
        client.must_reset(task, seed)
        arrivals.clear()
        client.execute(task, timeout=seconds, max_steps=int(seconds * REALTIME_HZ))
        client.spin_until(lambda: bool(arrivals) and arrivals[-1][1] - arrivals[0][1] >= seconds, seconds + 5)
    return arrival_timing(arrivals, REALTIME_HZ)


def arrival_timing(arrivals: list[tuple[int, float]], hz: float) -> dict[str, float]:
    """Rate and lateness of world states arriving as (step, seconds): a step is late when it comes more
    than half a period after its slot, one period after the step before. So a stall counts once, as the
    steps it held up, and the steps after it are on time again; a slow timer shows in the rate."""
    steps = dict(arrivals)  # a repeated step (a heartbeat) keeps its last arrival
    ordered = sorted(steps.items())
    gaps = [later - earlier for (_, earlier), (_, later) in pairwise(ordered)]
    span = ordered[-1][1] - ordered[0][1]
    return {"steps": len(ordered), "rate_hz": (ordered[-1][0] - ordered[0][0]) / span if span else 0.0,
            "late_fraction": sum(gap > 1.5 / hz for gap in gaps) / max(1, len(gaps)),
            "max_gap_ms": 1000 * max(gaps, default=0.0)}


PIXELS = Sight(perception="camera", policy_input="camera")


def from_pixels(task: str, episodes: int, seed: int, truth_rate: float, composed: bool) -> dict:
    """The lockstep episodes again with the planner and the policy on the RGB-D camera, beside ground truth's rate; with
    ``composed``, also with the graph's nodes (perception's among them) in one process."""
    runs, _ = lockstep(task, episodes, seed, PIXELS, record=False)
    result = {"lockstep_pixels_steps_per_s": round(rate(runs), 1), "pixels_over_truth": round(rate(runs) / truth_rate, 3),
              "pixels_steps": [run.steps for run in runs]}
    if composed:
        together, _ = lockstep(task, episodes, seed, PIXELS, record=False, composed=True)
        result.update(lockstep_pixels_composed_steps_per_s=round(rate(together), 1),
                      pixels_composed_over_processes=round(rate(together) / rate(runs), 3))
    return result


def composed_rates(task: str, episodes: int, seed: int, processes: list[Run], local: list[Run]) -> dict:
    """The lockstep episodes again with the graph's nodes in one process, beside four processes and in process; and
    with every message between them through the middleware (``SEMGOAL_IN_PROCESS=0``), what handing them over as
    objects saves."""
    runs, _ = lockstep(task, episodes, seed, record=False, composed=True)
    with _environment(IN_PROCESS_VARIABLE, "0"):
        through, _ = lockstep(task, episodes, seed, record=False, composed=True)
    return {"lockstep_composed_steps_per_s": round(rate(runs), 1),
            "composed_over_in_process": round(rate(runs) / rate(local), 3),
            "composed_over_processes": round(rate(runs) / rate(processes), 3),
            "composed_cpu_ms_per_step": round(cpu_ms_per_step(runs), 2),
            "composed_through_middleware_steps_per_s": round(rate(through), 1),
            "composed_over_through_middleware": round(rate(runs) / rate(through), 3),
            "composed_through_middleware_cpu_ms_per_step": round(cpu_ms_per_step(through), 2)}


@contextlib.contextmanager
def _environment(name: str, value: str) -> Iterator[None]:
    """``name=value`` in this process's environment (so in the processes it starts) meanwhile."""
    before = os.environ.get(name)
    os.environ[name] = value
    try:
        yield
    finally:
        if before is None:
            del os.environ[name]
        else:
            os.environ[name] = before


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="semgoal bench graph", description=__doc__.split("\n\n")[0])
    parser.add_argument("--task", default="MC-2")
    parser.add_argument("--episodes", type=count, default=5)
    parser.add_argument("--seed", type=natural, default=3_000_000)
    parser.add_argument("--realtime-s", type=seconds, default=20.0, help="seconds of realtime running")
    parser.add_argument("--pixels", action="store_true", help="also the lockstep episodes with everything on the camera")
    parser.add_argument("--composed", action="store_true", help="also the lockstep episodes with the four nodes in one "
                        "process (graph_node)")
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args(argv)
    import torch

    torch.set_num_threads(1)
    task = get_task(args.task).name
    graph, recorded = lockstep(task, args.episodes, args.seed)
    local = in_process(task, args.episodes, args.seed)
    result = {"task": task, "episodes": args.episodes,
              "lockstep_graph_steps_per_s": round(rate(graph), 1),
              "in_process_steps_per_s": round(rate(local), 1),
              "graph_over_in_process": round(rate(graph) / rate(local), 3),
              "graph_cpu_ms_per_step": round(cpu_ms_per_step(graph), 2),
              "in_process_cpu_ms_per_step": round(cpu_ms_per_step(local), 2),
              "lockstep_recorded_steps_per_s": round(rate(recorded), 1),
              "recorded_over_unrecorded": round(statistics.median(
                  (run.steps / run.wall_s) / (plain.steps / plain.wall_s)
                  for run, plain in zip(recorded, graph, strict=True)), 3),
              "graph_steps": [run.steps for run in graph], "in_process_steps": [run.steps for run in local],
              **(from_pixels(task, args.episodes, args.seed, rate(graph), args.composed) if args.pixels else {}),
              **(composed_rates(task, args.episodes, args.seed, graph, local) if args.composed else {}),
              "realtime": {k: round(v, 4) for k, v in realtime(task, args.seed, args.realtime_s).items()}}
    print(f"lockstep through the graph: {result['lockstep_graph_steps_per_s']} control steps/s (median of "
          f"{args.episodes}); in one process: {result['in_process_steps_per_s']} steps/s; "
          f"ratio {result['graph_over_in_process']}; recording every topic: {result['lockstep_recorded_steps_per_s']} "
          f"steps/s ({result['recorded_over_unrecorded']} of unrecorded, median over the pairs of one start)")
    print(f"CPU per control step: the graph's processes {result['graph_cpu_ms_per_step']} ms, in one process "
          f"{result['in_process_cpu_ms_per_step']} ms")
    if args.composed:
        print(f"lockstep with the four nodes in one process: {result['lockstep_composed_steps_per_s']} control steps/s, "
              f"{result['composed_over_in_process']} of in process, {result['composed_over_processes']} of four processes, "
              f"{result['composed_cpu_ms_per_step']} ms CPU per step; every message through the middleware: "
              f"{result['composed_through_middleware_steps_per_s']} steps/s, "
              f"{result['composed_through_middleware_cpu_ms_per_step']} ms CPU per step (handed over in the process: "
              f"{result['composed_over_through_middleware']}x)")
    if args.pixels:
        print(f"lockstep from pixels (planner and policy on the camera): {result['lockstep_pixels_steps_per_s']} "
              f"control steps/s, {result['pixels_over_truth']} of ground truth's")
        if args.composed:
            print(f"lockstep from pixels, the nodes in one process: {result['lockstep_pixels_composed_steps_per_s']} "
                  f"control steps/s, {result['pixels_composed_over_processes']} of the separate processes'")
    rt = result["realtime"]
    print(f"realtime at {REALTIME_HZ:.0f} Hz: {rt['steps']} steps at {rt['rate_hz']:.2f} Hz, "
          f"{100 * rt['late_fraction']:.2f} % late (> 1.5 periods after the step before), "
          f"longest gap {rt['max_gap_ms']:.1f} ms")
    if args.json:
        print(json.dumps(result))
    return 0
