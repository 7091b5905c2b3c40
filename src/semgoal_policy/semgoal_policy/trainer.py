"""Training loop: batched collection, expert supervision, sub-goal curriculum, checkpoints, export.

One cycle collects one episode in each of ``n_envs`` envs (some run by the scripted expert with noise:
demonstrations), stores them with the expert's labels, then runs ``updates_per_step`` gradient steps
per collected env step. Every ``eval_every`` env steps the deterministic actor is evaluated per sub-goal
type, a CSV row is written and a checkpoint (model, optimisers, replay buffer, RNG, curriculum) saved,
so ``--resume`` continues exactly where a killed run stopped. Without its ``replay.npz`` (the
committed checkpoints leave it out: 35-60 MB each) a resumed run first refills the buffer with
``refill_steps`` of collection and no updates; those steps are not counted in ``steps``, which is the
budget of env steps that feed updates.
"""

from __future__ import annotations

import csv
import json
import os
import shlex
import signal
import sys
import threading
import time
import zipfile
from collections.abc import Callable
from dataclasses import asdict, dataclass, field, replace
from pathlib import Path

import numpy as np
import torch
from tqdm import tqdm

from semgoal_core.provenance import provenance
from semgoal_core.vocabulary import SCENES
from semgoal_policy import actor as actor_io
from semgoal_policy.agents import AGENTS, AgentSpec
from semgoal_policy.evaluate import EVAL_SEED_BASE, run_episodes, success_by_kind
from semgoal_policy.model_card import write_card
from semgoal_policy.replay import EpisodeReplay
from semgoal_policy.sac import SacAgent, SacConfig

PROJECT_ROOT = Path(os.environ.get("SEMGOAL_ROOT") or Path.cwd())
"""The checkout (``tools/env.sh`` sets SEMGOAL_ROOT), so a run's folder does not depend on where it is started."""
RUNS_DIR = PROJECT_ROOT / "runs"


@dataclass
class TrainConfig:
    scene: str
    """two_blocks, three_blocks or desk_cleanup."""
    agent: str = "hierarchical"
    """hierarchical (sub-goals), flat-semantic (task goals) or flat-continuous (block positions)."""
    steps: int = 300_000
    """Env steps to train for (all envs together)."""
    seed: int = 0
    """Seeds the networks, the sampling and the training envs (whose episode seeds stay below the evaluation's)."""
    n_envs: int = 8
    """Envs stepped side by side; one episode each per collection cycle."""
    updates_per_step: float = 0.25
    """Gradient steps per collected env step (the HER baselines use 0.4 with 2 workers)."""
    learning_starts: int = 2_000
    """Transitions collected (demonstrations only) before the first gradient step."""
    refill_steps: int = 100_000
    """Env steps collected without updates when a run resumes without its replay buffer (at most the steps
    it had); they do not count toward ``steps``. With only ``learning_starts`` refilled, the critic
    overfitted the small buffer."""
    demo_fraction: float = 0.25
    """Share of collection episodes run by the scripted expert (with noise): the demonstrations."""
    demo_noise: float = 0.2
    """Std of the Gaussian noise on the expert's actions in demonstrations."""
    derived_features: tuple[str, ...] = ()
    """Features appended to the observation (``semgoal_core.features``; hierarchical agent only)."""
    spawn_margin: float = 0.0
    """How far (m, in x) training blocks may start beyond the tasks' spawn area (``SubgoalEnv``; hierarchical
    agent only). Evaluation during training keeps to the tasks' area."""
    missed_put_share: float = 0.0
    """Share of put_near episodes that start from a put that let go just out of reach (``SubgoalEnv``;
    hierarchical agent only), so that actors pick the block again. Evaluation during training starts none."""
    max_blocks: int | None = None
    """The most blocks a training episode has (``SubgoalEnv``; hierarchical agent only; None: every count the scene
    allows; evaluation during training draws the same). Six on the tabletop keeps Tower-7 and Clean-8 zero-shot."""
    tower_share: float | None = None
    """Share of training starts with a tower among the blocks (``SubgoalEnv``; scenes with towers, hierarchical agent
    only; None: the scene's own share). Evaluation during training keeps the scene's own."""
    curriculum: bool = True
    """Sample sub-goal types more often the lower their recent success (else uniformly)."""
    eval_every: int = 10_000
    """Env steps between evaluations (each writes a progress row and a checkpoint)."""
    eval_episodes: int = 20
    """Evaluation episodes per sub-goal type at each eval point (the final eval uses ``final_eval_episodes``)."""
    final_eval_episodes: int = 100
    """Evaluation episodes per sub-goal type after training (recorded in the exported actor.json)."""
    snapshots: bool = False
    """Also export the actor at every eval point (``run_dir/snapshots/<env steps>``, 350 KB each), so a
    checkpoint can be chosen on held-out task starts: per-type rates at 20 episodes are too noisy."""
    tensorboard: bool = False
    """Also write every progress row as TensorBoard scalars, same keys, x = env steps (``run_dir/tensorboard``:
    ``tensorboard --logdir runs``)."""
    max_wall_s: float = 2 * 3600
    """Stop (and export) after this much wall time across resumes, the time the run stood paused not counted
    (:class:`RunningClock`)."""
    torch_threads: int = 1
    """CPU threads for torch (1: small networks gain nothing from more, and runs share the cores)."""
    sac: SacConfig = field(default_factory=SacConfig)
    run_dir: Path | None = None
    """Checkpoints, progress and snapshots (default runs/<scene>-<agent>/seed<seed> in the checkout)."""
    export_dir: Path | None = None
    """Where the final actor is exported (default the run's export/; ``train --ship``: models/)."""
    command: str = ""
    phases: tuple[Phase, ...] = ()
    """Settings that change during the run (a recipe's ``phases``): from each phase's ``from_steps`` on, its
    settings replace the run's own (:data:`PHASED_SETTINGS` only)."""


PHASED_SETTINGS = ("updates_per_step", "demo_fraction", "demo_noise", "spawn_margin", "missed_put_share", "tower_share",
                   "curriculum")
"""What a phase may change: how the data is drawn and how much is learnt from it, never the networks' shape."""


@dataclass(frozen=True)
class Phase:
    """From ``from_steps`` env steps on, ``settings`` (a subset of :data:`PHASED_SETTINGS`) apply."""

    from_steps: int
    settings: dict

    @classmethod
    def from_recipe(cls, entry: dict) -> Phase:
        """A recipe's ``{from_steps: N, setting: value, ...}``; ValueError naming what is wrong."""
        entry = dict(entry)
        start = entry.pop("from_steps", None)
        if not isinstance(start, int) or isinstance(start, bool) or start <= 0:
            raise ValueError(f"a phase needs from_steps, a positive whole number of env steps (got {start!r})")
        unknown = sorted(set(entry) - set(PHASED_SETTINGS))
        if unknown or not entry:
            raise ValueError(f"a phase from {start} sets {', '.join(unknown) or 'nothing'}; a phase may set "
                             f"{', '.join(PHASED_SETTINGS)}")
        return cls(start, entry)


def settings_at(config: TrainConfig, env_steps: int) -> TrainConfig:
    """The configuration in force at ``env_steps``: the run's own settings, then every phase begun by then."""
    changed = {}
    for phase in config.phases:
        if phase.from_steps <= env_steps:
            changed.update(phase.settings)
    return replace(config, **changed) if changed else config


def schedule(config: TrainConfig, until: int | None = None) -> list[dict]:
    """The phased settings over a run (to ``until`` env steps, default the run's length): the settings from 0,
    then each phase's start with the settings then in force. What a run records and a recipe promises."""
    end = config.steps if until is None else until
    starts = [0, *(p.from_steps for p in config.phases if p.from_steps < end)]
    rows = []
    for start in starts:
        at = settings_at(config, start)
        rows.append({"from_steps": start, **{name: getattr(at, name) for name in PHASED_SETTINGS}})
    return rows


def _shapes_starts(settings: dict) -> bool:
    """Whether phased ``settings`` (a :func:`schedule` row) draw training starts that evaluation does not."""
    return bool(settings["spawn_margin"] or settings["missed_put_share"] or settings["tower_share"] is not None)


def recorded_config(config: TrainConfig) -> dict:
    """The configuration as a run records it (config.json, actor.json): plain JSON values, folders inside the
    checkout relative to it, so that the record reads the same on every machine."""

    def portable(value):
        if isinstance(value, Path):
            return str(value.relative_to(PROJECT_ROOT)) if value.is_relative_to(PROJECT_ROOT) else str(value)
        return value

    return json.loads(json.dumps({k: portable(v) for k, v in asdict(config).items()}, default=str))


class Curriculum:
    """Recent training success per kind (moving average); kinds are drawn more the less they succeed."""

    def __init__(self, kinds: tuple[str, ...], enabled: bool, rate: float = 0.05) -> None:
        self.kinds, self.enabled, self.rate = kinds, enabled, rate
        self.success = dict.fromkeys(kinds, 0.0)

    def probabilities(self) -> np.ndarray:
        if not self.enabled:
            return np.full(len(self.kinds), 1.0 / len(self.kinds))
        weights = np.array([1.0 - self.success[k] for k in self.kinds]) + 0.1
        return weights / weights.sum()

    def draw(self, rng: np.random.Generator, count: int) -> list[str]:
        return [str(k) for k in rng.choice(self.kinds, size=count, p=self.probabilities())]

    def record(self, kinds: list[str], success: np.ndarray) -> None:
        for kind, ok in zip(kinds, success, strict=True):
            self.success[kind] += self.rate * (float(ok) - self.success[kind])


class RunningClock:
    """Wall time a process ran, summed over :meth:`tick` calls: time it stood stopped (SIGSTOP, as a training run is
    paused while CI runs beside it) is not counted. SIGCONT ends a pause, and the interval it falls in is dropped
    (with the little work done in it: one collection cycle, or one evaluation)."""

    def __init__(self, start: float = 0.0) -> None:
        self.total = start
        self._last = time.perf_counter()
        self._paused = False
        self._previous = None
        if hasattr(signal, "SIGCONT") and threading.current_thread() is threading.main_thread():
            self._previous = signal.signal(signal.SIGCONT, self._continued)

    def _continued(self, *_) -> None:
        self._paused = True

    def tick(self) -> float:
        """The running time so far (s)."""
        now = time.perf_counter()
        if not self._paused:
            self.total += now - self._last
        self._paused, self._last = False, now
        return self.total

    def close(self) -> None:
        """Give SIGCONT back to whoever handled it before."""
        if self._previous is not None:
            signal.signal(signal.SIGCONT, self._previous)
            self._previous = None


class Trainer:
    """SAC+HER with expert supervision on ``config.n_envs`` envs that ``make_env()`` builds: goal-conditioned
    gymnasium envs with ``max_steps``, ``expert_action()``, an ``is_success`` info entry and
    ``reset(options={"kind": k})`` (the simulator's, bound in ``semgoal_bringup.experiments.training``)."""

    def __init__(self, config: TrainConfig, make_env: Callable[[], object]) -> None:
        self.base_config = config
        """The run's configuration with its phases; :attr:`config` is the one in force at ``env_steps``."""
        self.config = cfg = config
        torch.set_num_threads(cfg.torch_threads)
        torch.manual_seed(cfg.seed)
        self.spec: AgentSpec = AGENTS[cfg.agent]
        if not self.spec.subgoals and any(_shapes_starts(row) for row in schedule(cfg)):
            raise ValueError("a spawn margin, missed puts and a tower share are for the hierarchical agent only")
        self.rng = np.random.default_rng(cfg.seed)
        # training envs draw from seeds below EVAL_SEED_BASE; evaluation from above it
        self.envs = [make_env() for _ in range(cfg.n_envs)]
        for i, env in enumerate(self.envs):
            env.reset(seed=cfg.seed * 1000 + i)
            env.action_space.seed(cfg.seed * 1000 + i)
        probe = self.envs[0].observation_space
        obs_size, goal_size = probe["observation"].shape[0], probe["desired_goal"].shape[0]
        self.kinds = self.spec.kinds(cfg.scene)
        self.agent = SacAgent(obs_size, goal_size, cfg.sac, cfg.scene)
        horizon = self.envs[0].max_steps
        motion_size = 2 * SCENES[cfg.scene].max_blocks
        self.replay = EpisodeReplay(cfg.steps // horizon + cfg.n_envs, horizon, obs_size, goal_size,
                                    self.spec.reward_fn(cfg.scene), motion_size=motion_size)
        self.curriculum = Curriculum(self.kinds, cfg.curriculum)
        self.env_steps = 0
        self.wall_s = 0.0
        self.run_dir = cfg.run_dir or RUNS_DIR / f"{cfg.scene}-{cfg.agent}" / f"seed{cfg.seed}"
        self.export_dir = cfg.export_dir or self.run_dir / "export"
        self.last_metrics: dict[str, float] = {}

    # -- checkpoints ---------------------------------------------------------------------------------
    @property
    def checkpoint_path(self) -> Path:
        return self.run_dir / "checkpoint.pt"

    def save(self) -> None:
        self.run_dir.mkdir(parents=True, exist_ok=True)
        self.replay.save(self.run_dir / "replay.npz")
        state = {"agent": self.agent.state_dict(), "env_steps": self.env_steps, "wall_s": self.wall_s,
                 "rng": self.rng.bit_generator.state, "torch_rng": torch.get_rng_state(),
                 "curriculum": self.curriculum.success,
                 "env_rngs": [env.np_random.bit_generator.state for env in self.envs]}
        torch.save(state, self.checkpoint_path.with_suffix(".tmp"))
        self.checkpoint_path.with_suffix(".tmp").replace(self.checkpoint_path)

    def restore(self) -> None:
        state = torch.load(self.checkpoint_path, weights_only=False)
        self.agent.load_state_dict(state["agent"])
        self.env_steps, self.wall_s = state["env_steps"], state["wall_s"]
        self.rng.bit_generator.state = state["rng"]
        torch.set_rng_state(state["torch_rng"])
        self.curriculum.success = state["curriculum"]
        for env, rng_state in zip(self.envs, state["env_rngs"], strict=True):
            env.np_random.bit_generator.state = rng_state
        _drop_rows_after(self.run_dir / "progress.csv", self.env_steps)
        replay_path = self.run_dir / "replay.npz"
        if replay_path.exists():
            try:
                self.replay.load(replay_path)
            except (OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile) as error:  # a torn write
                self.replay.clear()
                print(f"{replay_path} unreadable ({type(error).__name__}: {error}): left aside as "
                      f"{replay_path.name}.unreadable; the buffer is refilled", file=sys.stderr)
                replay_path.replace(replay_path.with_name(f"{replay_path.name}.unreadable"))

    def refill(self, progress: Callable[[int], object] = lambda steps: None) -> int:
        """Collect without updates until the buffer holds ``refill_steps`` transitions (a resumed run whose
        buffer was not kept: the committed checkpoints); ``progress`` gets each cycle's env steps.
        Returns the env steps this took, which stay out of the run's count: they only replace the lost buffer."""
        target = min(self.config.refill_steps, self.env_steps, self.replay.capacity * self.envs[0].max_steps)
        if self.replay.transitions >= target:
            return 0
        print(f"{self.run_dir / 'replay.npz'} missing: refilling the replay buffer with {target} env steps "
              "before updates resume", file=sys.stderr)
        before = self.env_steps
        while self.replay.transitions < target:
            progress(self.collect())
        refilled, self.env_steps = self.env_steps - before, before
        return refilled

    # -- the loop ------------------------------------------------------------------------------------
    def collect(self) -> int:
        """One episode in each env, stored with the expert's labels; returns the env steps collected."""
        cfg, n = self.config, self.config.n_envs
        kinds = self.curriculum.draw(self.rng, n)
        expert = self.rng.uniform(size=n) < cfg.demo_fraction
        if self.replay.transitions < cfg.learning_starts and cfg.demo_fraction > 0:
            expert[:] = True  # the buffer starts with demonstrations only
        result = run_episodes(self.envs, self.agent.explore, [{"kind": k} for k in kinds],
                              expert_mask=expert, expert_noise=cfg.demo_noise, rng=self.rng)
        self.replay.add(result.obs, result.achieved, result.motion, result.goal, result.action, result.expert_action)
        self.agent.actor.normaliser.update(result.obs)
        agent_runs = ~expert
        self.curriculum.record([k for k, a in zip(result.kinds, agent_runs, strict=True) if a], result.success[agent_runs])
        self.env_steps += n * self.envs[0].max_steps
        return n * self.envs[0].max_steps

    def cycle(self) -> int:
        """One collection cycle and its gradient steps; returns the env steps collected."""
        steps = self.collect()
        self.train_step(steps)
        return steps

    def train_step(self, env_steps: int) -> None:
        cfg = self.config
        if self.replay.transitions < cfg.learning_starts:
            return
        cloning = cfg.sac.bc_weight > 0
        for _ in range(max(1, round(env_steps * cfg.updates_per_step))):
            batch = self.replay.sample(self.rng, cfg.sac.batch_size)
            bc_batch = self.replay.sample(self.rng, cfg.sac.batch_size, her_ratio=0.0) if cloning else None
            self.last_metrics = self.agent.update(batch, bc_batch)

    def evaluate(self, episodes: int) -> dict[str, float]:
        # evaluation reseeds the envs: without this, every window of training after an evaluation would
        # replay the same random starts
        training_rngs = [env.np_random.bit_generator.state for env in self.envs]
        self._set_training_starts(on=False)
        policy = self.agent.policy
        policy.eval()
        rates = success_by_kind(self.envs, policy.act, self.spec.evaluated_kinds(self.config.scene), episodes,
                                EVAL_SEED_BASE)
        policy.train()
        self._set_training_starts(on=True)
        for env, state in zip(self.envs, training_rngs, strict=True):
            env.np_random.bit_generator.state = state
        return rates

    def _enter_phase(self) -> None:
        """Bring :attr:`config` to the settings in force at ``env_steps`` (a phase begun, or a resumed run)."""
        now = settings_at(self.base_config, self.env_steps)
        if now == self.config:
            return
        changed = {name: getattr(now, name) for name in PHASED_SETTINGS if getattr(now, name) != getattr(self.config, name)}
        self.config = now
        self.curriculum.enabled = now.curriculum
        self._set_training_starts(on=True)
        tqdm.write(f"from {self.env_steps} env steps: " + ", ".join(f"{k} {v}" for k, v in changed.items()), file=sys.stderr)

    def _set_training_starts(self, on: bool) -> None:
        """The starts only training draws (spawn margin, missed puts, more towers), on or off: evaluation keeps to
        the tasks'."""
        if any(_shapes_starts(row) for row in schedule(self.base_config)):
            for env in self.envs:
                env.spawn_margin = self.config.spawn_margin if on else 0.0
                env.missed_put_share = self.config.missed_put_share if on else 0.0
                env.tower_share = self.config.tower_share if on else None

    def run(self, resume: bool = False) -> dict[str, float]:
        cfg = self.config
        if resume and self.checkpoint_path.exists():
            self.restore()
        elif not resume and self.checkpoint_path.exists():
            raise FileExistsError(f"{self.run_dir} holds a checkpoint: pass --resume to continue it, or remove the folder")
        self.run_dir.mkdir(parents=True, exist_ok=True)
        (self.run_dir / "config.json").write_text(json.dumps(recorded_config(self.base_config), indent=2) + "\n")
        csv_path = self.run_dir / "progress.csv"
        bar = tqdm(total=cfg.steps, initial=self.env_steps, unit="step", desc=f"{cfg.scene}/{cfg.agent}",
                   file=sys.stderr, mininterval=5, dynamic_ncols=True)
        clock = RunningClock(self.wall_s)
        self._enter_phase()
        self.refill(lambda steps: bar.set_postfix_str(f"refilling the replay buffer: {self.replay.transitions}"))
        next_eval = (self.env_steps // cfg.eval_every + 1) * cfg.eval_every
        while self.env_steps < cfg.steps and self.wall_s < cfg.max_wall_s:
            self._enter_phase()
            bar.update(self.cycle())
            self.wall_s = clock.tick()
            if self.env_steps >= next_eval:
                rates = self.evaluate(cfg.eval_episodes)
                self._log(csv_path, rates)
                if cfg.snapshots:
                    self._snapshot(rates)
                bar.set_postfix(success=f"{np.mean(list(rates.values())):.2f}")
                self.save()
                next_eval += cfg.eval_every
        bar.close()
        clock.close()
        self.save()
        final = self.evaluate(cfg.final_eval_episodes)
        self._export(final)
        return final

    def _snapshot(self, rates: dict[str, float]) -> None:
        """Export the evaluated actor to ``snapshots/<env steps>``; with averaging on, the live actor also goes
        to ``snapshots/<env steps>-live``, so one run compares the two on the same training."""
        snapshots, info = self.run_dir / "snapshots", {"env_steps": self.env_steps, "eval": rates}
        self._export_actor(self.agent.policy, snapshots / str(self.env_steps), info)
        if self.agent.policy is not self.agent.actor:
            self._export_actor(self.agent.actor, snapshots / f"{self.env_steps}-live", {"env_steps": self.env_steps})

    def _export_actor(self, actor: actor_io.Actor, directory: Path, info: dict) -> None:
        actor_io.export(actor, directory, self.config.scene, info, self.spec.goal, tuple(self.config.derived_features))

    def _log(self, csv_path: Path, rates: dict[str, float]) -> None:
        row = {"env_steps": self.env_steps, "wall_s": round(self.wall_s, 1),
               **{f"eval/success/{k}": v for k, v in rates.items()},
               "eval/success/overall": float(np.mean(list(rates.values()))),
               **{k: round(v, 5) for k, v in self.last_metrics.items()}}
        _append_row(csv_path, row)
        if self.config.tensorboard:
            self._tensorboard_row(row)
        print(f"[{self.env_steps} steps, {self.wall_s / 60:.1f} min] "
              + " ".join(f"{k}={v:.2f}" for k, v in rates.items()), file=sys.stderr, flush=True)

    def _tensorboard_row(self, row: dict[str, float]) -> None:
        from torch.utils.tensorboard import SummaryWriter  # only when asked: it loads the tensorboard package

        with SummaryWriter(self.run_dir / "tensorboard") as writer:
            for key, value in row.items():
                if key != "env_steps":
                    writer.add_scalar(key, value, self.env_steps)

    def _export(self, final: dict[str, float]) -> None:
        from semgoal_policy.plots import learning_curve

        cfg = self.config
        curve = learning_curve(self.run_dir / "progress.csv", self.export_dir / "learning_curve.png",
                               f"{cfg.scene} / {cfg.agent} (seed {cfg.seed})")
        command = cfg.command or shlex.join(sys.argv)
        info = {"agent": cfg.agent, "seed": cfg.seed, "env_steps": self.env_steps, "wall_s": round(self.wall_s, 1),
                "command": command, "provenance": provenance(command, cfg.seed), "kinds": list(self.kinds),
                "final_eval": {"episodes_per_kind": cfg.final_eval_episodes, "seed": EVAL_SEED_BASE,
                               "per_kind": final, "overall": float(np.mean(list(final.values())))},
                "first_reached_95": curve, "config": recorded_config(self.base_config),
                "schedule": schedule(self.base_config, until=self.env_steps)}
        self._export_actor(self.agent.policy, self.export_dir, info)
        (self.export_dir / "progress.csv").write_text((self.run_dir / "progress.csv").read_text())
        write_card(self.export_dir)


def _drop_rows_after(csv_path: Path, env_steps: int) -> None:
    """Leave out the progress rows past ``env_steps``: a run stopped after evaluating but before its next checkpoint
    resumes from the checkpoint, and would log those steps again (seed 202's curve had 1,725,200 twice)."""
    if not csv_path.exists():
        return
    with csv_path.open(newline="") as f:
        reader = csv.DictReader(f)
        fields, rows = reader.fieldnames or [], list(reader)
    kept = [row for row in rows if int(float(row["env_steps"])) <= env_steps]
    if len(kept) < len(rows):
        with csv_path.open("w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=fields)
            writer.writeheader()
            writer.writerows(kept)


def _append_row(csv_path: Path, row: dict) -> None:
    """Append ``row`` to the CSV (its header read, nothing more); where it brings new columns (a resumed run that
    reports more), the file is written again with them at the end, the rows before leaving them empty."""
    fields: list[str] = []
    if csv_path.exists():
        with csv_path.open(newline="") as f:
            fields = next(csv.reader(f), [])
    added = [key for key in row if key not in fields]
    if fields and not added:
        with csv_path.open("a", newline="") as f:
            csv.DictWriter(f, fieldnames=fields).writerow(row)
        return
    rows: list[dict] = []
    if fields:
        with csv_path.open(newline="") as f:
            rows = list(csv.DictReader(f))
    with csv_path.open("w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=fields + added)
        writer.writeheader()
        writer.writerows([*rows, row])
