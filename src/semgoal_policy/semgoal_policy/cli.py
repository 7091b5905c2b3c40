"""Policy subcommands of ./semgoal: `train` and `eval-subgoals`."""

from __future__ import annotations

import argparse
import json
import shlex
import sys
from pathlib import Path

from semgoal_core.vocabulary import SCENES


def train_main(argv: list[str]) -> int:
    """`./semgoal train --scene S [--agent A] --steps N --seed S [--resume]`: train with SAC+HER and export."""
    from semgoal_core.features import DERIVED_FEATURES
    from semgoal_policy.agents import AGENTS
    from semgoal_policy.sac import SacConfig
    from semgoal_policy.trainer import TrainConfig, Trainer

    defaults = TrainConfig(scene="two_blocks")
    parser = argparse.ArgumentParser(prog="semgoal train", description=train_main.__doc__)
    parser.add_argument("--scene", required=True, choices=list(SCENES))
    parser.add_argument("--agent", default="hierarchical", choices=list(AGENTS))
    parser.add_argument("--steps", type=int, default=defaults.steps)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--resume", action="store_true", help="continue the run's last checkpoint")
    parser.add_argument("--envs", type=int, default=defaults.n_envs)
    parser.add_argument("--refill-steps", type=int, default=defaults.refill_steps,
                        help="on --resume without the run's replay.npz: env steps collected before updates resume")
    parser.add_argument("--updates-per-step", type=float, default=defaults.updates_per_step)
    parser.add_argument("--demo-fraction", type=float, default=defaults.demo_fraction,
                        help="share of episodes run by the scripted expert (0: no demonstrations)")
    parser.add_argument("--lr", type=float, default=SacConfig.lr, help="Adam learning rate (also on --resume)")
    parser.add_argument("--bc-weight", type=float, default=SacConfig.bc_weight, help="0: no behaviour cloning")
    parser.add_argument("--no-q-filter", action="store_true", help="clone the expert's label in every state, "
                        "not only where the critic rates it above the actor's action")
    parser.add_argument("--target-entropy", type=float, default=SacConfig.target_entropy,
                        help="entropy the SAC temperature is tuned toward")
    parser.add_argument("--log-std-max", type=float, default=SacConfig.log_std_max,
                        help="upper clamp of the actor's log std (2: SB3's)")
    parser.add_argument("--mean-reg", type=float, default=SacConfig.mean_reg,
                        help="weight of an L2 penalty on the actor's pre-tanh mean (0: off)")
    parser.add_argument("--actor-average-rate", type=float, default=SacConfig.actor_average_rate,
                        help="Polyak rate of the averaged actor that is evaluated and exported (0: the live actor)")
    parser.add_argument("--derive", action="append", default=[], choices=list(DERIVED_FEATURES),
                        help="append this derived feature to the observation (repeatable; hierarchical only)")
    parser.add_argument("--spawn-margin", type=float, default=defaults.spawn_margin,
                        help="m: training blocks start up to this far beyond the tasks' area in x (hierarchical only)")
    parser.add_argument("--no-curriculum", action="store_true")
    parser.add_argument("--eval-every", type=int, default=defaults.eval_every)
    parser.add_argument("--eval-episodes", type=int, default=defaults.eval_episodes)
    parser.add_argument("--final-eval-episodes", type=int, default=defaults.final_eval_episodes)
    parser.add_argument("--snapshots", action="store_true", help="export the actor at every eval point too (run-dir/snapshots/)")
    parser.add_argument("--max-wall-min", type=float, default=defaults.max_wall_s / 60)
    parser.add_argument("--run-dir", type=Path, help="checkpoints and logs (default runs/SCENE-AGENT/seedS)")
    parser.add_argument("--export-dir", type=Path, help="where the actor is exported (default models/...)")
    args = parser.parse_args(argv)
    config = TrainConfig(
        scene=args.scene, agent=args.agent, steps=args.steps, seed=args.seed, n_envs=args.envs, refill_steps=args.refill_steps,
        updates_per_step=args.updates_per_step, demo_fraction=args.demo_fraction, curriculum=not args.no_curriculum,
        derived_features=tuple(args.derive), spawn_margin=args.spawn_margin,
        eval_every=args.eval_every, eval_episodes=args.eval_episodes, final_eval_episodes=args.final_eval_episodes,
        snapshots=args.snapshots, max_wall_s=args.max_wall_min * 60,
        sac=SacConfig(lr=args.lr, bc_weight=args.bc_weight, q_filter=not args.no_q_filter, target_entropy=args.target_entropy,
                      actor_average_rate=args.actor_average_rate, log_std_max=args.log_std_max,
                      mean_reg=args.mean_reg),
        run_dir=args.run_dir, export_dir=args.export_dir, command=shlex.join(["./semgoal", "train", *argv]),
    )
    try:
        trainer = Trainer(config)
        final = trainer.run(resume=args.resume)
    except (FileExistsError, ValueError) as error:
        print(f"semgoal train: {error}", file=sys.stderr)
        return 2
    print(json.dumps({"scene": args.scene, "agent": args.agent, "env_steps": trainer.env_steps,
                      "wall_s": round(trainer.wall_s, 1), "per_kind": final, "export": str(trainer.export_dir)}))
    return 0


def eval_subgoals_main(argv: list[str]) -> int:
    """`./semgoal eval-subgoals --scene S --episodes N --seed S --json`: the shipped actor per sub-goal type."""
    from semgoal_policy.actor import MODELS_DIR, derived_features, load
    from semgoal_policy.agents import get_agent
    from semgoal_policy.controller import ACTION_MODES
    from semgoal_policy.evaluate import success_by_kind
    from semgoal_sim.env import EPISODE_STEPS, TAKE_OUT

    parser = argparse.ArgumentParser(prog="semgoal eval-subgoals", description=eval_subgoals_main.__doc__)
    parser.add_argument("--scene", required=True, choices=list(SCENES))
    parser.add_argument("--episodes", type=int, default=200, help="episodes per sub-goal type")
    parser.add_argument("--seed", type=int, default=2_000_000, help="first episode seed (training uses seeds < 1e6)")
    parser.add_argument("--horizon", type=int, default=EPISODE_STEPS,
                        help=f"control steps per episode (default {EPISODE_STEPS}, the training horizon; the planner "
                             "grants a step stall_steps, 150, before it re-plans)")
    parser.add_argument("--action-mode", choices=ACTION_MODES, default="mean",
                        help="mean: the deterministic actor (default); sample: its Gaussian, seeded by --seed, "
                             "as policy_node runs it (action_mode: sample)")
    parser.add_argument("--model-dir", type=Path, help=f"exported actor (default {MODELS_DIR}/SCENE)")
    parser.add_argument("--envs", type=int, default=10)
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args(argv)
    for name in ("episodes", "horizon", "envs"):
        if getattr(args, name) < 1:
            parser.error(f"--{name} must be at least 1, got {getattr(args, name)}")
    import numpy as np
    import torch

    torch.set_num_threads(1)
    actor, meta = load(args.model_dir or MODELS_DIR / args.scene, args.scene)
    spec = get_agent("hierarchical")
    envs = [spec.make_env(args.scene, derived_features(meta)) for _ in range(args.envs)]
    for env in envs:
        env.max_steps = args.horizon
    noise = np.random.default_rng(args.seed)

    def act(obs: np.ndarray, goal: np.ndarray) -> np.ndarray:
        """The actor's mean, or a sample of its Gaussian as the policy node draws it."""
        return actor.act(obs, goal, noise.standard_normal((len(obs), 4)) if args.action_mode == "sample" else None)

    kinds = spec.kinds(args.scene) + ((TAKE_OUT,) if envs[0].scene.bin is not None else ())  # put_on_table from the bin
    rates = success_by_kind(envs, act, kinds, args.episodes, args.seed)
    result = {"scene": args.scene, "episodes": args.episodes, "seed": args.seed, "horizon": args.horizon,
              "action_mode": args.action_mode, "per_subgoal": rates,
              "overall": sum(rates.values()) / len(rates)}
    if not args.json:
        for kind, rate in rates.items():
            print(f"{kind:14s} {rate:6.1%}")
    print(json.dumps(result) if args.json else f"{'overall':14s} {result['overall']:6.1%}")
    return 0
