"""The four nodes as separate processes: what a launch file would start (launch is not on PyPI)."""

from __future__ import annotations

import os
import subprocess
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from semgoal_sim.tasks import get_task

NODES = (("semgoal_sim", "sim_node"), ("semgoal_sim", "predicate_node"),
         ("semgoal_planner", "planner_node"), ("semgoal_policy", "policy_node"))


def node_params(task_name: str, seed: int, mode: str, models: str = "") -> dict[str, dict[str, object]]:
    """Parameters per executable for a task's scene (the YAML a launch file would pass)."""
    task = get_task(task_name)
    return {
        "sim_node": {"scene": task.scene, "task": task.name, "seed": seed, "mode": mode},
        "predicate_node": {},
        "planner_node": {"scene": task.scene},
        "policy_node": {"scene": task.scene, "mode": mode, **({"model_dir": f"{models}/{task.scene}"} if models else {})},
    }


def start_graph(task_name: str, seed: int, mode: str = "lockstep", log_level: str = "warn",
                skip: tuple[str, ...] = (), models: str = "") -> dict[str, subprocess.Popen]:
    """Start the nodes (all but ``skip``); ``models``: a folder of exported actors instead of the shipped ones."""
    root = Path(os.environ["SEMGOAL_ROOT"])
    processes = {}
    for package, executable in NODES:
        if executable in skip:
            continue
        args = [str(root / "semgoal"), "run", package, executable, "--ros-args", "--log-level", log_level]
        for key, value in node_params(task_name, seed, mode, models)[executable].items():
            args += ["-p", f"{key}:={value}"]
        processes[executable] = subprocess.Popen(args)
    return processes


def stop_graph(processes: dict[str, subprocess.Popen]) -> None:
    for process in processes.values():
        process.terminate()
    for process in processes.values():
        try:
            process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            process.kill()


@contextmanager
def running_graph(task_name: str, seed: int, mode: str = "lockstep", client_name: str = "semgoal_operator",
                  models: str = "") -> Iterator:
    """The four nodes and a :class:`GraphClient` on the current ROS domain, ready; all stopped on exit.
    RuntimeError when the nodes do not come up."""
    from semgoal_bringup.graph_client import GraphClient

    processes = start_graph(task_name, seed, mode=mode, models=models)
    client = None
    try:
        client = GraphClient(client_name)
        if not client.wait_ready():
            raise RuntimeError(f"the node graph for {task_name} did not come up")
        yield client
    finally:
        if client is not None:
            client.close()
        stop_graph(processes)
