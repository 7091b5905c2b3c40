"""The trainer end to end on a tiny budget: it learns-and-logs, checkpoints, resumes and exports."""

import csv
import os
import signal
import time
from dataclasses import replace

import numpy as np
import pytest
import torch

from semgoal_bringup.experiments.training import trainer_for
from semgoal_policy.actor import load
from semgoal_policy.replay import Batch
from semgoal_policy.sac import SacAgent, SacConfig
from semgoal_policy.trainer import Phase, RunningClock, TrainConfig


def config(tmp_path, steps: int) -> TrainConfig:
    return TrainConfig(scene="two_blocks", steps=steps, n_envs=4, learning_starts=400, eval_every=400,
                       eval_episodes=2, final_eval_episodes=2, run_dir=tmp_path / "run", export_dir=tmp_path / "export")


@pytest.mark.slow
def test_tiny_run_checkpoints_resumes_and_exports(tmp_path) -> None:
    first = trainer_for(config(tmp_path, 400))
    first.run()
    assert first.env_steps == 400 and (tmp_path / "run" / "checkpoint.pt").exists()
    resumed = trainer_for(replace(config(tmp_path, 800), snapshots=True))
    resumed.run(resume=True)
    assert resumed.env_steps == 800 and resumed.replay.size == 800 // 50
    rows = list(csv.DictReader((tmp_path / "run" / "progress.csv").open()))
    assert [int(r["env_steps"]) for r in rows] == [400, 800]
    assert "train/critic_loss" in rows[-1] and rows[-1]["train/critic_loss"]
    _, meta = load(tmp_path / "export", "two_blocks")
    assert meta["env_steps"] == 800 and set(meta["final_eval"]["per_kind"]) == {"pick", "put_near", "put_away", "put_on"}
    assert (tmp_path / "export" / "learning_curve.png").stat().st_size > 1000
    assert sorted(p.name for p in (tmp_path / "run" / "snapshots").iterdir()) == ["800"]
    assert load(tmp_path / "run" / "snapshots" / "800", "two_blocks")[1]["env_steps"] == 800


@pytest.mark.slow
def test_tensorboard_gets_the_progress_rows_keys_across_a_resume(tmp_path) -> None:
    from tensorboard.backend.event_processing.event_accumulator import EventAccumulator

    trainer_for(replace(config(tmp_path, 400), tensorboard=True)).run()
    trainer_for(replace(config(tmp_path, 800), tensorboard=True)).run(resume=True)
    rows = list(csv.DictReader((tmp_path / "run" / "progress.csv").open()))
    events = EventAccumulator(str(tmp_path / "run" / "tensorboard"))
    events.Reload()
    assert set(events.Tags()["scalars"]) == set(rows[0]) - {"env_steps"}
    overall = events.Scalars("eval/success/overall")
    assert [(e.step, round(e.value, 4)) for e in overall] == [(int(r["env_steps"]), round(float(r["eval/success/overall"]), 4))
                                                               for r in rows]
    assert (tmp_path / "export" / "MODEL_CARD.md").read_text().startswith("# two_blocks · hierarchical actor")


@pytest.mark.slow
def test_averaged_runs_snapshot_the_live_actor_beside_the_averaged_one(tmp_path) -> None:
    trainer_for(replace(config(tmp_path, 400), snapshots=True, sac=SacConfig(actor_average_rate=0.25))).run()
    snapshots = tmp_path / "run" / "snapshots"
    assert sorted(p.name for p in snapshots.iterdir()) == ["400", "400-live"]
    averaged, live = (load(snapshots / name, "two_blocks")[0] for name in ("400", "400-live"))
    assert not all(torch.equal(a, b) for a, b in zip(averaged.parameters(), live.parameters(), strict=True))


def test_evaluation_leaves_the_training_envs_random_streams_alone(tmp_path) -> None:
    trainer = trainer_for(config(tmp_path, 400))
    before = [env.np_random.bit_generator.state for env in trainer.envs]
    trainer.evaluate(2)
    assert [env.np_random.bit_generator.state for env in trainer.envs] == before
    trainer.collect()
    assert [env.np_random.bit_generator.state for env in trainer.envs] != before


def test_a_resumed_agent_takes_the_configured_learning_rate_not_the_checkpoints() -> None:
    saved = SacAgent(10, 6, SacConfig(lr=1e-3)).state_dict()
    resumed = SacAgent(10, 6, SacConfig(lr=3e-4))
    resumed.load_state_dict(saved)
    optimisers = (resumed.actor_optimizer, resumed.critic_optimizer, resumed.alpha_optimizer)
    assert {group["lr"] for opt in optimisers for group in opt.param_groups} == {3e-4}


@pytest.mark.slow
def test_resume_without_replay_buffer_refills_at_most_the_steps_the_run_had(tmp_path) -> None:
    trainer_for(config(tmp_path, 400)).run()
    (tmp_path / "run" / "replay.npz").unlink()
    resumed = trainer_for(config(tmp_path, 800))  # refill_steps 100k, capped at the 400 steps before the resume
    resumed.run(resume=True)
    # the refill's 400 steps replace the lost buffer and stay out of the budget: 400 more steps of training follow
    assert resumed.env_steps == 800 and resumed.replay.size == (400 + 400) // 50


@pytest.mark.slow
def test_a_resume_drops_the_progress_rows_past_its_checkpoint(tmp_path) -> None:
    """Rows logged after the last checkpoint (a run stopped between them) are of steps the resume takes again."""
    trainer_for(config(tmp_path, 400)).run()
    progress = tmp_path / "run" / "progress.csv"
    lines = progress.read_text().splitlines()
    progress.write_text("\n".join([*lines, lines[-1].replace("400", "600", 1)]) + "\n")
    trainer_for(config(tmp_path, 800)).run(resume=True)
    assert [int(r["env_steps"]) for r in csv.DictReader(progress.open())] == [400, 800]


@pytest.mark.slow
def test_resume_over_a_torn_replay_buffer_sets_it_aside_and_refills(tmp_path) -> None:
    """A run stopped while its buffer was written (an older save, not atomic) left half a file: the resume goes on."""
    trainer_for(config(tmp_path, 400)).run()
    replay = tmp_path / "run" / "replay.npz"
    replay.write_bytes(replay.read_bytes()[: replay.stat().st_size // 2])
    resumed = trainer_for(config(tmp_path, 800))
    resumed.run(resume=True)
    assert resumed.env_steps == 800 and resumed.replay.size == (400 + 400) // 50
    assert (tmp_path / "run" / "replay.npz.unreadable").exists()


@pytest.mark.slow
def test_the_refill_collects_without_updating_the_networks(tmp_path) -> None:
    trainer_for(config(tmp_path, 400)).run()
    (tmp_path / "run" / "replay.npz").unlink()
    resumed = trainer_for(replace(config(tmp_path, 1200), refill_steps=300))
    resumed.restore()
    weights = [p.clone() for p in (*resumed.agent.actor.net.parameters(), *resumed.agent.critic.parameters())]
    assert resumed.refill() == 400  # whole cycles of 4 envs x 50 steps until 300 are in
    assert resumed.env_steps == 400 and resumed.replay.transitions == 400
    after = (*resumed.agent.actor.net.parameters(), *resumed.agent.critic.parameters())
    assert all(torch.equal(a, b) for a, b in zip(weights, after, strict=True))
    assert resumed.refill() == 0  # a full enough buffer is left alone


@pytest.mark.slow
def test_flat_baseline_trains_on_whole_tasks_and_exports_with_its_goal_layout(tmp_path) -> None:
    cfg = config(tmp_path, 2 * 4 * 120)
    cfg.agent, cfg.learning_starts, cfg.eval_every = "flat-semantic", 480, 960
    trainer = trainer_for(cfg)
    trainer.run()
    _, meta = load(tmp_path / "export", "two_blocks")
    assert meta["agent"] == "flat-semantic" and set(meta["final_eval"]["per_kind"]) == {"MC-2", "MA-2", "Swap-2"}


def _batch(rng: np.random.Generator, size: int = 32) -> Batch:
    def f(*shape: int) -> np.ndarray:
        return rng.standard_normal((size, *shape)).astype(np.float32)
    return Batch(obs=f(10), goal=(f(6) > 0).astype(np.float32), action=np.tanh(f(4)), reward=(f() > 0).astype(np.float32),
                 next_obs=f(10), expert_action=np.tanh(f(4)), has_label=np.ones(size, np.float32))


def test_the_averaged_actor_trails_the_live_one_and_is_the_one_evaluated() -> None:
    agent = SacAgent(10, 6, SacConfig(actor_average_rate=0.25))
    rng = np.random.default_rng(0)
    before = [p.clone() for p in agent.actor.net.parameters()]
    agent.update(_batch(rng), _batch(rng))
    for old, new, average in zip(before, agent.actor.net.parameters(), agent.actor_average.net.parameters(), strict=True):
        assert torch.allclose(average, 0.75 * old + 0.25 * new)
    agent.actor.normaliser.update(rng.standard_normal((5, 10)))
    assert agent.policy is agent.actor_average
    assert torch.equal(agent.policy.normaliser.mean, agent.actor.normaliser.mean)


def test_averaging_resumes_from_its_checkpoint_or_starts_at_the_actor() -> None:
    agent = SacAgent(10, 6, SacConfig(actor_average_rate=0.25))
    agent.update(_batch(np.random.default_rng(1)))
    resumed = SacAgent(10, 6, SacConfig(actor_average_rate=0.25))
    resumed.load_state_dict(agent.state_dict())
    assert all(torch.equal(a, b) for a, b in zip(resumed.actor_average.parameters(), agent.actor_average.parameters(), strict=True))
    plain = SacAgent(10, 6, SacConfig())
    plain.load_state_dict(agent.state_dict())  # a checkpoint written with averaging loads without it
    assert plain.policy is plain.actor
    started = SacAgent(10, 6, SacConfig(actor_average_rate=0.25))
    started.load_state_dict(plain.state_dict())  # one written without averaging starts the average at the actor
    assert all(torch.equal(a, b) for a, b in zip(started.actor_average.parameters(), started.actor.parameters(), strict=True))


def test_a_spawn_margin_and_missed_puts_shape_training_starts_but_not_evaluation(tmp_path) -> None:
    trainer = trainer_for(replace(config(tmp_path, 400), spawn_margin=0.05, missed_put_share=0.25))
    seen = []
    original = type(trainer.envs[0])._sample_positions

    def spy(env, binned: bool = False):
        seen.append((env.spawn_margin, env.missed_put_share))
        return original(env, binned)

    for env in trainer.envs:
        env._sample_positions = spy.__get__(env)
    trainer.evaluate(1)
    assert seen and set(seen) == {(0.0, 0.0)}
    seen.clear()
    trainer.collect()
    assert seen and set(seen) == {(0.05, 0.25)}


@pytest.mark.slow
def test_a_phase_begins_at_its_step_and_a_resumed_run_starts_in_it(tmp_path) -> None:
    phased = replace(config(tmp_path, 400), missed_put_share=0.0,
                     phases=(Phase(200, {"missed_put_share": 0.25, "demo_fraction": 0.5}),))
    trainer = trainer_for(phased)
    trainer._enter_phase()
    assert trainer.config.missed_put_share == 0.0 and trainer.envs[0].missed_put_share == 0.0
    while trainer.env_steps < 200:
        trainer.collect()
    trainer._enter_phase()
    assert trainer.config.demo_fraction == 0.5 and {env.missed_put_share for env in trainer.envs} == {0.25}
    trainer.evaluate(1)  # evaluation keeps to the tasks' starts, then training's phase comes back
    assert {env.missed_put_share for env in trainer.envs} == {0.25}


def test_a_tower_share_phase_shapes_training_starts_but_not_evaluation(tmp_path) -> None:
    phased = replace(config(tmp_path, 400), scene="tabletop", n_envs=2, phases=(Phase(200, {"tower_share": 0.8}),))
    trainer = trainer_for(phased)
    trainer._enter_phase()
    assert {env.tower_share for env in trainer.envs} == {None}
    trainer.env_steps = 200
    trainer._enter_phase()
    assert {env.tower_share for env in trainer.envs} == {0.8}
    seen = []
    original = type(trainer.envs[0])._sample_positions

    def spy(env, binned: bool = False):
        seen.append(env.tower_share)
        return original(env, binned)

    for env in trainer.envs:
        env._sample_positions = spy.__get__(env)
    trainer.evaluate(1)
    assert seen and set(seen) == {None} and {env.tower_share for env in trainer.envs} == {0.8}


@pytest.mark.parametrize("setting", [{"spawn_margin": 0.05}, {"missed_put_share": 0.25}, {"tower_share": 0.5}, {"max_blocks": 2},
                                     {"phases": (Phase(200, {"missed_put_share": 0.25}),)}])
def test_flat_baselines_refuse_training_only_starts(tmp_path, setting: dict) -> None:
    with pytest.raises(ValueError, match="hierarchical agent only"):
        trainer_for(replace(config(tmp_path, 400), agent="flat-semantic", **setting))


def test_the_running_clock_leaves_out_a_pause_that_sigcont_ends() -> None:
    """A run paused (SIGSTOP) while CI runs beside it does not spend its wall-time cap standing still."""
    clock = RunningClock(100.0)
    try:
        time.sleep(0.05)
        assert 100.04 < clock.tick() < 101.0
        time.sleep(0.2)  # standing stopped, as far as the clock can tell
        os.kill(os.getpid(), signal.SIGCONT)
        paused = clock.tick()
        time.sleep(0.05)
        assert paused < 100.2 and 0.04 < clock.tick() - paused < 0.2
    finally:
        clock.close()
    assert signal.getsignal(signal.SIGCONT) in (signal.SIG_DFL, None)


def test_a_resumed_run_that_reports_more_keeps_one_csv_with_every_column(tmp_path) -> None:
    from semgoal_policy.plots import learning_curve
    from semgoal_policy.trainer import _append_row

    path = tmp_path / "progress.csv"
    for steps in (1000, 2000):
        _append_row(path, {"env_steps": steps, "eval/success/pick": 0.95, "eval/success/overall": 0.95})
    _append_row(path, {"env_steps": 3000, "eval/success/pick": 1.0, "eval/success/overall": 0.5,
                       "eval/success/take_out": 0.0})
    _append_row(path, {"env_steps": 4000, "eval/success/pick": 1.0, "eval/success/overall": 0.98,
                       "eval/success/take_out": 0.96})
    rows = list(csv.DictReader(path.open()))
    assert [r["eval/success/take_out"] for r in rows] == ["", "", "0.0", "0.96"]
    assert [r["env_steps"] for r in rows] == ["1000", "2000", "3000", "4000"]
    # every kind at 95 % first where every kind is measured and there
    assert learning_curve(path, tmp_path / "curve.png", "t") == 4000 and (tmp_path / "curve.png").stat().st_size > 1000


def test_evaluation_reports_take_outs_apart_where_there_is_a_bin(tmp_path) -> None:
    from semgoal_policy.agents import AGENTS

    trainer = trainer_for(replace(config(tmp_path, 400), scene="desk_cleanup", n_envs=2))
    assert list(trainer.evaluate(1)) == [*trainer.kinds, "take_out"]

    hierarchical = AGENTS["hierarchical"]
    assert hierarchical.evaluated_kinds("tabletop")[-1] == "take_out"
    assert hierarchical.evaluated_kinds("desk_cleanup")[-1] == "take_out"
    assert hierarchical.evaluated_kinds("two_blocks") == hierarchical.kinds("two_blocks")
    assert "take_out" not in AGENTS["flat-semantic"].evaluated_kinds("desk_cleanup")
