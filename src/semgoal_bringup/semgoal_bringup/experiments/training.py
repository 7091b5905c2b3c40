"""Training and sub-goal evaluation, where the policy's learning meets the simulator's envs: `./semgoal train`
and `./semgoal eval-subgoals`. The policy package knows agents, recipes and the trainer; which env each
agent trains in is chosen here (:func:`make_env`), so that the policy imports no simulator."""

from __future__ import annotations

import argparse
import json
import shlex
import sys
from functools import partial
from pathlib import Path

from semgoal_core.arguments import count, names, natural
from semgoal_core.vocabulary import SCENES, BinGeometry


def make_env(agent: str, scene: str, derived: tuple[str, ...] = (), spawn_margin: float = 0.0,
             missed_put_share: float = 0.0, tower_share: float | None = None, max_blocks: int | None = None,
             sleep: bool = True, shown_bin: BinGeometry | None = None):
    """The env ``agent`` learns in: sub-goal episodes for the hierarchy (their blocks at rest sleeping unless
    ``sleep`` is False; ``shown_bin``: :class:`~semgoal_sim.env.SubgoalEnv`'s), whole tasks for the flat baselines (semantic
    goals, or block positions for flat-continuous)."""
    from semgoal_policy.agents import get_agent
    from semgoal_sim.env import SubgoalEnv
    from semgoal_sim.task_env import TaskEnv

    spec = get_agent(agent)
    if spec.subgoals:
        return SubgoalEnv(scene, derived=derived, spawn_margin=spawn_margin, missed_put_share=missed_put_share,
                          tower_share=tower_share, max_blocks=max_blocks, sleep=sleep, shown_bin=shown_bin)
    if derived:
        raise ValueError(f"derived features ({', '.join(derived)}) are for the hierarchical agent only")
    if spawn_margin or missed_put_share or tower_share is not None or max_blocks is not None or not sleep or shown_bin:
        raise ValueError("a spawn margin, missed puts, a tower share, a block limit and blocks kept awake are for the "
                         "hierarchical agent only (task starts are the paper's)")
    return TaskEnv(scene, spec.goal)


def checkout_models_dir() -> Path:
    """Where `train --ship` writes: the checkout's ``src/semgoal_policy/models`` (``make setup`` installs it)."""
    from semgoal_policy.trainer import PROJECT_ROOT

    return PROJECT_ROOT / "src" / "semgoal_policy" / "models"


def trainer_for(config):
    """A :class:`~semgoal_policy.trainer.Trainer` on the envs of the configuration's agent and scene."""
    from semgoal_policy.trainer import Trainer

    return Trainer(config, partial(make_env, config.agent, config.scene, tuple(config.derived_features),
                                   config.spawn_margin, config.missed_put_share, config.tower_share, config.max_blocks))


def train_main(argv: list[str]) -> int:
    """`./semgoal train --recipe NAME --seed S [--resume] [--ship] [settings]` (or --scene S instead of a recipe):
    train a goal-conditioned SAC+HER actor and export it to its run's folder (with --ship, over the shipped actor)."""
    config, args = train_config(argv)
    try:
        trainer = trainer_for(config)
        final = trainer.run(resume=args.resume)
    except (FileExistsError, ValueError) as error:
        print(f"semgoal train: {error}", file=sys.stderr)
        return 2
    print(json.dumps({"scene": config.scene, "agent": config.agent, "env_steps": trainer.env_steps,
                      "wall_s": round(trainer.wall_s, 1), "per_kind": final, "export": str(trainer.export_dir)}))
    return 0


def train_config(argv: list[str]):
    """The training configuration ``./semgoal train argv`` asks for (defaults, then the recipe, then the
    flags), and the parsed arguments; exits 2 with the reason on a bad recipe or setting."""
    from semgoal_policy.agents import AGENTS
    from semgoal_policy.recipes import RecipeError, add_config_flags, build_config, flag_overrides, load_recipe, recipe_names
    from semgoal_policy.sac import bf16_is_native

    parser = argparse.ArgumentParser(prog="semgoal train", description=train_main.__doc__)
    parser.add_argument("--recipe", help=f"the settings of a shipped run: {', '.join(recipe_names())}, or a .yaml path")
    parser.add_argument("--resume", action="store_true", help="continue the run's last checkpoint")
    parser.add_argument("--ship", action="store_true", help="export over the shipped actor in models/ (else the run's export/)")
    add_config_flags(parser)
    args = parser.parse_args(argv)
    try:
        recipe = load_recipe(args.recipe) if args.recipe else {}
    except RecipeError as error:
        parser.error(str(error))
    overrides = flag_overrides(args)
    if "scene" in recipe and overrides.get("scene", recipe["scene"]) != recipe["scene"]:
        parser.error(f"recipe {args.recipe} is for scene {recipe['scene']}, not {overrides['scene']}")
    if "scene" not in recipe and "scene" not in overrides:
        parser.error("give a --recipe or a --scene")
    try:
        config = build_config(recipe, overrides)
    except (TypeError, ValueError) as error:
        parser.error(str(error))
    if config.scene not in SCENES or config.agent not in AGENTS:
        parser.error(f"scenes are {', '.join(SCENES)} and agents {', '.join(AGENTS)}; got {config.scene}, {config.agent}")
    if config.sac.precision == "bf16" and not bf16_is_native():
        print("semgoal train: warning: this CPU has no bfloat16 in hardware; precision bf16 runs a dozen times slower "
              "than fp32 here (semgoal bench policy)", file=sys.stderr)
    if args.ship:
        if config.export_dir is not None:
            parser.error("--ship exports to models/: leave out --export-dir")
        config.export_dir = checkout_models_dir() / AGENTS[config.agent].model_name(config.scene)
    config.command = shlex.join(["./semgoal", "train", *argv])
    return config, args


def eval_subgoals_main(argv: list[str]) -> int:
    """`./semgoal eval-subgoals --scene S --episodes N --seed S --json`: the shipped actor per sub-goal type."""
    from semgoal_core import features, layout
    from semgoal_core.settling import SETTLE_STEPS
    from semgoal_policy.actor import derived_features, load, models_dir
    from semgoal_policy.agents import get_agent
    from semgoal_policy.controller import ACTION_MODES, SubgoalController
    from semgoal_policy.evaluate import KIND_SEED_STRIDE, success_by_kind
    from semgoal_sim.env import EPISODE_STEPS

    parser = argparse.ArgumentParser(prog="semgoal eval subgoals", description=eval_subgoals_main.__doc__)
    parser.add_argument("--scene", required=True, choices=list(SCENES))
    parser.add_argument("--episodes", type=count, default=200, help="episodes per sub-goal type")
    parser.add_argument("--seed", type=natural, default=2_000_000, help="first episode seed (training uses seeds < 1e6)")
    parser.add_argument("--horizon", type=count, default=EPISODE_STEPS,
                        help=f"control steps per episode (default {EPISODE_STEPS}, the training horizon; the planner "
                             "grants a step stall_steps, 150, before it re-plans)")
    parser.add_argument("--action-mode", choices=ACTION_MODES, default="mean",
                        help="mean: the deterministic actor (default); sample: its Gaussian, seeded by --seed and the "
                             "sub-goal type, as policy_node runs it (action_mode: sample)")
    parser.add_argument("--model-dir", type=Path, help="exported actor (default: the shipped one, share/semgoal_policy/models/SCENE)")
    parser.add_argument("--envs", type=count, default=10)
    parser.add_argument("--shields", action="store_true",
                        help="the policy node's rules on top of the actor, as the graph runs it (no held block let go off "
                             "the table's edge or over the bin's wall, a block put on another let go centred, the hand "
                             "lifted off a tower's top, the palm and a held block kept off stacks, a block on a stack grasped at its "
                             "middle, fingers opening no further than a block beside them leaves room, a block put near "
                             "others let go only with the hand slow and within the expert's reach of them); default: the actor alone")
    parser.add_argument("--types", type=names, metavar="TYPE[,TYPE...]",
                        help="only these sub-goal types (default: every type of the scene), each from the same starts "
                             "and with the same sampled noise as in the whole evaluation")
    parser.add_argument("--misses", action="store_true",
                        help="also list every missed episode: its seed, sub-goal and why it is not achieved at rest at the end")
    parser.add_argument("--awake", action="store_true",
                        help="blocks never sleep (MuJoCo's sleeping islands off, as the actors were trained)")
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args(argv)
    spec = get_agent("hierarchical")
    kinds = spec.evaluated_kinds(args.scene)
    chosen = args.types or kinds
    unknown = [kind for kind in chosen if kind not in kinds]
    if unknown:
        parser.error(f"argument --types: {', '.join(unknown)}: not a sub-goal type of {args.scene} "
                     f"(it has {', '.join(kinds)})")
    import numpy as np
    import torch

    torch.set_num_threads(1)
    try:
        actor, meta = load(args.model_dir or models_dir() / args.scene, args.scene)
    except (FileNotFoundError, ValueError) as error:  # no actor there, or one of another scene
        parser.error(str(error))
    shown_bin = features.shown_bin(args.scene, meta["layout"]["scene"])
    envs = [make_env("hierarchical", args.scene, derived_features(meta), sleep=not args.awake, shown_bin=shown_bin)
            for _ in range(args.envs)]
    for env in envs:
        env.max_steps = args.horizon

    observation_size = layout.observation_size(args.scene)

    controller = SubgoalController(args.scene, args.model_dir) if args.shields else None  # rules hold no state of
    # their own beyond the sub-goal, so one controller serves every env, set to each env's sub-goal in turn

    def act(obs: np.ndarray, goal: np.ndarray) -> np.ndarray:
        """The actor's mean, or a sample of its Gaussian as the policy node draws it; with ``--shields``, the policy
        node's rules for each env's sub-goal on top."""
        actions = actor.act(obs, goal, noise.standard_normal((len(obs), 4)) if args.action_mode == "sample" else None)
        if controller is not None:
            for env, observation, action in zip(envs, obs, actions, strict=False):
                controller.set_subgoal(env.subgoal.literals())
                action[:] = controller.ruled(observation[:observation_size], action)
        return actions

    misses: list[dict] = []

    def record(kind: str, seed: int, env) -> None:
        why = env.shortfall() or [f"achieved at rest at the end, for fewer than the {SETTLE_STEPS} steps that confirm it"]
        misses.append({"kind": kind, "seed": seed, "subgoal": str(env.subgoal), "why": why})

    rates = {}
    for kind in chosen:  # each type its own starts and noise: the same figures alone as among the others
        k = kinds.index(kind)
        noise = np.random.default_rng([args.seed, k])
        rates |= success_by_kind(envs, act, [kind], args.episodes, args.seed + KIND_SEED_STRIDE * k,
                                 on_miss=record if args.misses else None)
    result = {"scene": args.scene, "episodes": args.episodes, "seed": args.seed, "horizon": args.horizon, "sleep": not args.awake,
              "action_mode": args.action_mode, "shields": args.shields, "per_subgoal": rates,
              "overall": sum(rates.values()) / len(rates)} | ({"misses": misses} if args.misses else {})
    if not args.json:
        for miss in misses:
            print(f"missed {miss['kind']} seed {miss['seed']}: {miss['subgoal']}: {'; '.join(miss['why'])}")
        for kind, rate in rates.items():
            print(f"{kind:14s} {rate:6.1%}")
    print(json.dumps(result) if args.json else f"{'overall':14s} {result['overall']:6.1%}")
    return 0
