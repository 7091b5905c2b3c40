"""Scripted expert: achieves any sub-goal from any reachable state (the paper's "expert supervision").

The controller is stateless: each step it reads the world and decides what to do (approach, descend,
grasp, lift, carry, lower, release, retreat). So it recovers by itself when a block slips or a person
moves one, and it serves as an oracle and as the source of demonstrations. Where to put a block
(near, away, in the bin, ...) is chosen from the other blocks only, which stay put while it carries.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np

from semgoal_core.geometry import GRASP_OPENING, TABLE_TOP, bin_spot, clear_of, nearest
from semgoal_core.tasks import SPAWN_HIGH, SPAWN_LOW
from semgoal_core.vocabulary import BLOCK_HALF_SIZE, THRESHOLDS, BinGeometry, SubGoal, held_alone

GAIN = 15.0
"""Action per metre of position error (saturates at 1, i.e. 0.05 m per step, beyond 6.7 cm)."""
HOVER = 0.08
"""Height above a block's centre from which the gripper descends onto it (m)."""
CARRY_CLEARANCE = 0.07
"""Carried block's bottom stays this far above every other block's top (m)."""
ALIGN_XY = 0.008
ALIGN_Z = 0.008
FUNNEL_XY = 0.03
"""Within this xy distance of a block it is picking, the gripper's height follows a funnel: the block's
centre at :data:`ALIGN_XY`, :data:`HOVER` above it here, linear between: labels a centimetre apart never
say rise and descend at once, which stalled actors over blocks slightly off in xy."""
CLOSE = -1.0
RELEASE = 1.0
"""Finger command when letting go of a carried block: open fully, at once. Finger commands are metres added
to each finger's target, so anything above about +0.005 drops a held block: the +0.015 that opening to
:data:`GRASP_OPENING` takes was cloned as 0 by three_blocks actors, which hovered holding the block over
the spot while the critic rated opening higher. Wider than :data:`GRASP_OPENING`, but the
block is gone before the fingers reach a neighbour; the expert alone succeeds as often as before."""

NEAR_RANGE = (0.055, 0.093)
"""Centre distances at which put_near places a block next to its references (close: <= 0.10 m)."""
AWAY_DISTANCE = 0.16
"""Minimum distance put_away keeps from its references (m)."""
COMPACT_SLACK = 0.005
"""put_near picks among the spots whose summed distance to the references is within this of the least."""
DROP_REACH = 0.085
"""put_near lets go of the held block as soon as every reference is within this of it in the table plane:
wherever it falls, beside a reference or onto it, the centres end up close (<= 0.10 m)."""
PLACE_HEIGHT = 0.02
"""Puts let go only once the held block's bottom is at most this high (m) above what it will land on (the
table, the bin floor, a block below): it is placed, not dropped, and comes to rest within a few control
steps (a block let go 12 cm up fell for 6 to 8 steps, and the reward paid for the fall)."""
AWAY_DROP_DISTANCE = THRESHOLDS.close_distance + 0.02
"""Centre distance (m) from every other block at which put_away lets go: 2 cm beyond ``close``, as the reward
has it, not :data:`AWAY_DISTANCE` (the spot it heads for): with the latter, actors hovered between the two,
holding the block."""
BYSTANDER_CLEARANCE = THRESHOLDS.close_distance + 0.03
"""Minimum distance (m) of a put's spot from blocks it must not end up close to (put_away: every other
block; put_near: those the step keeps apart from), 1 cm beyond :data:`AWAY_DROP_DISTANCE`, so the block
may be let go on the way to it."""
TOWER_CLEARANCE = 0.12
"""Least distance (m) in the table plane of a put's table spot from a block resting on another: lowering a block
beside a tower of six, 5.5 cm off it, the hand knocked it over, and beside one of two, off the table's edge."""
SLOT_TOLERANCE = 0.02
"""put_in_bin lets go over the bin once the block is within this of its free slot (xy): a neighbour let go
that far off its own slot still leaves the next slot free (slots are 8 cm apart, blocks need 5.8)."""
DROP_CLEARANCE = 2 * BLOCK_HALF_SIZE + 0.004
"""put_in_bin lets go only where every other block's centre is this far (xy): the block falls clear of it."""


@dataclass(frozen=True)
class WorldView:
    """What the expert reads: block centres by name, the grip site, the finger opening, the bin."""

    positions: dict[str, np.ndarray]
    grip: np.ndarray
    opening: float
    bin: BinGeometry | None = None
    ceiling: float = np.inf
    """The highest the grip can go (m): a carry over a tall tower goes no higher."""

    def holds(self, block: str) -> bool:
        """``holding(block)``: the closed fingers hold it, alone."""
        names = list(self.positions)
        return bool(held_alone(np.array(list(self.positions.values())), self.grip, self.opening)[names.index(block)])

    def others(self, block: str) -> dict[str, np.ndarray]:
        return {name: pos for name, pos in self.positions.items() if name != block}


def move_to(grip: np.ndarray, target: np.ndarray, gripper: float) -> np.ndarray:
    """The action that moves the grip site toward ``target`` (saturating beyond 6.7 cm), fingers at ``gripper``."""
    return np.append(np.clip((target - grip) * GAIN, -1.0, 1.0), gripper)


def _open(world: WorldView) -> float:
    """Gripper command that opens the fingers to :data:`GRASP_OPENING` (position target = now + command)."""
    return float(np.clip((GRASP_OPENING - world.opening) / 2, -1.0, 1.0))


def _placement_candidates(step: float = 0.005) -> np.ndarray:
    xs = np.arange(SPAWN_LOW[0] - 0.05, SPAWN_HIGH[0] + 0.05 + 1e-9, step)
    ys = np.arange(SPAWN_LOW[1] - 0.05, SPAWN_HIGH[1] + 0.03 + 1e-9, step)
    return np.array(list(itertools.product(xs, ys)))


CANDIDATES = _placement_candidates()


def destination(subgoal: SubGoal, world: WorldView) -> np.ndarray | None:
    """Where the moved block's centre should come to rest for a put sub-goal; None when nowhere fits."""
    x = subgoal.block
    others = world.others(x)
    here = world.positions[x]
    rest_z = TABLE_TOP + BLOCK_HALF_SIZE
    if subgoal.kind == "put_on":
        below = others[subgoal.references[0]]
        return below + np.array([0.0, 0.0, 2 * BLOCK_HALF_SIZE])
    if subgoal.kind == "put_in_bin":
        assert world.bin is not None, "put_in_bin needs a bin"
        floor = TABLE_TOP + world.bin.floor_thickness + BLOCK_HALF_SIZE
        spot = bin_spot(world.bin, list(others.values()), here)
        return None if spot is None else np.array([*spot, floor])
    ok, spread = _table_spots(CANDIDATES, subgoal, world)
    if subgoal.kind == "put_near":
        if not ok.any():
            return None
        ok &= spread <= spread[ok].min() + COMPACT_SLACK  # the most compact spot: room for a third block
    spot = nearest(CANDIDATES, ok, here)
    return None if spot is None else np.array([*spot, rest_z])


def _table_spots(points: np.ndarray, subgoal: SubGoal, world: WorldView) -> tuple[np.ndarray, np.ndarray]:
    """Which table ``points`` (M, 2) fit ``subgoal`` (put_near, put_away, put_on_table) and, for put_near,
    their summed distance to the references (how compact the group they make is)."""
    others = world.others(subgoal.block)
    ok = clear_of(points, list(others.values()))
    towers = [p for p in others.values() if p[2] > TABLE_TOP + 2 * BLOCK_HALF_SIZE + BLOCK_HALF_SIZE]
    if towers:  # the hand coming down beside a tower brushes it over: keep well clear of its column
        ok &= np.all(np.linalg.norm(points[:, None, :] - np.array(towers)[None, :, :2], axis=2) >= TOWER_CLEARANCE, axis=1)
    if world.bin is not None:  # never on or in the bin when a table spot is asked for
        ok &= np.any(np.abs(points - np.array(world.bin.center)) > np.array(world.bin.inner_half_size) + world.bin.keep_out, axis=1)
    spread = np.zeros(len(points))
    if subgoal.kind == "put_near":
        for ref in subgoal.references:
            d = np.linalg.norm(points - others[ref][:2], axis=1)
            ok &= (d >= NEAR_RANGE[0]) & (d <= NEAR_RANGE[1])
            spread += d
        ok &= clear_of(points, [others[block] for block in subgoal.apart], BYSTANDER_CLEARANCE)
    elif subgoal.kind == "put_away":
        for ref in subgoal.references:
            ok &= np.linalg.norm(points - others[ref][:2], axis=1) >= AWAY_DISTANCE
        # far from every other block too, so moving x makes nothing else close by accident
        ok &= clear_of(points, list(others.values()), BYSTANDER_CLEARANCE)
    return ok, spread


def _funnel_height(block_z: float, xy_error: float) -> float:
    """Height to approach a block at ``xy_error`` from it (:data:`FUNNEL_XY`)."""
    share = np.clip((xy_error - ALIGN_XY) / (FUNNEL_XY - ALIGN_XY), 0.0, 1.0)
    return float(block_z + HOVER * share)


def _pick(block: str, world: WorldView) -> np.ndarray:
    target = world.positions[block]
    grip = world.grip
    if world.holds(block):  # lift clear of everything
        carry_z = max(p[2] for p in world.positions.values()) + 2 * BLOCK_HALF_SIZE + CARRY_CLEARANCE
        return move_to(grip, np.array([grip[0], grip[1], min(carry_z, world.ceiling)]), CLOSE)
    xy_error = np.linalg.norm(target[:2] - grip[:2])
    if xy_error > FUNNEL_XY:  # travel over the blocks at no less than the hover height
        safe_z = max(p[2] for p in world.positions.values()) + HOVER
        if grip[2] < safe_z - 0.02:  # rise before travelling, never sweep blocks
            return move_to(grip, np.array([grip[0], grip[1], safe_z]), _open(world))
        return move_to(grip, np.array([target[0], target[1], max(target[2] + HOVER, min(grip[2], safe_z))]), _open(world))
    if xy_error > ALIGN_XY:
        return move_to(grip, np.array([target[0], target[1], _funnel_height(target[2], xy_error)]), _open(world))
    if abs(grip[2] - target[2]) > ALIGN_Z:  # above the block: descend; low on it: rise (a grasp there
        if world.opening < GRASP_OPENING - 0.006:  # pinches the block below too), opening first either way
            return move_to(grip, np.array([target[0], target[1], grip[2]]), _open(world))
        return move_to(grip, target, _open(world))
    return move_to(grip, target, CLOSE)


def _place(subgoal: SubGoal, spot: np.ndarray, world: WorldView) -> np.ndarray:
    x = subgoal.block
    grip, block = world.grip, world.positions[x]
    offset = grip - block  # keep the block where it sits in the hand
    release = spot + offset + np.array([0.0, 0.0, 0.004])
    obstacles = [p[2] for n, p in world.others(x).items()] or [TABLE_TOP]
    carry_z = min(max(max(obstacles) + 2 * BLOCK_HALF_SIZE + CARRY_CLEARANCE, spot[2] + 0.02) + offset[2], world.ceiling)
    xy_error = np.linalg.norm(spot[:2] - block[:2])
    if xy_error > ALIGN_XY:
        if grip[2] < carry_z - 0.02 and xy_error > 0.02:
            return move_to(grip, np.array([grip[0], grip[1], carry_z]), CLOSE)
        return move_to(grip, np.array([release[0], release[1], max(carry_z, release[2])]), CLOSE)
    if grip[2] - release[2] > ALIGN_Z:
        return move_to(grip, release, CLOSE)
    return move_to(grip, release, _open(world))


def _support_top(x: str, world: WorldView) -> float:
    """Height (m) of what the block ``x`` lands on if let go now: the highest of the table top, the bin floor
    under it and the top of any other block under its footprint."""
    block = world.positions[x]
    tops = [TABLE_TOP]
    if world.bin is not None and np.all(np.abs(block[:2] - np.asarray(world.bin.center)) < world.bin.inner_half_size):
        tops.append(TABLE_TOP + world.bin.floor_thickness)
    tops += [p[2] + BLOCK_HALF_SIZE for p in world.others(x).values()
             if np.all(np.abs(p[:2] - block[:2]) < 2 * BLOCK_HALF_SIZE)]
    return max(tops)


def _let_go_or_lower(x: str, world: WorldView, spot: np.ndarray | None) -> np.ndarray:
    """Let go where the block is low enough over what it lands on (:data:`PLACE_HEIGHT`); else lower it,
    carrying on toward ``spot`` (its destination, if any) in the table plane."""
    block = world.positions[x]
    excess = block[2] - BLOCK_HALF_SIZE - _support_top(x, world) - PLACE_HEIGHT
    if excess <= 0:
        return move_to(world.grip, world.grip, RELEASE)
    target = world.grip - np.array([0.0, 0.0, excess + 0.005])
    if spot is not None:
        target[:2] += spot[:2] - block[:2]
    return move_to(world.grip, target, CLOSE)


def _within_drop_reach(subgoal: SubGoal, world: WorldView) -> bool:
    """put_near: every reference is within :data:`DROP_REACH` and every block to keep apart from beyond
    :data:`AWAY_DROP_DISTANCE`, so letting go here achieves it."""
    x, others = world.positions[subgoal.block], world.others(subgoal.block)
    return (all(np.linalg.norm(x[:2] - others[ref][:2]) <= DROP_REACH for ref in subgoal.references)
            and all(np.linalg.norm(x[:2] - others[block][:2]) >= AWAY_DROP_DISTANCE for block in subgoal.apart))


def _away_drop_holds(subgoal: SubGoal, world: WorldView) -> bool:
    """put_away: the block is far enough from every other block (:data:`AWAY_DROP_DISTANCE`) that placing it
    here achieves it, on the table, not on a block."""
    block = world.positions[subgoal.block]
    return bool(clear_of(block[None, :2], list(world.others(subgoal.block).values()), AWAY_DROP_DISTANCE)[0])


def _over_slot(subgoal: SubGoal, slot: np.ndarray, world: WorldView) -> bool:
    """put_in_bin: the block is inside the walls, within :data:`SLOT_TOLERANCE` of its free ``slot`` and
    :data:`DROP_CLEARANCE` from every other block, so it falls onto the floor, not onto a neighbour."""
    block, bin_geometry = world.positions[subgoal.block], world.bin
    inner = np.asarray(bin_geometry.inner_half_size) - BLOCK_HALF_SIZE
    inside = np.all(np.abs(block[:2] - np.asarray(bin_geometry.center)) <= inner)
    clear = all(np.linalg.norm(block[:2] - other[:2]) >= DROP_CLEARANCE for other in world.others(subgoal.block).values())
    return bool(inside and clear and np.linalg.norm(slot[:2] - block[:2]) <= SLOT_TOLERANCE)


def _back_off(block: str, world: WorldView) -> np.ndarray:
    """Once a put holds: raise the open fingers clear above the block, so the put stays achieved."""
    clear_z = world.positions[block][2] + HOVER
    return move_to(world.grip, np.array([world.grip[0], world.grip[1], max(world.grip[2], clear_z)]), _open(world))


def expert_action(subgoal: SubGoal, world: WorldView, achieved: bool = False) -> np.ndarray:
    """The expert's 4-D action for ``subgoal`` in ``world``.

    :param achieved: the sub-goal's literals hold now. The expert then keeps them so (a pick lifts the
        block, a put backs away from it) instead of starting over: as demonstrations and cloning labels,
        the steps after success must teach staying done, not undoing it.
    """
    x = subgoal.block
    if subgoal.kind == "pick":
        return _pick(x, world)
    if achieved:
        return _back_off(x, world)
    if not world.holds(x):
        return _pick(x, world)
    # Place the block as soon as the put will hold once it rests there, not after carrying it on to the
    # exact spot: cloning froze actors holding a block where letting go would have done
    # (``docs/history.md``). It is lowered first (:data:`PLACE_HEIGHT`), never dropped.
    spot = destination(subgoal, world)
    if ((subgoal.kind == "put_near" and _within_drop_reach(subgoal, world))
            or (subgoal.kind == "put_away" and _away_drop_holds(subgoal, world))
            or (subgoal.kind == "put_in_bin" and spot is not None and _over_slot(subgoal, spot, world))):
        return _let_go_or_lower(x, world, spot)
    if spot is None:  # nowhere to put it: hold still and wait for the world to change
        return np.array([0.0, 0.0, 0.0, CLOSE])
    return _place(subgoal, spot, world)
