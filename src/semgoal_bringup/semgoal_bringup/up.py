"""`./semgoal up [--task T] [--seed S] [--mode lockstep|realtime]`: start the four nodes and stay up.

The operator then drives it from another shell with the same ROS_DOMAIN_ID: `./semgoal goal DC-3`,
`./semgoal plan show`, `./semgoal plan pause` ... Ctrl-C stops every node.
"""

from __future__ import annotations

import argparse
import os
import time

from semgoal_bringup.graph import start_graph, stop_graph
from semgoal_core.names import Mode


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="semgoal up", description=__doc__.splitlines()[0])
    parser.add_argument("--task", default="DC-3", help="the task whose scene and start the sim loads")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--models", default="", help="folder of exported actors (SCENE/actor.pt); default: the shipped ones")
    parser.add_argument("--mode", choices=list(Mode), default=Mode.REALTIME.value)
    parser.add_argument("--log-level", default="info")
    args = parser.parse_args(argv)
    processes = start_graph(args.task, args.seed, args.mode, args.log_level, models=args.models)
    print(f"[up] {', '.join(processes)} running (ROS_DOMAIN_ID={os.environ.get('ROS_DOMAIN_ID')}); "
          f"send a goal with ./semgoal goal {args.task}; Ctrl-C stops", flush=True)
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
