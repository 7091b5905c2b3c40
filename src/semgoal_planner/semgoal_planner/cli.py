"""Planner subcommands of ./semgoal: `plan-pddl` (any STRIPS domain) and `parse-goal` (a sentence to literals)."""

from __future__ import annotations

import argparse
import sys

from semgoal_planner.heuristics import HEURISTICS
from semgoal_planner.search import SEARCHES


def plan_pddl_main(argv: list[str]) -> int:
    """`./semgoal plan-pddl DOMAIN PROBLEM --search S [--heuristic H]`: exit 0 plan, 1 unsolvable, 2 bad PDDL or
    an unreadable file, 3 valid PDDL outside the supported STRIPS fragment (the message names the construct)."""
    from semgoal_planner.pddl import PddlError, PddlUnsupportedError
    from semgoal_planner.planner import solve_pddl

    parser = argparse.ArgumentParser(prog="semgoal plan-pddl", description=plan_pddl_main.__doc__)
    parser.add_argument("domain")
    parser.add_argument("problem")
    parser.add_argument("--search", choices=list(SEARCHES), default="bfs")
    parser.add_argument("--heuristic", choices=list(HEURISTICS), help="default: blind (bfs), lmcut (astar), hff (gbfs)")
    parser.add_argument("--stats", action="store_true", help="print expanded states and time to stderr")
    args = parser.parse_args(argv)
    try:
        result = solve_pddl(_read(args.domain), _read(args.problem), args.search, args.heuristic)
    except OSError as error:
        print(f"semgoal plan-pddl: {error}", file=sys.stderr)
        return 2
    except PddlUnsupportedError as error:
        print(f"semgoal plan-pddl: unsupported PDDL: {error}", file=sys.stderr)
        return 3
    except PddlError as error:
        print(f"semgoal plan-pddl: bad PDDL: {error}", file=sys.stderr)
        return 2
    if args.stats:
        print(f"expanded {result.stats.expanded}, generated {result.stats.generated}, "
              f"{result.seconds * 1000:.2f} ms", file=sys.stderr)
    if result.plan is None:
        print("unsolvable")
        if result.reason:
            print(result.reason, file=sys.stderr)
        return 1
    for op in result.plan:
        print(op)
    return 0


def _read(path: str) -> str:
    with open(path, encoding="utf-8") as file:
        return file.read()


def parse_goal_main(argv: list[str]) -> int:
    """`./semgoal parse-goal --scene S [--blocks a,b,...] [--json] TEXT...`: the literals each sentence becomes.

    With ``--json``, one object per TEXT, in order: ``{"text": TEXT, "literals": [...]}`` or ``{"text": TEXT,
    "error": "..."}``. Exit 0 when every TEXT parsed, 2 otherwise."""
    import json

    from semgoal_core.vocabulary import SCENES
    from semgoal_planner.english import LanguageError, parse_english

    parser = argparse.ArgumentParser(prog="semgoal parse-goal", description=parse_goal_main.__doc__.splitlines()[0])
    parser.add_argument("--scene", required=True, choices=list(SCENES))
    parser.add_argument("--blocks", help="comma-separated blocks present (default: all of the scene's)")
    parser.add_argument("--json", action="store_true", help="one JSON object per TEXT")
    parser.add_argument("texts", nargs="+", metavar="TEXT")
    args = parser.parse_args(argv)
    blocks = tuple(b.strip().lower() for b in args.blocks.split(",") if b.strip()) if args.blocks else SCENES[args.scene].objects
    unknown = [b for b in blocks if b not in SCENES[args.scene].objects]
    if unknown or not blocks:
        parser.error(f"--blocks: {', '.join(unknown) or 'none'} not in scene {args.scene} "
                     f"({', '.join(SCENES[args.scene].objects)})")
    failed = False
    for text in args.texts:
        try:
            result = {"text": text, "literals": [str(lit) for lit in parse_english(text, args.scene, blocks)]}
        except LanguageError as error:
            result, failed = {"text": text, "error": str(error)}, True
        if args.json:
            print(json.dumps(result))
        else:
            print(f"{text!r}: {' & '.join(result['literals']) if 'literals' in result else 'refused: ' + result['error']}")
    return 2 if failed else 0


if __name__ == "__main__":  # ./semgoal plan-pddl starts here, without ROS (see ./semgoal)
    sys.exit(plan_pddl_main(sys.argv[1:]))
