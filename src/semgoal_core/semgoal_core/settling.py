"""When a goal or sub-goal counts as achieved: its literals hold **with the world at rest**. No MuJoCo.

One rule for the executive (goals and plan steps), the policy node, the training reward and HER, the
sub-goal and task evaluations and the expert's rollouts. A block in free fall can satisfy ``close``
(by height) or ``not in_bin`` (above the rim) for a few steps; counting such a state made a dropped
block a success that no longer held a second later.

The world is at rest when no block is *restless*: a block is restless when its linear speed is at least
:data:`REST_SPEED`, or when it is in the hand although the literals do not ask for it to be held. A block
the literals ask to be held moves with the arm and is exempt. The state must last :data:`SETTLE_STEPS`
control steps in a row (:class:`Settling`).
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import numpy as np

from semgoal_core.layout import goal_reward
from semgoal_core.vocabulary import Literal, SemanticLayout

REST_SPEED = 0.02
"""A block slower than this (m/s, linear) is still. Resting blocks measure about 2e-9 m/s; a block let go
2 cm over the table stays at or above it for 3 control steps, 5 cm up for 4, 12 cm up for 6
(``semgoal_bench/rest_speeds.py``), so a falling or sliding block never passes."""
SETTLE_STEPS = 5
"""Consecutive control steps (0.2 s) the literals must hold at rest: the planner's sub-goal confirmation
(``SUBGOAL_CONFIRM_STEPS``), which a grasp that only brushes a block's top edge does not pass either."""


def held_blocks_asked(literals: Iterable[Literal]) -> set[str]:
    """The blocks the literals ask to be held (``holding(x)`` true): they may move with the arm."""
    return {lit.args[0] for lit in literals if lit.name == "holding" and lit.value}


HER_REPLAY_KWARGS = {"copy_info_dict": True}
"""What Stable-Baselines3's ``HerReplayBuffer`` needs (``replay_buffer_kwargs``) to relabel at rest: by
default it hands ``compute_reward`` empty info dicts, and rest cannot be judged from goals alone."""


def info_motion(info: dict | Sequence[dict]) -> np.ndarray:
    """The motion bits of a step's info dict, or of a sequence of them (as Stable-Baselines3's HER passes).

    :raises ValueError: an info lacks ``motion``, saying how to keep it (:data:`HER_REPLAY_KWARGS`).
    """
    infos = [info] if isinstance(info, dict) else list(info)
    if any("motion" not in i for i in infos):
        raise ValueError(
            "compute_reward needs each step's info['motion'] to judge the world at rest; with "
            "Stable-Baselines3's HerReplayBuffer pass replay_buffer_kwargs={'copy_info_dict': True} "
            "(semgoal_core.settling.HER_REPLAY_KWARGS) so that it keeps the infos")
    motion = np.asarray([i["motion"] for i in infos])
    return motion[0] if isinstance(info, dict) else motion


def restless(moving: np.ndarray, held: np.ndarray, asked: np.ndarray) -> np.ndarray:
    """Which blocks keep the world from being at rest, vectorised over leading axes.

    :param moving: (..., N) bool, the block's linear speed is at least :data:`REST_SPEED`.
    :param held: (..., N) bool, ``holding`` holds for the block.
    :param asked: (..., N) bool, the literals ask for the block to be held.
    """
    return (moving | held) & ~(held & asked)


def moving_blocks(names: Sequence[str], velocities: np.ndarray) -> tuple[str, ...]:
    """The blocks among ``names`` whose linear speed (``velocities`` (N, >=3), m/s) is at least :data:`REST_SPEED`."""
    speeds = np.linalg.norm(np.asarray(velocities, dtype=np.float64)[:, :3], axis=1)
    return tuple(name for name, speed in zip(names, speeds, strict=True) if speed >= REST_SPEED)


def at_rest(literals: Iterable[Literal], moving: Iterable[str], held: Iterable[str]) -> bool:
    """Whether the world is at rest for ``literals``: no block moving or in the hand, except one asked to be held."""
    asked = held_blocks_asked(literals)
    return not ((set(moving) | set(held)) - asked)


class MotionReward:
    """The sparse semantic reward at rest, for training and HER relabelling.

    ``motion`` is what :func:`motion_bits` stores per step: whether each block slot moves and whether it is
    held. Which held blocks are exempt is read from the (possibly relabelled) goal's ``holding`` entries.
    """

    def __init__(self, layout: SemanticLayout) -> None:
        entries, args = layout.groundings["holding"]
        self.size = layout.size
        self.holding_entries = entries[np.argsort(args[:, 0])]
        """Vector entry of ``holding(block)`` for each block slot, in object order."""

    def asked(self, goal: np.ndarray) -> np.ndarray:
        """(..., N) bool: the goal asks for each block slot to be held."""
        target, mask = goal[..., : self.size], goal[..., self.size:]
        return (target[..., self.holding_entries] > 0.5) & (mask[..., self.holding_entries] > 0.5)

    def __call__(self, achieved: np.ndarray, desired: np.ndarray, motion: np.ndarray) -> np.ndarray:
        """The reward: 1 where every masked literal matches and the world is at rest, vectorised."""
        return goal_reward(achieved, desired) * self.settled(desired, motion)

    def settled(self, goal: np.ndarray, motion: np.ndarray) -> np.ndarray:
        """(...,) bool: no restless block under ``goal``; ``motion`` (..., 2N) is moving then held."""
        return self.at_rest(self.asked(goal), motion)

    @staticmethod
    def at_rest(asked: np.ndarray, motion: np.ndarray) -> np.ndarray:
        """:meth:`settled` with the goal's :meth:`asked` blocks worked out already (a sub-goal's, once)."""
        slots = motion.shape[-1] // 2
        moving, held = motion[..., :slots] > 0.5, motion[..., slots:] > 0.5
        return ~restless(moving, held, asked).any(axis=-1)


def motion_bits(speeds: np.ndarray, held: np.ndarray, slots: int) -> np.ndarray:
    """(2 * slots,) float32: per block slot, moving (speed >= :data:`REST_SPEED`) then held; absent slots 0."""
    bits = np.zeros(2 * slots, dtype=np.float32)
    count = len(speeds)
    bits[:count] = np.asarray(speeds) >= REST_SPEED
    bits[slots: slots + count] = np.asarray(held[:count], dtype=bool)
    return bits


@dataclass
class Settling:
    """Counts the consecutive control steps over which literals held at rest; kept by the executive (for
    the goal and for the active step), the policy node and every evaluation."""

    steps: int = SETTLE_STEPS
    since: int | None = None
    """First step of the current run of steps in which the literals held at rest."""

    def update(self, holds: bool, step: int, now: int | None = None) -> bool:
        """Record whether the literals hold at rest at ``step``; True once they did from ``since`` up to
        ``now`` (default ``step``)."""
        if not holds:
            self.since = None
            return False
        if self.since is None:
            self.since = step
        return (step if now is None else now) - self.since + 1 >= self.steps

    def reset(self) -> None:
        self.since = None

    @property
    def pending(self) -> bool:
        return self.since is not None
