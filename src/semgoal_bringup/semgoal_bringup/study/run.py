"""`./semgoal study run PROTOCOL.yaml|NAME --participant P [--out DIR] [--port PORT] [--token T] [--row K]`: start the
graph in realtime on the protocol's first world and the console in study mode for participant P, and print the URL
to open; the page walks them through the conditions in their order. Ctrl-C stops it all; run it again with the
same ID to carry on where the session stopped. ``./semgoal study report DIR`` makes the tables."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from semgoal_bringup.graph import graph_commands, graph_nodes, stop_graph
from semgoal_bringup.study.protocol import ProtocolError, check_participant, load_protocol
from semgoal_core.arguments import count, natural
from semgoal_core.names import Mode
from semgoal_core.tasks import get_task
from semgoal_ros.package_data import share_path


def main(argv: list[str]) -> int:
    from semgoal_bringup.tools import console
    from semgoal_bringup.up import start_process

    parser = argparse.ArgumentParser(prog="semgoal study run", description=__doc__.split("\n\n")[0])
    parser.add_argument("protocol", type=Path, help="a protocol (YAML), or the name of a shipped one: "
                        "desk-together")
    parser.add_argument("--participant", required=True)
    parser.add_argument("--out", type=Path, default=Path("study-results"))
    parser.add_argument("--port", type=count, default=8080)
    parser.add_argument("--token", default="")
    parser.add_argument("--row", type=natural, help="the Latin square's row (default: from the participant's ID)")
    args = parser.parse_args(argv)
    if not args.protocol.exists() and args.protocol.suffix == "":  # a shipped protocol, by name
        args.protocol = share_path("semgoal_bringup", "study", f"{args.protocol}.yaml")
    try:
        protocol, participant = load_protocol(args.protocol), check_participant(args.participant)
    except ProtocolError as error:
        parser.error(str(error))
    first = protocol.conditions[0].episodes[0]
    nodes = graph_nodes(get_task(first.world).name, first.seed, Mode.REALTIME)
    processes = {name: start_process(name, command) for name, command in graph_commands(nodes, log_level="info").items()}
    try:
        return console.main(["--study", str(args.protocol), "--participant", participant, "--out", str(args.out),
                             "--port", str(args.port), *(["--token", args.token] if args.token else []),
                             *(["--row", str(args.row)] if args.row is not None else [])])
    finally:
        stop_graph(processes)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
