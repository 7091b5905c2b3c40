"""`ros2 run semgoal_bringup graph_node [--nodes sim_node,...,robot2/policy_node] [--param NS/EXE:KEY:=VALUE]
--ros-args ...`: the graph's nodes in one process, spun by one executor (:func:`semgoal_ros.interfaces.run_nodes`; the
ROS 2 composition idea, for rclpy). Each is still a node of its own, with its own name (under a namespace where its
entry names one, as the second arm's policy node runs in /robot2), parameters (the params file's section of its name,
then ``-p NAME:KEY:=VALUE``, or ``--param NS/EXE:KEY:=VALUE`` for a node under a namespace: ROS's ``-p`` names a node
by its name alone, which /policy and /robot2/policy share) and topics, and the graph behaves as the separate processes
do; it only spends less CPU on the way between them, its nodes' messages to
each other handed over as objects where no one else listens (:mod:`semgoal_ros.in_process`). The separate processes
stay the default (``ros2 run`` each, ``./semgoal up``); ``bench graph --composed`` measures both. rclpy's
EventsExecutor (experimental in Jazzy) left ``reset_world`` unanswered here, so it is not offered."""

from __future__ import annotations

import argparse
import functools
import importlib
import sys
from collections.abc import Callable
from typing import Any

import yaml

from semgoal_core.arguments import names

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


def split_entry(entry: str) -> tuple[str, str]:
    """``robot2/policy_node`` -> (``/robot2``, ``policy_node``); a plain executable has the root namespace, ``""``."""
    namespace, _, executable = entry.strip().rpartition("/")
    return (f"/{namespace.strip('/')}" if namespace else ""), executable


def parameter_overrides(settings: list[str], entries: list[str]) -> dict[str, list]:
    """Each ``NS/EXE:KEY:=VALUE`` of ``settings`` as an rclpy ``Parameter`` of its entry, the value read as ``-p``
    reads one (YAML; an empty value is an empty string). ValueError for a setting of no entry or not so written."""
    from rclpy.parameter import Parameter

    overrides: dict[str, list] = {entry: [] for entry in entries}
    for setting in settings:
        target, separator, value = setting.partition(":=")
        entry, _, key = target.rpartition(":")
        if not separator or not key or entry not in overrides:
            raise ValueError(f"--param {setting!r}: write NS/EXE:KEY:=VALUE for a node of --nodes "
                             f"({', '.join(entries)})")
        loaded = yaml.safe_load(value) if value else ""
        overrides[entry].append(Parameter(key, value="" if loaded is None else loaded))
    return overrides


def node_factories(entries: list[str], settings: list[str]) -> list[Callable[[], Any]]:
    """A factory per entry of ``--nodes``: its node class under the entry's namespace, with its ``--param`` values."""
    overrides = parameter_overrides(settings, entries)
    factories = []
    for entry in entries:
        namespace, executable = split_entry(entry)
        options = {"namespace": namespace} if namespace else {}
        if overrides[entry]:
            options["parameter_overrides"] = overrides[entry]
        factories.append(functools.partial(node_class(executable), **options))
    return factories


def main(argv: list[str] | None = None) -> None:
    from semgoal_ros.interfaces import run_nodes

    argv = sys.argv[1:] if argv is None else argv
    split = argv.index("--ros-args") if "--ros-args" in argv else len(argv)
    parser = argparse.ArgumentParser(prog="graph_node", description=__doc__.split("\n\n")[0])
    parser.add_argument("--nodes", type=names, default=",".join(DEFAULT_NODES),
                        help=f"of {', '.join(NODE_CLASSES)}, each under a namespace if written NS/EXE")
    parser.add_argument("--param", action="append", default=[], metavar="NS/EXE:KEY:=VALUE",
                        help="a value of a node under a namespace (repeat for more)")
    args = parser.parse_args(argv[:split])
    entries = args.nodes
    if unknown := [name for name in entries if split_entry(name)[1] not in NODE_CLASSES]:
        parser.error(f"unknown node(s) {', '.join(unknown)}: of {', '.join(NODE_CLASSES)}")
    try:
        factories = node_factories(entries, args.param)
    except ValueError as error:
        parser.error(str(error))
    run_nodes(factories, ["graph_node", *argv[split:]])


if __name__ == "__main__":
    main()
