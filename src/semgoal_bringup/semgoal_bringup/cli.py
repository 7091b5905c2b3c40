"""The `./semgoal` dispatcher: one registry of subcommands, each living in the package it belongs to; the
benchmarks live outside the product, in the checkout's ``bench/``."""

import importlib
import os
import sys
from pathlib import Path

COMMANDS: dict[str, tuple[str, str]] = {  # name: ("module[:function]", help); function defaults to main
    "run": ("semgoal_bringup.run", "what `ros2 run PKG EXE` does on a native install"),
    "doctor": ("semgoal_bringup.doctor", "versions, workspace state and DDS settings in force"),
    "demo": ("semgoal_bringup.demo", "start the node graph and solve a task (make demo)"),
    "replay": ("semgoal_bringup.replay", "an episode recorded as MCAP: summary, re-run check (--verify), GIF"),
    "console": ("semgoal_bringup.console", "the collaboration console: a web page to set goals, edit the plan and do steps"),
    "up": ("semgoal_bringup.up", "start sim, predicates, planner and policy and stay up for an operator"),
    "expert": ("semgoal_sim.cli:expert_main", "run the scripted expert on a task: success rate, steps"),
    "render": ("semgoal_sim.render", "a PNG of a task's start state (offscreen)"),
    "bench-sim": ("bench.sim", "env steps/s per scene beside FetchPickAndPlace-v4"),
    "parse-goal": ("semgoal_planner.cli:parse_goal_main", "the literals a plain-English goal becomes (or why not)"),
    "plan-pddl": ("strips_planner.plan_pddl", "plan with our STRIPS planner on any PDDL domain and problem"),
    "goal": ("semgoal_planner.operator:goal_main", "send a goal to the planner (ros2 topic pub / action send_goal)"),
    "plan": ("semgoal_planner.operator:plan_main", "show or edit the plan (ros2 service call get_plan / edit_plan)"),
    "bench-planner": ("bench.planner", "our planner beside pyperplan (throwaway venv): plan lengths, times"),
    "train": ("semgoal_bringup.training:train_main", "train a goal-conditioned SAC+HER actor for a scene and export it"),
    "sweep": ("semgoal_bringup.sweep", "train a recipe on many seeds, each a job (local or Dask), resumed if it dies"),
    "model-card": ("semgoal_policy.model_card:main", "write MODEL_CARD.md beside exported actors (from actor.json)"),
    "eval": ("semgoal_bringup.evaluation", "Table 1: task completion of the agents on the eight tasks"),
    "bench-graph": ("bench.graph", "control steps/s through the four nodes (lockstep) and 25 Hz jitter"),
    "ablation": ("semgoal_bringup.ablation", "train the recipe's variants side by side: what expert supervision buys"),
    "bench-policy": ("bench.policy", "training steps/s and actor latency beside SB3 SAC+HER"),
    "bench-eval": ("bench.eval", "evaluation episodes/s on the local pool and on Dask, 1 and 2 workers"),
    "eval-goals": ("semgoal_bringup.goal_eval", "the hierarchical agent on goal families beyond the benchmark"),
    "train-perception": ("semgoal_bringup.perception_training", "render labelled camera frames and train the block voter"),
    "eval-perception": ("semgoal_bringup.perception_eval", "the block voter on held-out frames: pose error, literal agreement, latency"),
    "eval-subgoals": ("semgoal_bringup.training:eval_subgoals_main", "success of the shipped actor per sub-goal type"),
}


def usage() -> str:
    """Return the help text listing every subcommand."""
    width = max(map(len, COMMANDS))
    lines = ["usage: ./semgoal COMMAND [args...]", "", "commands:"]
    lines += [f"  {name:<{width}}  {text}" for name, (_, text) in COMMANDS.items()]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    """Dispatch ``argv[0]`` to its module's ``main(argv[1:])``."""
    argv = sys.argv[1:] if argv is None else argv
    if not argv or argv[0] in ("-h", "--help", "help"):
        print(usage())
        return 0
    command, rest = argv[0], argv[1:]
    if command not in COMMANDS:
        print(f"semgoal: unknown command {command!r}\n\n{usage()}", file=sys.stderr)
        return 2
    module_name, _, function = COMMANDS[command][0].partition(":")
    if module_name.startswith("bench."):
        sys.path.insert(0, os.environ.get("SEMGOAL_ROOT") or str(Path.cwd()))
    entry = getattr(importlib.import_module(module_name), function or "main")
    try:
        return int(entry(rest) or 0)
    except KeyboardInterrupt:  # Ctrl-C: the command cleaned up on its way out; no traceback
        return 130


if __name__ == "__main__":
    sys.exit(main())
