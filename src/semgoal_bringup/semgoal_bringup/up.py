"""`./semgoal up [--task T] [--scene S] [--seed S] [--mode realtime|lockstep] [--models DIR] [--rviz true]
[--record FILE]`: start
the four nodes and stay up; the options are the launch file's arguments (``ros2 launch semgoal_bringup
semgoal.launch.py``), read from the same definition.

The operator then drives it from another shell with the same ROS_DOMAIN_ID: `./semgoal goal DC-3`,
`./semgoal plan show`, `./semgoal plan pause` ... Ctrl-C stops every node.
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import time

from semgoal_bringup.graph import LAUNCH_ARGUMENTS, rviz_config, scene_task, start_graph, stop_graph
from semgoal_core.names import Mode


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="semgoal up", description=__doc__.splitlines()[0])
    for name, default, text in LAUNCH_ARGUMENTS:
        parser.add_argument(f"--{name}", default=default, help=text)
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
    processes = start_graph(task.name, int(args.seed), args.mode, args.log_level, models=args.models, record=args.record)
    if rviz:
        processes["rviz2"] = subprocess.Popen(["rviz2", "-d", str(rviz_config())])
    print(f"[up] {', '.join(processes)} running (ROS_DOMAIN_ID={os.environ.get('ROS_DOMAIN_ID')}); "
          f"send a goal with ./semgoal goal {task.name}; Ctrl-C stops", flush=True)
    try:
        while all(p.poll() is None for p in processes.values()):
            time.sleep(0.5)
        dead = [name for name, p in processes.items() if p.poll() is not None]
        print(f"[up] {', '.join(dead)} exited; stopping the rest")
        return 1
    except KeyboardInterrupt:
        return 0
    finally:
        stop_graph(processes)
