"""The `./semgoal` dispatcher: one registry of commands, each living in the package it belongs to (the
benchmarks in ``semgoal_bench``). Experiments and benchmarks are grouped (``semgoal eval goals``, ``semgoal
bench sim``); ``eval`` and ``train`` called with options only run what they once were (``semgoal eval --tasks
all``), and the
flat spellings of earlier releases (``eval-goals``, ``bench-sim``) stay as aliases."""

import importlib
import sys

Entry = tuple[str, str]
"""("module[:function]", help); the function defaults to ``main``."""

COMMANDS: dict[str, Entry | dict[str, Entry]] = {
    # the graph
    "up": ("semgoal_bringup.up", "start sim, predicates, planner and policy and stay up for an operator"),
    "demo": ("semgoal_bringup.demo", "start the node graph and solve a task (make demo)"),
    "run": ("semgoal_bringup.run", "what `ros2 run PKG EXE` does on a native install"),
    "doctor": ("semgoal_bringup.doctor", "versions, workspace state and DDS settings in force"),
    # the operator
    "goal": ("semgoal_planner.operator:goal_main", "send a goal to the planner (ros2 topic pub / action send_goal)"),
    "plan": ("semgoal_planner.operator:plan_main", "show or edit the plan (ros2 service call get_plan / edit_plan)"),
    "parse-goal": ("semgoal_planner.cli:parse_goal_main", "the literals a goal (a sentence, or literals) becomes, or why it is refused"),
    "console": ("semgoal_bringup.tools.console", "the collaboration console: a web page to set goals, edit the plan and do steps"),
    "replay": ("semgoal_bringup.tools.replay", "an episode recorded as MCAP: summary, re-run check (--verify), GIF"),
    "plan-pddl": ("strips_planner.plan_pddl", "plan with our STRIPS planner on any PDDL domain and problem"),
    # the world and the actors
    "expert": ("semgoal_sim.cli:expert_main", "run the scripted expert on a task: success rate, steps"),
    "render": ("semgoal_sim.render", "a PNG of a task's start state (offscreen)"),
    "train": {
        "actor": ("semgoal_bringup.experiments.training:train_main", "train a goal-conditioned SAC+HER actor for a scene and export it"),
        "perception": ("semgoal_bringup.experiments.perception_training", "render labelled camera frames and train the block voter"),
        "dagger": ("semgoal_bringup.experiments.dagger", "fine-tune an actor by DAgger: it drives, the expert labels where it goes"),
    },
    "sweep": ("semgoal_bringup.experiments.sweep", "train a recipe on many seeds, each a job (local or Dask), resumed if it dies"),
    "ablation": ("semgoal_bringup.experiments.ablation", "train the recipe's variants side by side: what expert supervision buys"),
    "model-card": ("semgoal_policy.model_card:main", "write MODEL_CARD.md beside exported actors (from actor.json)"),
    # experiments
    "eval": {
        "tasks": ("semgoal_bringup.experiments.evaluation", "Table 1: task completion of the agents on the eight tasks"),
        "goals": ("semgoal_bringup.experiments.goal_eval", "the hierarchical agent on goal families beyond the benchmark"),
        "subgoals": ("semgoal_bringup.experiments.training:eval_subgoals_main", "success of the shipped actor per sub-goal type"),
        "perception": ("semgoal_bringup.experiments.perception_eval", "the block voter on held-out frames: pose error, literals, latency"),
        "together": ("semgoal_bringup.experiments.together", "the robot and a scripted person on one plan: in turns and at once"),
        "arms": ("semgoal_bringup.experiments.arms", "one arm and two arms across the table on the same starts"),
    },
    "study": {
        "run": ("semgoal_bringup.study.run", "a participant through a study protocol: the graph and the console in study mode"),
        "report": ("semgoal_bringup.study.report", "a study's tables: per participant and across them (CSV, Markdown)"),
    },
    "bench": {
        "sim": ("semgoal_bench.sim", "env steps/s per scene beside FetchPickAndPlace-v4"),
        "planner": ("semgoal_bench.planner", "our planner beside pyperplan (throwaway venv): plan lengths, times"),
        "policy": ("semgoal_bench.policy", "training steps/s and actor latency beside SB3 SAC+HER"),
        "graph": ("semgoal_bench.graph", "control steps/s through the four nodes (lockstep) and 25 Hz jitter"),
        "eval": ("semgoal_bench.eval", "evaluation episodes/s on the local pool and on Dask, 1 and 2 workers"),
    },
}
ALIASES = {"eval-goals": ("eval", "goals"), "eval-subgoals": ("eval", "subgoals"), "eval-perception": ("eval", "perception"),
           "train-perception": ("train", "perception"), "bench-sim": ("bench", "sim"), "bench-planner": ("bench", "planner"),
           "bench-policy": ("bench", "policy"), "bench-graph": ("bench", "graph"), "bench-eval": ("bench", "eval")}
"""The flat spellings of earlier releases."""
DEFAULTS = {"eval": "tasks", "train": "actor"}
"""What a group that was once a command runs when called with options only (``semgoal eval --tasks all``)."""


def usage() -> str:
    """Return the help text listing every command."""
    rows = []
    for name, entry in COMMANDS.items():
        if isinstance(entry, dict):
            rows += [(f"{name} [{sub}]" if DEFAULTS.get(name) == sub else f"{name} {sub}", text) for sub, (_, text) in entry.items()]
        else:
            rows.append((name, entry[1]))
    width = max(len(name) for name, _ in rows)
    lines = ["usage: ./semgoal COMMAND [args...]", "", "commands:"]
    lines += [f"  {name:<{width}}  {text}" for name, text in rows]
    lines += ["", "also: " + ", ".join(f"{old} (= {' '.join(new)})" for old, new in ALIASES.items())]
    return "\n".join(lines)


def resolve(argv: list[str]) -> tuple[Entry, list[str]] | None:
    """The entry ``argv`` names and the arguments it gets; None for an unknown command."""
    command, rest = argv[0], argv[1:]
    if command in ALIASES:
        command, rest = ALIASES[command][0], [ALIASES[command][1], *rest]
    entry = COMMANDS.get(command)
    if not isinstance(entry, dict):
        return (entry, rest) if entry else None
    if rest and rest[0] in entry:
        return entry[rest[0]], rest[1:]
    if command in DEFAULTS and (not rest or rest[0].startswith("-")):
        return entry[DEFAULTS[command]], rest  # options only: what the command once was
    return None


def main(argv: list[str] | None = None) -> int:
    """Dispatch to the named module's ``main(args)``."""
    argv = sys.argv[1:] if argv is None else argv
    if not argv or argv[0] in ("-h", "--help", "help"):
        print(usage())
        return 0
    found = resolve(argv)
    if found is None:
        print(f"semgoal: unknown command {' '.join(argv[:2])!r}\n\n{usage()}", file=sys.stderr)
        return 2
    (target, _), rest = found
    module_name, _, function = target.partition(":")
    entry = getattr(importlib.import_module(module_name), function or "main")
    try:
        return int(entry(rest) or 0)
    except KeyboardInterrupt:  # Ctrl-C: the command cleaned up on its way out; no traceback
        return 130


if __name__ == "__main__":
    sys.exit(main())
