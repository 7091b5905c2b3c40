"""`ros2 run semgoal_bringup graph_node [--nodes sim_node,...] --ros-args ...`: the graph's nodes in one process,
spun by one executor (:func:`semgoal_ros.interfaces.run_nodes`; the ROS 2 composition idea, for rclpy). Each is
still a node of its own, with its own name, parameters (the params file's section of its name) and topics, and the
graph behaves as the separate processes do; it only spends less CPU on the way between them, its nodes' messages to
each other handed over as objects where no one else listens (:mod:`semgoal_ros.in_process`). The separate processes
stay the default (``ros2 run`` each, ``./semgoal up``); ``bench graph --composed`` measures both. rclpy's
EventsExecutor (experimental in Jazzy) left ``reset_world`` unanswered here, so it is not offered."""

from __future__ import annotations

import argparse
import importlib
import sys

NODE_CLASSES = {
    "sim_node": "semgoal_sim.sim_node:SimNode",
    "predicate_node": "semgoal_sim.predicate_node:PredicateNode",
    "perception_node": "semgoal_perception.perception_node:PerceptionNode",
    "planner_node": "semgoal_planner.planner_node:PlannerNode",
    "policy_node": "semgoal_policy.policy_node:PolicyNode",
}
"""Each executable of the graph and the node class it runs."""
NODE_NAMES = {"sim_node": "sim", "predicate_node": "predicates", "perception_node": "perception",
              "planner_node": "planner", "policy_node": "policy"}
"""Each executable's node name: its section of a params file."""
DEFAULT_NODES = ("sim_node", "predicate_node", "planner_node", "policy_node")


def node_class(executable: str) -> type:
    module, name = NODE_CLASSES[executable].split(":")
    return getattr(importlib.import_module(module), name)


def main(argv: list[str] | None = None) -> None:
    from semgoal_ros.interfaces import run_nodes

    argv = sys.argv[1:] if argv is None else argv
    split = argv.index("--ros-args") if "--ros-args" in argv else len(argv)
    parser = argparse.ArgumentParser(prog="graph_node", description=__doc__.split("\n\n")[0])
    parser.add_argument("--nodes", default=",".join(DEFAULT_NODES), help=f"of {', '.join(NODE_CLASSES)}")
    args = parser.parse_args(argv[:split])
    executables = [name.strip() for name in args.nodes.split(",") if name.strip()]
    if unknown := [name for name in executables if name not in NODE_CLASSES]:
        parser.error(f"unknown node(s) {', '.join(unknown)}: of {', '.join(NODE_CLASSES)}")
    run_nodes([node_class(name) for name in executables], ["graph_node", *argv[split:]])


if __name__ == "__main__":
    main()
