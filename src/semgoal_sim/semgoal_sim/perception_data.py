"""Labelled camera frames for training and measuring the perception: the expert works a set of tasks (the paper's
eight, or the tabletop's) while the camera records, under a randomised look per episode. Labels come from the
simulator (block centres, per-pixel block ids); nothing here is seen by the perception at run time.

Seeds: frames of seed S come from task starts ``S + episode``; training uses S = 8,000,000 (the tabletop's
8,700,000) and accuracy measurements S = 9,000,000 (the tabletop's 9,700,000), ranges no policy training or
evaluation draws from (``docs/perception.md``).
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass

import numpy as np

from semgoal_core.tasks import ALL_TASKS, TASKS, get_task
from semgoal_core.vocabulary import BLOCK_COLOURS
from semgoal_sim.camera import CONDITIONS, Appearance, Frame, RgbdCamera
from semgoal_sim.rollout import expert_controller, expert_next_steps, run_subgoal
from semgoal_sim.world import FetchWorld, Snapshot

TRAINING_SEED = 8_000_000
MEASUREMENT_SEED = 9_000_000
TABLETOP_MEASUREMENT_SEED = 9_700_000
FRAME_TASKS: tuple[str, ...] = tuple(ALL_TASKS)
"""Every task a frame may come from: a frame's ``task`` is its index here."""
FRAMES_PER_EPISODE = 6
MAX_SUBGOALS = 4


@dataclass
class LabelledFrames:
    """N frames as stacked arrays (what ``train-perception`` saves and loads)."""

    rgb: np.ndarray  # (N, H, W, 3) uint8
    depth: np.ndarray  # (N, H, W) float32, metres, 0 = no return
    labels: np.ndarray  # (N, H, W) int8, 0 = no block, k + 1 = colour k
    camera: np.ndarray  # (N, 4): fx, fy, cx, cy (pixels)
    world_from_camera: np.ndarray  # (N, 4, 4)
    centres: np.ndarray  # (N, colours, 3) block centres, NaN for a colour not in the scene
    speeds: np.ndarray  # (N, colours) block linear speeds (m/s), NaN for a colour not in the scene
    grip: np.ndarray  # (N, 4) grip site position and finger opening
    task: np.ndarray  # (N,) task index in FRAME_TASKS

    def save(self, path) -> None:
        np.savez_compressed(path, **self.__dict__)

    @classmethod
    def load(cls, path) -> LabelledFrames:
        with np.load(path) as data:
            return cls(**{name: data[name] for name in cls.__dataclass_fields__})

    def tasks(self) -> list:
        """Each frame's task."""
        return [get_task(FRAME_TASKS[t]) for t in self.task]

    def where(self, keep: np.ndarray) -> LabelledFrames:
        """The frames ``keep`` (a mask or indices) selects."""
        return LabelledFrames(**{name: getattr(self, name)[keep] for name in self.__dataclass_fields__})


def _episode_frames(task_name: str, seed: int, appearance: Appearance, camera_size: tuple[int, int],
                    rng: np.random.Generator) -> Iterator[tuple]:
    task = get_task(task_name)
    world = FetchWorld(task.scene, task.n_blocks)
    positions, goal = task.initial_state(seed)
    world.reset(positions)
    camera = RgbdCamera(world, *camera_size)
    camera.set_appearance(appearance, noise_seed=seed)
    total = int(rng.integers(40, 60 * 2 * MAX_SUBGOALS))
    chosen = set(rng.choice(total, size=FRAMES_PER_EPISODE, replace=False).tolist())
    step = 0
    frames = []

    def record() -> None:
        nonlocal step
        if step in chosen:
            frames.append((camera.frame(labels=True), world.snapshot()))
        step += 1

    def recording(subgoal, w: FetchWorld) -> np.ndarray:
        record()
        return expert_controller(subgoal, w)

    for _ in range(MAX_SUBGOALS):
        plan = expert_next_steps(goal, world.layout, world.semantic_vector(), world.view())
        if not plan or step >= total:
            break
        for subgoal in plan:
            run_subgoal(world, subgoal, recording)
    while step < total:  # the goal held early: the arm still, the blocks at rest
        record()
        world.step(np.zeros(4))
    camera.close()
    for frame, snapshot in frames:
        yield frame_row(frame, snapshot, [appearance.painted(block) for block in world.blocks])


def frame_row(frame: Frame, snapshot: Snapshot, blocks: Sequence[str]) -> tuple:
    """A labelled frame as one row of :class:`LabelledFrames` (all but its task): the picture, its labels, and the
    blocks' centres and speeds and the first arm's grip and opening from the world's ``snapshot`` at that step;
    ``blocks`` names the world's blocks in order by the colour each looks in the frame."""
    colours = list(BLOCK_COLOURS)
    centres, speeds = np.full((len(colours), 3), np.nan), np.full(len(colours), np.nan)
    for block, position, velocity in zip(blocks, snapshot.block_positions, snapshot.block_velocities, strict=True):
        centres[colours.index(block)] = position
        speeds[colours.index(block)] = np.linalg.norm(velocity[:3])
    k = frame.intrinsics
    return (frame.rgb, frame.depth, frame.labels, np.array([k.fx, k.fy, k.cx, k.cy]), frame.world_from_camera,
            centres, speeds, np.append(snapshot.grip_position, snapshot.finger_opening))


def stack_rows(rows: list[tuple]) -> LabelledFrames:
    """Rows of :func:`frame_row`, each with its task index last, as stacked arrays."""
    return LabelledFrames(*(np.stack([row[i] for row in rows]) for i in range(9)))


def labelled_frames(count: int, seed: int = TRAINING_SEED, camera_size: tuple[int, int] = (160, 120),
                    strength: float = 1.0, condition: str = "nominal", progress: bool = False,
                    tasks: Sequence[str] = tuple(TASKS), repaint: bool = False) -> LabelledFrames:
    """``count`` labelled frames from episodes of each of ``tasks`` in turn, starts ``seed + episode``; the look is
    the named ``condition`` (``semgoal_sim.camera.CONDITIONS``), randomised around its camera placement
    when ``strength`` > 0, with the blocks' colours shuffled per episode when ``repaint`` is also set."""
    from tqdm import tqdm

    rows: list[tuple] = []
    bar = tqdm(total=count, desc="rendering labelled frames", unit="frame", disable=not progress)
    episode = 0
    while len(rows) < count:
        task_name = tasks[episode % len(tasks)]
        rng = np.random.default_rng([seed, episode])
        look = CONDITIONS[condition]
        appearance = Appearance.randomised(rng, strength, look.placement, repaint) if strength > 0 else look
        for row in _episode_frames(task_name, seed + episode, appearance, camera_size, rng):
            rows.append((*row, FRAME_TASKS.index(task_name)))
            bar.update(1)
        episode += 1
    bar.close()
    return stack_rows(rows[:count])
