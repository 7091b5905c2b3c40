"""`./semgoal parse-goal`: a plain-English goal to the scene's literals (`plan-pddl` lives in plan_pddl.py)."""

from __future__ import annotations

import argparse


def parse_goal_main(argv: list[str]) -> int:
    """`./semgoal parse-goal --scene S [--blocks a,b,...] [--json] TEXT...`: the literals each sentence becomes (or
    literals joined by '&', checked as the planner checks them; a task is named).

    With ``--json``, one object per TEXT, in order: ``{"text": TEXT, "literals": [...]}``, ``{"text": TEXT, "task":
    NAME}`` or ``{"text": TEXT, "error": "..."}``. Exit 0 when every TEXT parsed, 2 otherwise."""
    import json

    from semgoal_core.tasks import goal_form
    from semgoal_core.vocabulary import SCENES
    from semgoal_planner.english import PLACED_WHEN_PLANNED, LanguageError, parse_english
    from semgoal_planner.goals import GoalError, read_goal

    parser = argparse.ArgumentParser(prog="semgoal parse-goal", description=parse_goal_main.__doc__.split("\n\n")[0])
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
            if goal_form(text) == "text":
                result = {"text": text, "literals": [str(lit) for lit in parse_english(text, args.scene, blocks)]}
            else:
                goal = read_goal(text, args.scene, blocks)
                result = {"text": text, **({"task": goal.task} if goal.task else
                                           {"literals": [str(lit) for lit in goal.literals]})}
        except (LanguageError, GoalError) as error:
            result, failed = {"text": text, "error": str(error)}, True
        if args.json:
            print(json.dumps(result))
            continue
        read = (" & ".join(result["literals"]) if "literals" in result else
                f"task {result['task']} (its literals come from the world when it is planned)" if "task" in result else
                "refused: " + result["error"])
        print(f"{text!r}: {read}")
        said = " ".join(result.get("literals", []))
        for stand_in, meaning in PLACED_WHEN_PLANNED.items():
            if stand_in in said:
                print(f"    {stand_in}: {meaning}")
    return 2 if failed else 0

