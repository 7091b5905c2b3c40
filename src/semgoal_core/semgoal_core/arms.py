"""The robot arms at one table: their names, their ROS namespaces, and the frame each sees the world in. No MuJoCo.

The second Fetch stands across the table from the first, turned half a turn about the vertical
(``semgoal_sim.scene``). The table and the bin are symmetric under the reflection ``x -> 2 * TABLE_CENTER[0] - x``,
and so is the gripper, pointing down with its fingers along y, up to swapping its two fingers. So the second arm,
seen through that reflection, is the first arm in the same world: the shipped actor drives it unchanged, its
observation reflected in (:meth:`ArmFrame.observation`) and its command reflected out (:meth:`ArmFrame.action`).
A reflection rather than the half turn itself: the half turn would show it the bin (which stands at the table's far
edge in y) at the near edge, where the actor never saw it.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from semgoal_core import layout
from semgoal_core.geometry import TABLE_CENTER, TABLE_TOP
from semgoal_core.names import Assignee
from semgoal_core.vocabulary import BLOCK_HALF_SIZE, held_alone

MAX_ARMS = 2
MIRROR_X = TABLE_CENTER[0]
"""The second arm's frame reflects x about the table's centre line."""
PARK = np.array([TABLE_CENTER[0] - 0.2, TABLE_CENTER[1], 0.55])
"""Where an arm with nothing to do and an empty hand waits on a shared table, in its own frame (m): over its own
edge of the table, above the blocks, 40 cm from the other arm's park spot."""
REACH_PAST_CENTRE = 0.08
"""How far (m) past the table's centre line, into the other arm's half, an arm takes a block."""


def robot_name(arm: int) -> str:
    """The agent name of arm ``arm`` (0-based) in plans: ``robot``, then ``robot:2``."""
    return Assignee.ROBOT.value if arm == 0 else f"{Assignee.ROBOT}:{arm + 1}"


def robot_names(arms: int) -> tuple[str, ...]:
    return tuple(robot_name(arm) for arm in range(arms))


def arm_of(name: str) -> int:
    """The 0-based arm of a robot's agent name; ValueError for anything else."""
    if name == Assignee.ROBOT:
        return 0
    number = name.removeprefix(f"{Assignee.ROBOT}:")
    if number == name or not number.isdigit() or not 2 <= int(number) <= MAX_ARMS:
        raise ValueError(f"a robot arm is 'robot' or 'robot:2', got {name!r}")
    return int(number) - 1


def arms_for(position: np.ndarray, arms: int) -> tuple[int, ...]:
    """The arms that take a block at ``position`` (world, m), the nearer first: each works its own half of the table,
    and :data:`REACH_PAST_CENTRE` beyond it."""
    if arms == 1:
        return (0,)
    offset = float(position[0]) - MIRROR_X
    near, far = (0, 1) if offset < 0 else (1, 0)
    return (near, far) if abs(offset) <= REACH_PAST_CENTRE else (near,)


def holder_of(block: int, positions: np.ndarray, hands: list[tuple[np.ndarray, float]]) -> int | None:
    """The arm whose hand holds block ``block`` of ``positions`` (N, 3), by ``holding``'s geometry; ``hands``: each
    arm's grip position and finger opening. None when no hand holds it."""
    return next((arm for arm, (grip, opening) in enumerate(hands) if held_alone(positions, grip, opening)[block]), None)


def takers(block: int, positions: np.ndarray, hands: list[tuple[np.ndarray, float]]) -> tuple[int, ...]:
    """The arms that may take a robot's step on block ``block``, the nearer first: the arm that holds it (a put after
    a re-plan goes to the hand the block is in), else :func:`arms_for`."""
    holder = holder_of(block, positions, hands)
    return (holder,) if holder is not None else arms_for(positions[block], len(hands))


def arm_namespace(arm: int) -> str:
    """The ROS namespace of arm ``arm``'s own topics and nodes under ``/semgoal``: none for the first, ``robot2``."""
    return "" if arm == 0 else f"robot{arm + 1}"


@dataclass(frozen=True)
class ArmFrame:
    """How arm ``arm`` sees the world: as it is (the first arm) or reflected about :data:`MIRROR_X` (the second)."""

    scene: str
    arm: int = 0

    @property
    def mirrored(self) -> bool:
        return self.arm % 2 == 1

    def positions(self, points: np.ndarray) -> np.ndarray:
        """World points (..., 3) in this arm's frame (a reflection is its own inverse: also back)."""
        points = np.array(points, dtype=np.float64)
        if self.mirrored:
            points[..., 0] = 2 * MIRROR_X - points[..., 0]
        return points

    def observation(self, observation: np.ndarray) -> np.ndarray:
        """A world-frame observation (:mod:`semgoal_core.layout`) as this arm sees it: x of positions reflected,
        x of velocities and offsets negated, the fingers swapped; absent block slots stay zero."""
        if not self.mirrored:
            return observation
        obs = np.array(observation, dtype=np.float32)
        obs[0] = 2 * MIRROR_X - obs[0]
        obs[3] = -obs[3]
        obs[6:8], obs[8:10] = obs[7:5:-1].copy(), obs[9:7:-1].copy()
        blocks = obs[layout.ARM_SIZE:layout.observation_size(self.scene)].reshape(-1, layout.BLOCK_SIZE)
        present = blocks[:, layout.BLOCK_SLICE["present"]][:, 0] > 0.5
        for feature in ("position", "relative_position", "velocity"):
            column = blocks[:, layout.BLOCK_SLICE[feature].start]
            column[:] = -column
        blocks[present, layout.BLOCK_SLICE["position"].start] += 2 * MIRROR_X
        return obs

    def action(self, action: np.ndarray) -> np.ndarray:
        """A command in this arm's frame as the world takes it: the x displacement reflected back."""
        if not self.mirrored:
            return action
        action = np.array(action, dtype=np.float32)
        action[0] = -action[0]
        return action


def arm_observation(scene: str, grip: np.ndarray, grip_velocity: np.ndarray, finger_positions: np.ndarray,
                    finger_velocities: np.ndarray, positions: np.ndarray, velocities: np.ndarray,
                    other_hands: Sequence[tuple[np.ndarray, float]] = ()) -> np.ndarray:
    """The policy observation of one arm's hand, in the world frame (:mod:`semgoal_core.layout`; ``positions`` and
    ``velocities`` of the scene's blocks present). A block in another arm's hand is shown at rest on the table under
    it: the actor never saw a block hang in the air in no hand of its own (shown there, one made the first arm let go
    of its own; left out, too), and it is an obstacle where it will be put down."""
    for other, opening in other_hands:
        held = held_alone(positions, other, opening)
        if held.any():
            positions, velocities = np.array(positions, dtype=float), np.array(velocities, dtype=float)
            positions[held, 2], velocities[held] = TABLE_TOP + BLOCK_HALF_SIZE, 0.0
    return layout.observation(scene, grip, grip_velocity, finger_positions, finger_velocities, positions, velocities)
