"""The tabletop scene: its starts, its bin of eight, and the scripted expert building and taking down towers."""

import itertools

import mujoco
import numpy as np
import pytest

from semgoal_core.geometry import TABLE_TOP, clear_of
from semgoal_core.tasks import (
    HOME_CLEARANCE,
    HOME_GRIP_XY,
    TABLETOP_SEPARATION,
    TABLETOP_SPAWN_HIGH,
    TABLETOP_SPAWN_LOW,
    TABLETOP_TASKS,
    stacked,
)
from semgoal_core.vocabulary import BLOCK_HALF_SIZE, LAYOUTS, SCENES, Literal
from semgoal_sim.rollout import run_task, settled, solve
from semgoal_sim.scene import STACKING_CONTACT, block_body_name
from semgoal_sim.world import FetchWorld

TABLETOP = SCENES["tabletop"]


@pytest.mark.parametrize("name", list(TABLETOP_TASKS))
def test_tabletop_starts_are_reproducible_valid_and_fingers_apart(name: str) -> None:
    task = TABLETOP_TASKS[name]
    for seed in range(20):
        positions, goal = task.initial_state(seed)
        np.testing.assert_array_equal(positions, task.initial_state(seed)[0])
        assert np.all(positions[:, :2] >= TABLETOP_SPAWN_LOW - 0.005) and np.all(positions[:, :2] <= TABLETOP_SPAWN_HIGH + 0.005)
        on_table = positions[np.abs(positions[:, 2] - (TABLE_TOP + BLOCK_HALF_SIZE)) < 0.01]
        for a, b in itertools.combinations(on_table, 2):
            assert np.linalg.norm(a[:2] - b[:2]) >= TABLETOP_SEPARATION - 1e-9
        for literal in goal:
            LAYOUTS["tabletop"].validate(literal)
        if name.startswith("Unstack"):  # the hand waits at home as the episode begins: not in the tower's way
            assert np.linalg.norm(positions[0, :2] - HOME_GRIP_XY) >= HOME_CLEARANCE


def test_the_bin_takes_eight_blocks_the_fingers_clear_of_each_other() -> None:
    slots = TABLETOP.bin.slots()
    assert len(slots) == 8
    for i, slot in enumerate(slots):
        others = [np.array([*other, 0.0]) for j, other in enumerate(slots) if j != i]
        assert clear_of(slot[None], others)[0]
    assert np.all(np.abs(slots - TABLETOP.bin.center) + BLOCK_HALF_SIZE < TABLETOP.bin.inner_half_size)


def test_the_expert_builds_a_tower_of_six_that_stands() -> None:
    task = TABLETOP_TASKS["Tower-6"]
    world = FetchWorld("tabletop", 6)
    positions, goal = task.initial_state(7)
    world.reset(positions)
    assert solve(world, goal).success
    for _ in range(50):
        world.step(np.zeros(4))
        assert settled(world, stacked(task.blocks))
    assert world.snapshot().block_positions[:, 2].max() > TABLE_TOP + 5.4 * 2 * BLOCK_HALF_SIZE


def _leaning_tower(scene: str, overhang: float, sleep: bool = True) -> FetchWorld:
    """A tower of six (the first two blocks for a scene of two) whose upper blocks all overhang the bottom one by
    ``overhang`` (m) along x, after 250 control steps (10 s) with the arm at home (``sleep``: the world's)."""
    count = min(6, SCENES[scene].max_blocks)
    world = FetchWorld(scene, count, sleep=sleep)
    world.reset(np.array([[1.30 + (overhang if k else 0.0), 0.60, TABLE_TOP + (2 * k + 1) * BLOCK_HALF_SIZE + 5e-4 * k]
                          for k in range(count)]))
    for _ in range(250):
        world.step(np.zeros(4))
    return world


@pytest.mark.parametrize("overhang", [0.0, 0.01, 0.018])
def test_a_tower_of_six_stands_while_its_upper_blocks_rest_on_the_bottom_one(overhang: float) -> None:
    """Their centre of mass is over the bottom block (half size 2.5 cm), so a rigid tower stands; the benchmark's soft
    contacts let one fall from an overhang of 6 mm."""
    world = _leaning_tower("tabletop", overhang)
    assert settled(world, stacked(world.blocks))
    assert np.abs(world.snapshot().block_positions[1:, 0] - 1.30 - overhang).max() < 0.005


def test_a_tower_of_six_falls_once_its_upper_blocks_overhang_the_bottom_one() -> None:
    assert _leaning_tower("tabletop", 1.2 * BLOCK_HALF_SIZE).snapshot().block_positions[-1, 2] < TABLE_TOP + 0.2


@pytest.mark.parametrize(("scene", "impedance"), [("two_blocks", 0.9), ("tabletop", STACKING_CONTACT.solimp[0])])
def test_only_the_tabletops_blocks_meet_through_stiff_contacts(scene: str, impedance: float) -> None:
    """The paper's scenes keep the Fetch benchmark's (MuJoCo's default) contacts, with which Table 1 was measured
    (read awake: sleeping blocks' contacts are not computed)."""
    world = _leaning_tower(scene, 0.0, sleep=False)
    model, data = world.model, world.data
    blocks = {mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_GEOM, block_body_name(block)) for block in world.blocks}
    between = [contact for contact in data.contact[:data.ncon] if {contact.geom1, contact.geom2} <= blocks]
    assert between and all(contact.solimp[0] == pytest.approx(impedance) for contact in between)


@pytest.mark.parametrize("name", ["Tower-5", "Unstack-6", "Sort", "Clean-6"])
def test_the_expert_solves_tabletop_tasks(name: str) -> None:
    results = [run_task(name, seed) for seed in range(200, 203)]
    assert all(r.success for r in results), results


def test_the_tabletop_reaches_higher_than_the_benchmarks_box() -> None:
    world = FetchWorld("tabletop", 2)
    world.reset(TABLETOP_TASKS["Tower-3"].initial_state(0)[0][:2])
    for _ in range(40):
        world.step(np.array([0.0, 0.0, 1.0, 0.0]))
    assert world.view().grip[2] > TABLE_TOP + 0.45
    desk = FetchWorld("desk_cleanup", 2)
    desk.reset(np.array([[1.2, 0.6, 0.425], [1.4, 0.6, 0.425]]))
    for _ in range(40):
        desk.step(np.array([0.0, 0.0, 1.0, 0.0]))
    assert desk.view().grip[2] < TABLE_TOP + 0.35
    assert Literal("above", ("green", "red")) in stacked(("red", "green"))


def test_training_may_draw_more_tower_starts_on_the_tabletop_only() -> None:
    from semgoal_sim.env import MAX_TOWER_SHARE, TOWER_START_SHARE, SubgoalEnv

    def towers(env: SubgoalEnv, draws: int = 200) -> float:
        env.reset(seed=0)
        return np.mean([(env._sample_positions()[:, 2] > TABLE_TOP + 3 * BLOCK_HALF_SIZE).any() for _ in range(draws)])

    env = SubgoalEnv("tabletop")
    default = towers(env)
    env.tower_share = MAX_TOWER_SHARE
    assert abs(default - TOWER_START_SHARE["tabletop"]) < 0.1 and towers(env) > default + 0.3
    with pytest.raises(ValueError, match="needs a scene with towers"):
        SubgoalEnv("two_blocks", tower_share=0.5)
    with pytest.raises(ValueError, match=r"in \[0, 0.8\]"):
        env.tower_share = 0.9


def test_more_tower_starts_keep_the_binned_ones_in_proportion() -> None:
    """A larger tower share takes from every other kind of start alike: drawn over the binned starts' range, it
    once left no training start with a block in the bin, and take-outs went untrained."""
    from semgoal_sim.env import BINNED_START_SHARE, MAX_TOWER_SHARE, TOWER_START_SHARE, SubgoalEnv

    def binned(env: SubgoalEnv, draws: int = 400) -> float:
        env.reset(seed=0)
        bin_floor = TABLE_TOP + env.scene.bin.floor_thickness + BLOCK_HALF_SIZE + 0.005
        inside = lambda p: np.all(np.abs(p[:, :2] - env.scene.bin.center) < env.scene.bin.inner_half_size, axis=1)  # noqa: E731
        return np.mean([(inside(p) & (p[:, 2] < bin_floor)).any() for p in (env._sample_positions() for _ in range(draws))])

    env = SubgoalEnv("tabletop")
    default = binned(env)
    expected = (1.0 - BINNED_START_SHARE) - TOWER_START_SHARE["tabletop"]  # the binned range beside the default towers
    assert abs(default - expected) < 0.05
    env.tower_share = MAX_TOWER_SHARE
    kept = expected * (1.0 - MAX_TOWER_SHARE) / (1.0 - TOWER_START_SHARE["tabletop"])
    assert abs(binned(env) - kept) < 0.04 and binned(env) > 0.02


def test_training_may_keep_to_six_blocks_so_seven_and_eight_stay_unseen() -> None:
    from semgoal_sim.env import SubgoalEnv

    env = SubgoalEnv("tabletop", max_blocks=6)
    assert env.block_counts == (2, 3, 4, 5, 6)
    drawn = set()
    for seed in range(40):
        env.reset(seed=seed)
        drawn.add(len(env.world.blocks))
    assert max(drawn) <= 6 and len(drawn) > 2
    with pytest.raises(ValueError, match="max_blocks 1 leaves no episode"):
        SubgoalEnv("tabletop", max_blocks=1)


@pytest.mark.parametrize("kind, first_seed", [("put_near", 2_010_000), ("put_away", 2_020_000), ("put_on", 2_030_000)])
def test_the_tabletop_draws_only_puts_a_plan_could_hand_over(kind: str, first_seed: int) -> None:
    """Evaluation's first starts of each put (the seeds of `eval subgoals`): a put on or near goes to a block outside
    the bin with nothing on it, near one standing on the table (the domain's preconditions), and a put near or away
    has a spot that fits. Drawn otherwise (2,010,009: near a block in the bin; 2,020,006: away from seven blocks with
    no room left), the expert held the block to the end."""
    from semgoal_core.expert import destination
    from semgoal_sim.env import SubgoalEnv

    env = SubgoalEnv("tabletop")
    for seed in range(first_seed, first_seed + 30):
        env.reset(seed=seed, options={"kind": kind})
        subgoal, state = env.subgoal, env.world.semantic_vector()
        assert env.world.view().holds(subgoal.block), (seed, subgoal)
        if kind != "put_away":
            for ref in subgoal.references:
                others = [b for b in env.world.blocks if b != ref]
                assert not state[env.layout.index(Literal("in_bin", (ref,)))], (seed, subgoal)
                assert not any(state[env.layout.index(Literal("above", (b, ref)))] for b in others), (seed, subgoal)
                if kind == "put_near":
                    assert not any(state[env.layout.index(Literal("above", (ref, b)))] for b in others), (seed, subgoal)
        if kind != "put_on":
            assert destination(subgoal, env.world.view()) is not None, (seed, subgoal)
