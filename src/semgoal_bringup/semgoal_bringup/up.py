"""`./semgoal up [--task T] [--scene S] [--seed S] [--mode realtime|lockstep] [--models DIR] [--rviz true]
[--record FILE] [--foxglove [PORT]] [--console [PORT]] [--state-dir DIR] [--robots 2]`: start
the four nodes and stay up; the options are the launch file's arguments (``ros2 launch semgoal_bringup
semgoal.launch.py``), read from the same definition.

The operator then drives it from another shell with the same ROS_DOMAIN_ID: `./semgoal goal DC-3`,
`./semgoal plan show`, `./semgoal plan pause` ... A node that dies is started again (after 1, 2, 4 ... s;
at most 5 times a minute) while the others run on; Ctrl-C (or SIGTERM) stops every node.
"""

from __future__ import annotations

import argparse
import os
import shutil
import signal
import subprocess
import time

from semgoal_bringup.graph import (
    LAUNCH_ARGUMENTS,
    Sight,
    graph_commands,
    graph_nodes,
    policy_model_dir,
    run_state_dir,
    rviz_config,
    scene_task,
    stop_graph,
)
from semgoal_core.names import Mode
from semgoal_core.tasks import Task
from semgoal_policy.expert_actor import EXPERT

DEFAULT_PORTS = {"foxglove": 8765, "console": 8080}
"""The Foxglove app's default port; the console's."""
MAX_RESTARTS = 5
RESTART_WINDOW_S = 60.0


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="semgoal up", description=__doc__.split("\n\n")[0])
    for name, default, text in LAUNCH_ARGUMENTS:
        flags = dict.fromkeys((f"--{name.replace('_', '-')}", f"--{name}"))  # --policy-input, and the launch file's spelling
        if name in DEFAULT_PORTS:  # `--foxglove` / `--console` alone: the default port
            parser.add_argument(*flags, dest=name, default=default, nargs="?", const=str(DEFAULT_PORTS[name]), help=text)
        else:
            parser.add_argument(*flags, dest=name, default=default, help=text)
    parser.add_argument("--log-level", default="info")
    args = parser.parse_args(argv)
    if args.mode not in list(Mode):
        parser.error(f"--mode must be one of {', '.join(Mode)}, got {args.mode!r}")
    if not args.seed.isdigit():
        parser.error(f"--seed must be a task seed (0 or more), got {args.seed!r}")
    try:
        task = scene_task(args.scene, args.task)
    except (KeyError, ValueError) as error:
        parser.error(str(error.args[0]))
    rviz = args.rviz.lower() in ("true", "1", "yes")
    if rviz and shutil.which("rviz2") is None:
        parser.error("--rviz needs rviz2 on the PATH (a native ROS 2 install or the Docker image)")
    state_dir, remove_state_dir = run_state_dir(args.state_dir)
    print(f"[up] the planner's journal: {state_dir}" + ("" if args.state_dir else " (removed when the graph stops)"),
          flush=True)
    try:
        if not args.robots.isdigit():
            raise ValueError(f"--robots must be 1 or 2, got {args.robots!r}")
        nodes = graph_nodes(task.name, int(args.seed), args.mode, args.models, args.record, args.foxglove, args.console,
                            state_dir, Sight(args.perception, args.policy_input), int(args.robots))
    except ValueError as error:
        remove_state_dir()
        parser.error(str(error))
    signal.signal(signal.SIGTERM, _interrupt)  # `kill` stops the nodes too, as Ctrl-C does
    try:
        return run_graph(task, nodes, args, rviz)
    finally:
        remove_state_dir()


def _interrupt(signum: int, frame: object) -> None:
    raise KeyboardInterrupt


def run_graph(task: Task, nodes: list, args: argparse.Namespace, rviz: bool) -> int:
    """Starts ``nodes`` and keeps them up (a node that dies is started again) until Ctrl-C or one keeps dying."""
    if policy_model_dir(task.scene, args.models) == EXPERT:
        print(f"[up] {task.scene} has no trained actor here: the scripted expert drives the arm", flush=True)
    commands = graph_commands(nodes, args.composed.lower() in ("true", "1", "yes"), args.log_level)
    processes = {name: start_process(name, command) for name, command in commands.items()}
    if rviz:
        processes["rviz2"] = subprocess.Popen(["rviz2", "-d", str(rviz_config())])
    print(f"[up] {', '.join(processes)} running (ROS_DOMAIN_ID={os.environ.get('ROS_DOMAIN_ID')}); "
          f"send a goal with ./semgoal goal {task.name}; Ctrl-C stops", flush=True)
    restarts = {name: Restarts() for name in processes}
    try:
        while True:
            time.sleep(0.2)
            for name, command in commands.items():
                process = processes[name]
                if process.poll() is None:
                    continue
                delay = restarts[name].next_delay()
                if delay is None:
                    print(f"[up] {name} keeps dying ({MAX_RESTARTS} restarts within {RESTART_WINDOW_S:.0f} s); "
                          "stopping the graph", flush=True)
                    return 1
                print(f"[up] {name} exited with {process.returncode}; restarting it in {delay:.0f} s", flush=True)
                time.sleep(delay)
                processes[name] = start_process(name, command)
    except KeyboardInterrupt:
        return 0
    finally:
        stop_graph(processes)


def start_process(name: str, command: list[str]) -> subprocess.Popen:
    process = subprocess.Popen(command)
    print(f"[up] started {name} (pid {process.pid})", flush=True)
    return process


class Restarts:
    """Back-off for a node that dies: 1, 2, 4 ... s, and no more than :data:`MAX_RESTARTS` within
    :data:`RESTART_WINDOW_S` (then something is wrong that restarting will not fix)."""

    def __init__(self) -> None:
        self.times: list[float] = []

    def next_delay(self) -> float | None:
        now = time.monotonic()
        self.times = [t for t in self.times if now - t < RESTART_WINDOW_S]
        if len(self.times) >= MAX_RESTARTS:
            return None
        self.times.append(now)
        return float(2 ** (len(self.times) - 1))
