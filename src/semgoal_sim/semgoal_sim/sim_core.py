"""The simulator as the sim node sees it: tasks and seeds, command checking, interventions. No rclpy.

Every input is checked here: a command with a non-finite entry is dropped, one out of [-1, 1] is
clamped, a stale lockstep command is ignored, an unknown task or block is refused; each case returns a
message for the node to log, and the world keeps its last good state.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from semgoal_core.arms import robot_name
from semgoal_core.geometry import TABLE_CENTER, TABLE_HALF_SIZE, TABLE_TOP
from semgoal_core.layout import CONTROL_DT
from semgoal_core.tasks import TASKS, get_task
from semgoal_core.vocabulary import BLOCK_HALF_SIZE, SCENES
from semgoal_sim.world import FetchWorld, Snapshot

MAX_SEED = 2**63
"""Task seeds lie in [0, 2**63): what ``WorldState.seed`` (int64) carries."""


@dataclass(frozen=True)
class CommandCheck:
    """Outcome of checking one arm command: the action to apply (None = drop it) and why."""

    action: np.ndarray | None
    warning: str = ""


def check_command(values: list[float] | np.ndarray) -> CommandCheck:
    """Drop non-finite commands, clamp out-of-range ones (Fetch actions live in [-1, 1])."""
    action = np.asarray(values, dtype=np.float64)
    if action.shape != (4,):
        return CommandCheck(None, f"dropped a command with {action.size} values (need 4)")
    if not np.all(np.isfinite(action)):
        return CommandCheck(None, f"dropped a command with non-finite values {action.tolist()}")
    if np.any(np.abs(action) > 1.0):
        return CommandCheck(np.clip(action, -1.0, 1.0), f"clamped an out-of-range command {action.tolist()} to [-1, 1]")
    return CommandCheck(action)


def _off_table(xy: np.ndarray) -> str:
    """Why a block centred at ``xy`` is not over the table ("" when it is)."""
    low = np.array(TABLE_CENTER) - np.array(TABLE_HALF_SIZE) + BLOCK_HALF_SIZE
    high = np.array(TABLE_CENTER) + np.array(TABLE_HALF_SIZE) - BLOCK_HALF_SIZE
    if np.any(xy < low) or np.any(xy > high):
        return f"({xy[0]:.3f}, {xy[1]:.3f}) is off the table (x {low[0]:.2f}..{high[0]:.2f}, y {low[1]:.2f}..{high[1]:.2f})"
    return ""


STACK_ALIGNMENT = 0.01
"""Metres: a block put within this of the centre of the block under it goes on top of it (a tower); further off
and it would hang over the edge and fall."""


HAND_MARGIN = 0.002
"""How near a block set down may come to a hand's parts (m)."""


def move_block(world: FetchWorld, block: str, position: np.ndarray) -> tuple[bool, str]:
    """A person's hand (an operator's intervention, the console, a scripted person): put ``block`` at ``position``
    (x, y; z is set to rest on the table, on the bin's floor inside its walls, or on top of the block or tower
    centred there). Refused off the table, half on another block, across the bin's walls, or for a block with
    another resting on it (the one on top would fall), or into a robot's hand (not the one that holds the block)."""
    if block not in world.blocks:
        return False, f"unknown block {block!r}: blocks here are {', '.join(world.blocks)}"
    xy = np.asarray(position, dtype=np.float64)[:2]
    if not np.all(np.isfinite(xy)):
        return False, "position must be finite"
    if off := _off_table(xy):
        return False, off
    snapshot = world.snapshot()
    positions = dict(zip(world.blocks, snapshot.block_positions, strict=True))
    here = positions.pop(block)
    width = 2 * BLOCK_HALF_SIZE
    if on_top := [other for other, pos in positions.items()
                  if np.linalg.norm(pos[:2] - here[:2]) < width and 0 < pos[2] - here[2] < 1.5 * width]:
        return False, f"{on_top[0]} rests on {block}: move {on_top[0]} first"
    column = {other: pos for other, pos in positions.items() if np.linalg.norm(pos[:2] - xy) < width + 0.005}
    if any(np.linalg.norm(pos[:2] - xy) > STACK_ALIGNMENT for pos in column.values()):
        other = next(o for o, pos in column.items() if np.linalg.norm(pos[:2] - xy) > STACK_ALIGNMENT)
        return False, f"({xy[0]:.3f}, {xy[1]:.3f}) is taken by {other}: put {block} on its centre or clear of it"
    rest_z, where = TABLE_TOP + BLOCK_HALF_SIZE, ""
    bin_ = world.scene.bin
    if column:
        top = max(column, key=lambda o: column[o][2])
        rest_z, where = column[top][2] + width + 0.002, f" on {top}"
    elif bin_ is not None:
        offset = np.abs(xy - np.asarray(bin_.center))
        inner = np.asarray(bin_.inner_half_size)
        outer = inner + bin_.wall_thickness + BLOCK_HALF_SIZE
        if np.all(offset <= inner - BLOCK_HALF_SIZE):  # on the bin's floor
            rest_z, where = TABLE_TOP + bin_.floor_thickness + BLOCK_HALF_SIZE, " in the bin"
        elif np.all(offset < outer):  # set there, it would cut into a wall and be thrown off the desk
            return False, (f"({xy[0]:.3f}, {xy[1]:.3f}) overlaps the bin's walls: put the block inside them "
                           f"(|x - {bin_.center[0]}| <= {inner[0] - BLOCK_HALF_SIZE:.3f}, "
                           f"|y - {bin_.center[1]}| <= {inner[1] - BLOCK_HALF_SIZE:.3f}) or clear of them")
    holder = world.holder(block)
    placed = np.array([*xy, rest_z])
    for arm in range(len(world.arms)):  # not into a hand (its own holder's fingers are around it already)
        if arm != holder and any(np.all(np.abs(centre - placed) < half + BLOCK_HALF_SIZE + HAND_MARGIN)
                                 for centre, half in world.hand_boxes(arm)):
            grip = world.hands()[arm][0]
            return False, (f"{robot_name(arm)}'s hand is at ({grip[0]:.3f}, {grip[1]:.3f}), {grip[2] - TABLE_TOP:.3f} m "
                           f"over the table: put {block} clear of it, or once it has risen")
    world.set_block_pose(block, placed)
    if holder is not None:  # taken out of the hand: the hand lets go, so it cannot close on what it held
        world.open_fingers(arm=holder)
        where += ", out of the robot's hand (the fingers opened)"
    return True, f"moved {block} to ({xy[0]:.3f}, {xy[1]:.3f}){where}"


MAX_START_HEIGHT = 0.3
"""Highest a block may start above the table top (m): a stack of the scene's blocks, and room to spare."""


def _bad_start(values: np.ndarray, blocks: int) -> str:
    """Why ``values`` (x, y, z per block, flat) cannot be a start of ``blocks`` blocks ("" when they can)."""
    if values.size != 3 * blocks:
        return f"the task has {blocks} blocks, so {3 * blocks} numbers (x, y, z each) are needed; got {values.size}"
    if not np.all(np.isfinite(values)):
        return "every number must be finite"
    for x, y, z in values.reshape(-1, 3):
        if off := _off_table(np.array([x, y])):
            return off
        if not TABLE_TOP <= z <= TABLE_TOP + MAX_START_HEIGHT:
            return f"z {z:.3f} is not between the table top {TABLE_TOP:.3f} and {MAX_START_HEIGHT} m above it"
    return ""


class SimCore:
    """One scene's world, reset to tasks by seed, stepped by checked commands."""

    def __init__(self, scene: str, task: str = "", seed: int = 0, arms: int = 1) -> None:
        if scene not in SCENES:
            raise ValueError(f"unknown scene {scene!r}: scenes are {', '.join(SCENES)}")
        self.scene, self.arms = scene, arms
        self.task = ""
        self.episode = 0
        self.ticks = 0
        """Control steps and resets since start: the sim clock (:attr:`clock_s`) runs on them, never backwards."""
        self._next_seed = seed
        self._worlds: dict[int, FetchWorld] = {}
        default_task = task or next(name for name, t in TASKS.items() if t.scene == scene)
        ok, message = self.reset(default_task, seed)
        if not ok:
            raise ValueError(message)

    @property
    def world(self) -> FetchWorld:
        return self._worlds[self._blocks]

    def reset(self, task_name: str, seed: int, positions: Sequence[float] = ()) -> tuple[bool, str]:
        """Reset to a seeded start of ``task_name`` (same scene); a negative seed takes the next one.
        ``positions``: x, y, z of each of the task's blocks, to start from instead of the seeded start (the
        goal families' starts); refused, the world unchanged, unless 3 per block, finite and over the table."""
        try:
            task = get_task(task_name or self.task)
        except KeyError as error:
            return False, str(error.args[0])
        if task.scene != self.scene:
            scene_tasks = ", ".join(n for n, t in TASKS.items() if t.scene == self.scene)
            return False, f"task {task.name} runs in scene {task.scene}, this sim is {self.scene} (tasks here: {scene_tasks})"
        given = np.asarray(positions, dtype=np.float64).reshape(-1)
        if given.size and (problem := _bad_start(given, task.n_blocks)):
            return False, f"positions refused: {problem}"
        if seed < 0:
            seed = self._next_seed
        self._next_seed = (seed + 1) % MAX_SEED  # WorldState.seed is an int64: the stream wraps, never overflows
        if task.n_blocks not in self._worlds:
            self._worlds[task.n_blocks] = FetchWorld(self.scene, task.n_blocks, self.arms)
        self._blocks = task.n_blocks
        start, self.goal = task.initial_state(seed)
        self.world.reset(given.reshape(-1, 3) if given.size else start)
        self.task, self.seed = task.name, seed
        self.episode += 1
        self.ticks += 1
        return True, f"reset to {task.name} with seed {seed}{' from the positions given' if given.size else ''}"

    def step(self, values: list[float] | np.ndarray) -> CommandCheck:
        """Check a command and, unless dropped, advance one control step (a second arm holds still)."""
        check = check_command(values)
        if check.action is not None:
            self.step_arms([check.action])
        return check

    def step_arms(self, actions: Sequence[np.ndarray]) -> None:
        """Advance one control step with one checked command per arm (:func:`check_command`)."""
        self.world.step(np.array(actions))
        self.ticks += 1

    @property
    def clock_s(self) -> float:
        """Sim time (s) for /clock and the message stamps: 0.04 s per control step (a reset counts one), across
        episodes, so it never runs backwards as an episode's own time does at a reset."""
        return self.ticks * CONTROL_DT

    def move_block(self, block: str, position: np.ndarray) -> tuple[bool, str]:
        """Operator intervention: :func:`move_block` in this world."""
        return move_block(self.world, block, position)

    def snapshot(self, arm: int = 0) -> Snapshot:
        return self.world.snapshot(arm)
