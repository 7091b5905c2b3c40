"""The policy's run-time core (no ROS): observation + active sub-goal -> a safe arm command."""

from __future__ import annotations

from collections.abc import Iterable
from enum import StrEnum
from pathlib import Path

import numpy as np

from semgoal_core import features, layout
from semgoal_core.arms import PARK, ArmFrame
from semgoal_core.expert import AWAY_DROP_DISTANCE, DROP_REACH, HOVER
from semgoal_core.geometry import FINGER_HALF_WIDTH, FINGER_OUTER_FACE, TABLE_CENTER, TABLE_HALF_SIZE, TABLE_TOP
from semgoal_core.settling import REST_SPEED, Settling, at_rest
from semgoal_core.vocabulary import (
    BLOCK_HALF_SIZE,
    LAYOUTS,
    SCENES,
    THRESHOLDS,
    Literal,
    SubGoal,
    VocabularyError,
    held_alone,
    rests_on,
    subgoal_of,
)
from semgoal_policy import actor as actor_io

HOLD = np.zeros(4, dtype=np.float32)
"""Zero displacement and finger targets at their current positions: the arm holds still."""
HOLD_GRIP = np.array([0.0, 0.0, 0.0, -1.0], dtype=np.float32)
"""The arm holds still and the fingers keep squeezing: a held block is kept, not let slip (a pause
dropped the held block)."""


RETREAT_OPENING = THRESHOLDS.holding_opening_max + 0.006
"""Finger opening (m) the idle arm keeps at least: past what ``holding`` reads, so a block let go of is never
held again (the fingers left at rest drift shut, from 52-61 mm to 48 mm in 25 steps, and ``holding`` read
true again), and no wider, so fingers beside a tower's block do not push it."""
RETREAT_HEIGHT = 0.08
"""How far (m) above the highest block's centre the idle arm's grip site goes: the fingertips clear every block
(the expert descends onto a block from this height) and ``holding``'s 0.04 m reach."""
ROOM_HEIGHT = RETREAT_HEIGHT + 2 * BLOCK_HALF_SIZE
"""How far (m) above the highest block's centre an empty hand goes on another's turn: as far over one more block
put on the highest (at 0.166 m over a tower of two, a person's block put on it was refused, or read as held)."""
EDGE_MARGIN = 0.045
"""A held block is let go only with its centre this far (m) inside the table's edge: 2 cm past its half-size. Let
go nearer, a block still sliding went over (held-out chains: put away at y 0.397, 3 mm inside the edge)."""
EDGE_NUDGE = 0.2
"""Least inward displacement command (1 cm a step) for a held block beyond :data:`EDGE_MARGIN`."""
WALL_MARGIN = 0.005
"""A block on its way into the bin is let go only with its centre this far (m) inside the bin's inner walls: let go
over a wall, it landed on it and tipped out (tabletop Clean-6, start 3,000,015: at x 1.50 over the far wall at 1.48,
it fell off the table's edge behind)."""
WALL_CLEARANCE = 0.02
"""How far (m) over a bin wall's top a held block's bottom stays while its footprint meets the wall's: a block swings
up to 1 cm in the hand."""
RETREAT_GAIN = 15.0
"""Displacement command per metre from the retreat height (saturates beyond 6.7 cm, as the expert's)."""
SEATED_DEPTH = 0.02
"""How far (m) below the grip site a kept block's centre may hang: deeper, the fingertips hold less than 2.4 cm of
its top (a block 2.5-3.9 cm under the grip site was confirmed held, then the squeezing fingers slid up off it)."""
SEATING_CLEARANCE = 0.09
"""A grasp is seated only with no other block's centre this near (m) in the table plane: fingers coming down
beside a neighbour pressed it and lifted its edge."""
SEATING_SPEED = 0.15
"""Downward command (5 mm a step) that seats a shallow grasp: the hand comes down, squeezing, until the block
rests on what is under it and the fingers slide down its sides."""
STRADDLE_HEIGHT = 0.06
"""An open hand's grip site less than this (m) above a block's centre still has its fingertips beside the block."""
PALM_HEIGHT = 0.074
"""How far (m) above the grip site the gripper's palm begins (the gripper link's mesh in the MJCF)."""
PALM_REACH = 0.063 + BLOCK_HALF_SIZE * np.sqrt(2) + 0.005
"""How near (m, along x or y) a block's centre may be to the grip site for the palm, 12.6 cm wide, to meet it: its
half width, a turned block's half diagonal and 5 mm to spare."""
SEATED_HEIGHT = 2 * BLOCK_HALF_SIZE
"""A block seated on another: its centre this far (m) over the other's."""
LANDING_HEIGHT = 0.03
"""A held block over the block it is put on comes down slowly from this high (m) over its seat."""
LANDING_SPEED = 0.1
"""Downward command (5 mm a step) a held block lands at on the block it is put on."""
RELEASE_XY = 0.006
"""A block put on another is let go only this near (m) its centre, in the table's plane (1 cm: Tower-6 86 % on the
starts from 3,000,000, 6 mm: 90 %)."""
RELEASE_HEIGHT = 0.008
"""... and only this near (m) its seat."""
PALM_CLEARANCE = 0.005
"""How far (m) above a stack's top the palm stays."""
GRASP_HEIGHT = 0.015
"""The highest (m) over the centre of a block on a stack at which the fingers close on it (the expert's within 8 mm)."""
CENTRING_SPEED = 0.1
"""The fastest (5 mm a step) the hand moves toward a stacked block's centre with its fingertips beside it: the
expert aligns there before it closes, and held still it never did."""
LIFT_CLEARANCE = 0.02
"""A block picked off a stack rises this far (m) over the block below before the hand moves sideways."""
FINGER_TIP = 0.0185
"""How far (m) the fingertips reach below the grip site (the Fetch gripper's finger boxes, in the MJCF)."""
FINGER_LENGTH = 0.077
"""A finger's length (m) from its tip up."""
FINGER_CLEARANCE = 0.0021
"""Room (m) an opening finger's outer face leaves to a block beside it."""
STACK_CLEARANCE = 0.02
"""Room (m) a held block keeps from a stack's footprint as it comes down beside it: blocks turned in the hand or in
the stack reach up to 1 cm beyond their square."""
PALM_FOOTPRINT = np.array([0.0414, 0.0631]) + BLOCK_HALF_SIZE + 0.01
"""How near (m, along x and along y) a block's centre may be to the grip site for the gripper's palm to meet it: the
gripper link's half extents in the table plane (the box around its mesh, 8.3 by 12.6 cm), a block's half size and 1 cm
to spare (with 5 mm, the hand coming down at full speed still grazed a tower)."""
PALM_BOTTOM = 0.051
"""How far (m) above the grip site the box around the gripper link's mesh begins: a tower's top block 1.7 cm above
the mesh's lowest point (:data:`PALM_HEIGHT`) was struck."""
PICK_SHIFT = np.array([0.018, 0.022])
"""How far (m, along x and along y) off a block's centre an empty hand may come down to pick it: the fingers (2.7 cm
wide) still close on its 5 cm face, and, opened fully (11 cm), still pass it on both sides."""
APPROACH_HEIGHT = 0.03
"""How far (m) over a stack's top the palm comes on the actor's own before the hand goes to its shifted pick point."""
SHIFT_TOLERANCE = 0.003
"""How near (m) the hand must be to its shifted pick point before it comes down past a stack."""
LET_GO_SPEED = 0.1
"""The fastest (m/s, 4 mm a step) the hand may move in the table's plane as it lets go of a block put near others or
into the bin: let go at 0.2-0.5 m/s within 5-7 cm of its references, blocks slid on to 10.2-11.5 cm, past ``close``."""
NEAR_AIM = 0.07
"""Where :func:`let_go_within_reach` brings a held block too far from one it is put near: this far from it (m)."""
APART_AIM = AWAY_DROP_DISTANCE + 0.005
"""Where :func:`let_go_within_reach` brings a held block too near one it stays apart from: this far from it (m)."""
STEER_SPEED = 0.5
"""The largest command (a fraction of the arm's 5 cm a step) with which a rule moves a held block to where it may be
let go."""
FOOTPRINT_CLEARANCE = 2 * BLOCK_HALF_SIZE + 0.004
"""How far apart (m) along the table's x or y a held block is let go from a block below it, where it is as near along
the other: nearer, their footprints overlap and it lands on that block's corner (:func:`let_go_within_reach`)."""
CLOSING_OFFSET = PICK_SHIFT[0] + 0.003
"""How far (m) off a block's centre across the fingers' width (the arm's x) an empty hand may close on it: the
fingers, 2.7 cm wide, still hold 1.7 cm of its 5 cm face, and a pick shifted past a stack (:data:`PICK_SHIFT`) still
closes."""
SLIDE_DISTANCE = 0.07
"""Where a block let go over one block's side, its centre beyond that side, comes to rest: this far (m) from that
block's centre along the axis it overlaps less (it tips off and slides; 6.9-7.6 cm traced, tabletop put near, starts
2,110,003, 2,110,128 and 2,110,160)."""
STEER_MIN = 0.002
"""The least move (m) for which :func:`let_go_within_reach` holds a block back: a smaller one, where its pulls cancel,
lets it go."""

ACTION_MODES = ("sample", "mean")
"""How the actor acts: ``sample`` draws from SAC's Gaussian policy (noise keyed by the task seed and the
step, so runs are reproducible and the graph and in-process evaluation act alike), ``mean`` takes its
mean. Sampling is the default: the deterministic mean can hover in place for good (MC-2, task seeds
3000000+: 10 of 12 solved with the mean, 12 of 12 sampled)."""


def kept_on_the_table(scene: str, observation: np.ndarray, action: np.ndarray) -> np.ndarray:
    """An actor's command (in the arm's own frame), except that a held block beyond :data:`EDGE_MARGIN` of the table's
    edge, over no other block, is not let go and is moved back inward: no block leaves the table by the robot's hand
    where the actor aims too far. The policy node applies it (:class:`SubgoalController`), and so can an evaluation of
    the actor alone (``eval subgoals --shields``)."""
    held = held_slots(scene, observation)
    if not held.any():
        return action
    blocks = layout.block_slots(scene, observation)
    block = blocks["position"][held][0]
    others = blocks["position"][(blocks["present"][:, 0] > 0.5) & ~held]
    if (np.linalg.norm(others[:, :2] - block[:2], axis=1) < THRESHOLDS.above_xy).any():
        return action  # over another block: a put on it, which holds it up (a tower at the edge stays allowed)
    offset = block[:2] - np.asarray(TABLE_CENTER)
    out = np.abs(offset) > np.asarray(TABLE_HALF_SIZE) - EDGE_MARGIN
    return _held_back(action, offset, out) if out.any() else action


def kept_off_the_walls(scene: str, observation: np.ndarray, action: np.ndarray) -> np.ndarray:
    """An actor's command (in the arm's own frame; the bin is symmetric about the arms' mirror) while it puts a block
    into the bin, except that the held block, over the bin but not :data:`WALL_MARGIN` inside its inner walls, is not
    let go and is moved inward."""
    bin_ = SCENES[scene].bin
    held = held_slots(scene, observation)
    if bin_ is None or not held.any() or action[3] <= 0.0:
        return action
    offset = layout.block_slots(scene, observation)["position"][held][0][:2] - np.asarray(bin_.center)
    inner = np.asarray(bin_.inner_half_size)
    over_the_bin = np.all(np.abs(offset) < inner + bin_.wall_thickness + BLOCK_HALF_SIZE)
    on_a_wall = np.abs(offset) > inner - WALL_MARGIN
    return _held_back(action, offset, on_a_wall) if over_the_bin and on_a_wall.any() else action


def held_block_kept_off_the_walls(scene: str, observation: np.ndarray, action: np.ndarray) -> np.ndarray:
    """An actor's command (in the arm's own frame) while it puts a block into the bin, except that the held block does
    not come down onto a wall: where its footprint meets a wall's, its bottom comes no nearer than
    :data:`WALL_CLEARANCE` to that wall's top (nearer, it rises) and the hand moves inward. Brought down onto the desk
    bin's wall, red was knocked out of the fingers and over the table's edge behind (DC-4 with the tabletop actor,
    start 3,200,016)."""
    bin_ = SCENES[scene].bin
    held = held_slots(scene, observation)
    if bin_ is None or not held.any():
        return action
    block = layout.block_slots(scene, observation)["position"][held][0]
    offset = block[:2] - np.asarray(bin_.center)
    inner = np.asarray(bin_.inner_half_size)
    reaches = np.abs(offset) - BLOCK_HALF_SIZE < inner + bin_.wall_thickness  # into the bin's outline, per axis
    on_a_wall = (np.abs(offset) + BLOCK_HALF_SIZE > inner) & reaches & reaches[::-1]
    if not on_a_wall.any():
        return action
    heights = (bin_.wall_height, bin_.back_wall_height if offset[1] > 0 else bin_.wall_height)
    top = TABLE_TOP + bin_.floor_thickness + max(h for h, on in zip(heights, on_a_wall, strict=True) if on)
    bottom = block[2] - BLOCK_HALF_SIZE
    if _lowered(bottom, action) >= top + WALL_CLEARANCE:
        return action
    _rise_over(action, bottom, top + WALL_CLEARANCE)
    return _held_back(action, offset, on_a_wall)


def let_go_on_the_bin_floor(scene: str, observation: np.ndarray, action: np.ndarray) -> np.ndarray:
    """An actor's command (in the arm's own frame) while it puts a block into the bin, except that the held block is
    neither let go nor brought down over a block below it (their footprints within :data:`FOOTPRINT_CLEARANCE` along
    both x and y): it keeps :data:`STACK_CLEARANCE` over that block's top, rising if nearer, and moves toward the
    bin's free spot (``bin_target``: where the expert's hand goes, its fingers clear of the blocks there); there, or
    with no spot free, it goes as the actor asks. Brought down onto blue in the desk's bin and let go
    over it, yellow came to rest on blue, out of the bin (DC-4 with the tabletop actor, start 3,100,013)."""
    bin_ = SCENES[scene].bin
    held = held_slots(scene, observation)
    if bin_ is None or not held.any():
        return action
    blocks = layout.block_slots(scene, observation)
    positions, present = blocks["position"], blocks["present"][:, 0] > 0.5
    here = positions[held][0]
    under = present & ~held & (positions[:, 2] < here[2] - BLOCK_HALF_SIZE) & (
        np.abs(positions[:, :2] - here[:2]) < FOOTPRINT_CLEARANCE).all(axis=1)
    if not under.any():
        return action
    floor = float(positions[under, 2].max()) + BLOCK_HALF_SIZE + STACK_CLEARANCE  # the held block's bottom stays over it
    bottom = here[2] - BLOCK_HALF_SIZE
    if action[3] <= 0.0 and _lowered(bottom, action) >= floor:
        return action
    spot = features.bin_target(scene, observation)  # from the grip, where the fingers fit
    if np.linalg.norm(spot) < STEER_MIN:  # the hand there, or the bin full (zeros): as the actor asks
        return action
    action[:2] = np.clip(spot * RETREAT_GAIN, -STEER_SPEED, STEER_SPEED)
    _rise_over(action, bottom, floor)
    action[3] = HOLD_GRIP[3]
    return action


def straddles_a_stack(scene: str, observation: np.ndarray, picking: Iterable[str] = ()) -> bool:
    """Whether an empty hand's fingers (in the arm's own frame) still straddle a block standing on another, one it is
    not asked to pick (``picking``), outside the bin. The actor moved sideways there and dragged the block it had just
    let go on a tower off its centre, and the tower's top fell (tabletop Tower-6, start 3,000,018): the controller
    rises straight up instead, as a retreating arm does (:meth:`SubgoalController.idle`), and the actor takes over once
    the fingertips are clear."""
    if held_slots(scene, observation).any():
        return False
    grip = layout.arm_state(observation)["grip_position"]
    blocks = layout.block_slots(scene, observation)
    present, positions = blocks["present"][:, 0] > 0.5, blocks["position"]
    offsets = positions[:, :2] - grip[:2]
    under = present & (np.sqrt((offsets * offsets).sum(axis=1)) < THRESHOLDS.holding_xy) & (
        positions[:, 2] > grip[2] - STRADDLE_HEIGHT) & (positions[:, 2] < grip[2] + BLOCK_HALF_SIZE)
    if not under.any():
        return False
    slot = int(np.flatnonzero(under)[positions[under, 2].argmax()])  # the fingers' block: the highest under the grip
    bin_ = SCENES[scene].bin  # in the bin the walls keep a block dragged off another, and the actor learned to do so
    others = present.copy()
    others[slot] = False
    return (SCENES[scene].objects[slot] not in picking and not (bin_ is not None and bin_.inside(positions[slot]))
            and bool(rests_on(positions[slot], positions[others]).any()))  # it stands on another block


def placed_gently(scene: str, observation: np.ndarray, action: np.ndarray, top: str, bottom: str) -> np.ndarray:
    """An actor's command (in the arm's own frame) while it puts ``top`` on ``bottom``, except that the held block
    lands slowly (:data:`LANDING_SPEED`) and is let go only centred on its seat (:data:`RELEASE_XY`,
    :data:`RELEASE_HEIGHT`); wanting to let go before, the hand keeps squeezing and brings it there. A block that
    came down fast on a tower of five pushed it over, and blocks let go 1-2 cm off centre leaned the tower more at
    each put (tabletop Tower-6, start 3,000,047)."""
    held = held_slots(scene, observation)
    objects = SCENES[scene].objects
    if not held[objects.index(top)]:
        return action
    positions = layout.block_slots(scene, observation)["position"]
    offset = positions[objects.index(bottom)] - positions[objects.index(top)]
    off_centre, over_seat = float(np.linalg.norm(offset[:2])), -offset[2] - SEATED_HEIGHT
    if off_centre < THRESHOLDS.above_xy and over_seat < LANDING_HEIGHT:
        action[2] = max(action[2], -LANDING_SPEED)
    if action[3] > 0.0 and (off_centre > RELEASE_XY or over_seat > RELEASE_HEIGHT):
        action[3] = HOLD_GRIP[3]
        action[:2] = np.clip(offset[:2] * RETREAT_GAIN, -1.0, 1.0)
        action[2] = -LANDING_SPEED if over_seat > RELEASE_HEIGHT else 0.0
    return action


def let_go_slowly(scene: str, observation: np.ndarray, action: np.ndarray) -> np.ndarray:
    """An actor's command (in the arm's own frame) while it puts a block near others or into the bin, except that a
    held block is let go only with the hand slower than :data:`LET_GO_SPEED` in the table's plane; wanting to let
    go before, the hand keeps squeezing and stops in the plane. Let go at 1.25 m/s 14 cm over the bin, next to its
    far wall, yellow flew over it and off the table (tabletop Clean-6, start 3,000,009)."""
    if action[3] <= 0.0 or not held_slots(scene, observation).any():
        return action
    speed = float(np.linalg.norm(layout.arm_state(observation)["grip_velocity"][:2])) / layout.CONTROL_DT
    if speed > LET_GO_SPEED:
        action[:2], action[3] = 0.0, HOLD_GRIP[3]
    return action


def let_go_within_reach(scene: str, observation: np.ndarray, action: np.ndarray, block: str, near: Iterable[str],
                        apart: Iterable[str]) -> np.ndarray:
    """An actor's command (in the arm's own frame) while it puts ``block`` near the blocks ``near`` and not close to
    those ``apart``, except that the held block is let go only where the expert lets go: every block of ``near``
    within its ``DROP_REACH`` in the table's plane, every one of ``apart`` beyond its ``AWAY_DROP_DISTANCE``. Wanting
    to let go elsewhere, the hand keeps squeezing, holds its height and moves the block in the plane toward
    :data:`NEAR_AIM` of the one and :data:`APART_AIM` of the other; where those moves cancel, it lets go. Let go
    9-10 cm from the block it was put near, blocks came to rest just beyond close (tabletop put near, seeds
    2,010,020 and 2,010,097). Nor is it let go over the corner of one block below it (its centre beyond that
    block's sides along both x and y, yet nearer than :data:`FOOTPRINT_CLEARANCE` along both): it landed on the
    corner, tumbled off and came to rest just beyond close (2,010,111); the hand moves it out along the axis it
    overlaps less first. Over two blocks' corners it bridges them: it is let go. Over one block's side it slides down
    beside it (the paper's MC-3 lets blocks go so), to :data:`SLIDE_DISTANCE` from it: the reach is judged there. Let go
    within reach over red's side, blue slid off away from green and came to rest 10.9 cm from it (2,110,003)."""
    held = held_slots(scene, observation)
    objects = SCENES[scene].objects
    if action[3] <= 0.0 or not held[objects.index(block)]:
        return action
    blocks = layout.block_slots(scene, observation)
    positions, present = blocks["position"], blocks["present"][:, 0] > 0.5
    here = positions[objects.index(block)]
    below = np.flatnonzero(present & (positions[:, 2] < here[2] - BLOCK_HALF_SIZE))  # under the held one
    apart_by = here[:2] - positions[below, :2]
    overlap = FOOTPRINT_CLEARANCE - np.abs(apart_by)
    over = (overlap > 0).all(axis=1)
    beyond = np.abs(apart_by) > BLOCK_HALF_SIZE
    corners, sides = np.flatnonzero(over & beyond.all(axis=1)), np.flatnonzero(over)
    move, landing = np.zeros(2), here[:2].copy()
    if len(corners) == 1:  # over one block's corner, out along the axis where it overlaps less (over two, it bridges them)
        axis = int(np.argmin(overlap[corners[0]]))
        move[axis] += np.copysign(overlap[corners[0], axis], apart_by[corners[0], axis])
    elif len(sides) == 1 and beyond[sides[0], axis := int(np.argmin(overlap[sides[0]]))]:
        # over one block's side: it slides off beside it, and is judged where it comes to rest
        landing[axis] = positions[below[sides[0]], axis] + np.copysign(SLIDE_DISTANCE, apart_by[sides[0], axis])
    for other in near:
        offset = positions[objects.index(other), :2] - landing
        distance = float(np.linalg.norm(offset))
        if distance > DROP_REACH:
            move += offset / distance * (distance - NEAR_AIM)
    for other in apart:
        offset = landing - positions[objects.index(other), :2]
        distance = float(np.linalg.norm(offset))
        if distance < AWAY_DROP_DISTANCE:
            move += offset / max(distance, 1e-6) * (APART_AIM - distance)
    if np.linalg.norm(move) < STEER_MIN:  # nowhere to go (the moves cancel): let go where the actor asks
        return action
    action[:2] = np.clip(move * RETREAT_GAIN, -STEER_SPEED, STEER_SPEED)
    action[2], action[3] = 0.0, HOLD_GRIP[3]
    return action


def grasped_in_place(scene: str, observation: np.ndarray, action: np.ndarray, block: str) -> np.ndarray:
    """An actor's command (in the arm's own frame) while it picks ``block`` off a stack, except that over the block
    the hand goes down only with the fingers wide open, closes them only at the block's middle (at most
    :data:`GRASP_HEIGHT` over its centre), and while the fingertips are beside the block moves in the plane only
    toward its centre, slowly (:data:`CENTRING_SPEED`), and not at all once it holds it, until the block is
    :data:`LIFT_CLEARANCE` clear of the block below. Fingers closed too high on the block rise off it
    before they open. Closing on the top of a tower of six, the hand moved 1.4 cm sideways (tabletop Unstack-6, start
    3,000,002), or the fingers pinched the block's top edge and dragged it (3,000,045), or pressed on its top and
    dragged it opening (3,000,006): each time the top block pulled the one under it along, and the tower fell."""
    blocks = layout.block_slots(scene, observation)
    positions, present = blocks["position"], blocks["present"][:, 0] > 0.5
    slot = SCENES[scene].objects.index(block)
    here = positions[slot]
    column = present & (np.linalg.norm(positions[:, :2] - here[:2], axis=1) < THRESHOLDS.above_xy) & (
        positions[:, 2] < here[2] - BLOCK_HALF_SIZE)
    arm = layout.arm_state(observation)
    grip, opening = arm["grip_position"], float(arm["finger_positions"].sum())
    height = grip[2] - here[2]
    if (not column.any() or np.linalg.norm(grip[:2] - here[:2]) >= THRESHOLDS.holding_xy
            or not -THRESHOLDS.holding_z < height < HOVER):
        return action
    gap = here[2] - BLOCK_HALF_SIZE - (positions[column, 2].max() + BLOCK_HALF_SIZE)
    held = bool(held_slots(scene, observation)[slot])
    if gap >= LIFT_CLEARANCE and held:
        return action
    low = grip[2] - FINGER_TIP < here[2] + BLOCK_HALF_SIZE + PALM_CLEARANCE  # the fingertips beside the block
    if low:
        action[:2] = 0.0 if held else np.clip((here[:2] - grip[:2]) * RETREAT_GAIN, -CENTRING_SPEED, CENTRING_SPEED)
    if height <= GRASP_HEIGHT:
        return action
    if opening >= RETREAT_OPENING:  # open: down to the block's middle, not closing before
        action[3] = max(action[3], 0.0)
        action[2] = min(action[2], -min((height - GRASP_HEIGHT) * RETREAT_GAIN, 1.0))
    elif low:  # closed too high, on or beside the block's top: up off it first, the fingers as they are
        action[3] = -float(arm["finger_velocities"].mean())
        action[2] = max(action[2], EDGE_NUDGE)
    else:  # over it, not open: open, not going down
        action[3] = _opening_toward(RETREAT_OPENING, opening)
        action[2] = max(action[2], 0.0)
    return action


def closed_across_the_middle(scene: str, observation: np.ndarray, action: np.ndarray, block: str) -> np.ndarray:
    """An actor's command (in the arm's own frame) while an empty hand picks ``block``, except that with the fingertips
    beside the block and the fingers still open wider than it, they do not close more than :data:`CLOSING_OFFSET` off
    its centre across their width: they stay as they are and the hand moves toward the centre along that axis
    (:data:`CENTRING_SPEED`). Closed 2.7 cm off green's centre, the fingers held 1.2 cm of its edge; lifted, it slipped
    out, fell and went over the table's far edge (tabletop Clean-6, start 3,300,015)."""
    arm = layout.arm_state(observation)
    grip, opening = arm["grip_position"], float(arm["finger_positions"].sum())
    if action[3] >= 0.0 or opening <= 2 * BLOCK_HALF_SIZE or held_slots(scene, observation).any():
        return action
    here = layout.block_slots(scene, observation)["position"][SCENES[scene].objects.index(block)]
    offset = here[:2] - grip[:2]
    beside = (grip[2] - FINGER_TIP < here[2] + BLOCK_HALF_SIZE and grip[2] > here[2] - BLOCK_HALF_SIZE
              and abs(offset[1]) < opening / 2)
    if beside and CLOSING_OFFSET < abs(offset[0]) < BLOCK_HALF_SIZE + FINGER_HALF_WIDTH:
        action[0] = float(np.clip(offset[0] * RETREAT_GAIN, -CENTRING_SPEED, CENTRING_SPEED))
        action[3] = 0.0
    return action


def fingers_kept_off_its_top(scene: str, observation: np.ndarray, action: np.ndarray, block: str) -> np.ndarray:
    """An actor's command (in the arm's own frame) while an empty hand picks ``block``, except that fingers too narrow
    to pass it do not come down on its top: over it, they come down no nearer than :data:`PALM_CLEARANCE` to its top
    and open there, the hand moving toward its centre across their opening (:data:`CENTRING_SPEED`); on its top, they
    rise off it first, the fingers as they are. Fingers closed over green came down on its top, pressed it down on one
    edge and pushed it along the table and over its edge (tabletop Clean-6, starts 3,300,004 and 3,300,046)."""
    arm = layout.arm_state(observation)
    grip, opening = arm["grip_position"], float(arm["finger_positions"].sum())
    if held_slots(scene, observation).any():
        return action
    here = layout.block_slots(scene, observation)["position"][SCENES[scene].objects.index(block)]
    toward = here[:2] - grip[:2]
    offset = np.abs(toward)
    top = here[2] + BLOCK_HALF_SIZE + PALM_CLEARANCE
    fingertips = grip[2] - FINGER_TIP
    over = (offset[0] < BLOCK_HALF_SIZE + FINGER_HALF_WIDTH and offset[1] < BLOCK_HALF_SIZE + opening / 2 + FINGER_OUTER_FACE
            and offset[1] + BLOCK_HALF_SIZE + FINGER_CLEARANCE > opening / 2)  # a finger over the block, not beside it
    if not over or fingertips < here[2]:  # below its middle: beside it already, the grasp's own business
        return action
    if fingertips < top - PALM_CLEARANCE:  # on its top: up off it before the fingers move
        _rise_over(action, fingertips, top)
        action[3] = -float(arm["finger_velocities"].mean())
    elif _lowered(fingertips, action) < top:
        action[1] = float(np.clip(toward[1] * RETREAT_GAIN, -CENTRING_SPEED, CENTRING_SPEED))
        action[2] = max(action[2], min((top - fingertips) / layout.MAX_DISPLACEMENT, 0.0))
        action[3] = 1.0
    return action


def palm_clear_of_stacks(scene: str, observation: np.ndarray, action: np.ndarray, block: str) -> np.ndarray:
    """An actor's command (in the arm's own frame) while an empty hand picks ``block`` off the table beside a stack
    whose top the gripper's palm would meet at the block's height, except that the hand comes down off the block's
    centre, away from the stack, as far as the palm needs to pass it (at most :data:`PICK_SHIFT`), and only once there,
    with the fingers wide enough to pass the block. Coming down on a block 8 cm from a tower of four, the palm struck
    the tower's upper blocks and it fell (tabletop Tower-5, starts 3,000,024 and 3,000,040; six such misses more in
    Tower-6 and Tower-7). Where no shift that small clears every such stack, the command is left as it is."""
    blocks = layout.block_slots(scene, observation)
    present, positions = blocks["present"][:, 0] > 0.5, blocks["position"]
    slot = SCENES[scene].objects.index(block)
    here = positions[slot]
    arm = layout.arm_state(observation)
    grip, opening = arm["grip_position"], float(arm["finger_positions"].sum())
    if (here[2] > TABLE_TOP + BLOCK_HALF_SIZE + LIFT_CLEARANCE or np.abs(grip[:2] - here[:2]).max() > PALM_FOOTPRINT.max()
            or held_slots(scene, observation).any()):
        return action
    others = present.copy()
    others[slot] = False
    tall = _stacked(positions, others) & (positions[:, 2] + BLOCK_HALF_SIZE + PALM_CLEARANCE > here[2] + PALM_BOTTOM)
    shift = _palm_shift(positions[tall, :2] - here[:2])
    if shift is None:
        return action
    top = float(positions[tall, 2].max()) + BLOCK_HALF_SIZE + PALM_CLEARANCE
    palm = grip[2] + PALM_BOTTOM
    palm_next = _lowered(palm, action)
    if palm_next >= top + APPROACH_HEIGHT:
        return action  # high over the stacks still: the actor's approach
    error = here[:2] + shift - grip[:2]
    action[:2] = np.clip(error * RETREAT_GAIN, -1.0, 1.0)
    if np.abs(error).max() > SHIFT_TOLERANCE and palm_next < top:
        _rise_over(action, palm, top)
    wide = 2 * (BLOCK_HALF_SIZE + abs(shift[1]) + FINGER_CLEARANCE)
    fingertips = _lowered(grip[2] - FINGER_TIP, action)
    if opening < wide and fingertips < here[2] + BLOCK_HALF_SIZE + PALM_CLEARANCE and grip[2] - FINGER_TIP > here[2]:
        action[2] = max(action[2], 0.0)  # not down beside the block until the fingers pass it
        action[3] = 1.0
    return action


def _palm_shift(offsets: np.ndarray) -> np.ndarray | None:
    """The least move (x, y) of the grip, along one axis and within :data:`PICK_SHIFT`, that takes the palm's footprint
    off every block at ``offsets`` (N, 2) from the grip; None when none is under it, or when no such move does."""
    inside = (np.abs(offsets) < PALM_FOOTPRINT).all(axis=1)
    if not inside.any():
        return None
    moves = []
    for axis in (0, 1):
        for direction in (-1.0, 1.0):
            into = PALM_FOOTPRINT[axis] + direction * offsets[:, axis]  # how far each block's centre is inside, ahead
            move = np.zeros(2)
            move[axis] = direction * max(0.0, float(into[inside].max()))
            if abs(move[axis]) <= PICK_SHIFT[axis] and not (np.abs(offsets - move) < PALM_FOOTPRINT).all(axis=1).any():
                moves.append(move)
    return min(moves, key=lambda m: float(np.abs(m).sum())) if moves else None


def fingers_spare_neighbours(scene: str, observation: np.ndarray, action: np.ndarray) -> np.ndarray:
    """An actor's command (in the arm's own frame), except that the fingers do not open into a block beside them along
    their axis, at their height: they open only as far as leaves :data:`FINGER_CLEARANCE` to it. Letting go of a block
    on the table 7.6 cm from another, the fingers opened fully, one struck the other block and flung it off the table
    (tabletop Unstack-6, start 3,000,008)."""
    if action[3] <= 0.0:
        return action
    arm, blocks = layout.arm_state(observation), layout.block_slots(scene, observation)
    grip, opening = arm["grip_position"], float(arm["finger_positions"].sum())
    offsets = blocks["position"] - grip
    beside = (blocks["present"][:, 0] > 0.5) & (np.abs(offsets[:, 0]) < FINGER_HALF_WIDTH + BLOCK_HALF_SIZE) & (
        np.abs(offsets[:, 1]) >= 2 * BLOCK_HALF_SIZE) & (offsets[:, 2] + BLOCK_HALF_SIZE > -FINGER_TIP) & (
        offsets[:, 2] - BLOCK_HALF_SIZE < FINGER_LENGTH - FINGER_TIP)
    if not beside.any():
        return action
    room = 2 * float(np.abs(offsets[beside, 1]).min() - BLOCK_HALF_SIZE - FINGER_OUTER_FACE - FINGER_CLEARANCE)
    action[3] = min(action[3], max(_opening_toward(room, opening), 0.0))
    return action


Stacks = tuple[np.ndarray, np.ndarray, np.ndarray]
"""What the rules on stacks read of an observation: the held block slots, the block positions, and which blocks, the
held one aside, are in a stack (on another or under one)."""


def stacks_of(scene: str, observation: np.ndarray) -> Stacks | None:
    """:data:`Stacks` of an observation (in the arm's own frame); None when the hand holds no block."""
    held = held_slots(scene, observation)
    if not held.any():
        return None
    blocks = layout.block_slots(scene, observation)
    positions = blocks["position"]
    return held, positions, _stacked(positions, (blocks["present"][:, 0] > 0.5) & ~held)


def _stacked(positions: np.ndarray, among: np.ndarray) -> np.ndarray:
    """(N,) bool: which of the blocks ``among`` stand on another of them or carry one (``above``'s geometry)."""
    pairs = rests_on(positions[:, None, :], positions[None, :, :]) & among[:, None] & among[None, :]
    return pairs.any(axis=0) | pairs.any(axis=1)


def palm_kept_off_stacks(scene: str, observation: np.ndarray, action: np.ndarray, stacks: Stacks | None = None
                         ) -> np.ndarray:
    """An actor's command (in the arm's own frame) while the hand holds a block, except that the gripper's palm does
    not come down beside a stack of blocks lower than its top: the hand stays up and moves away from the stack. The
    palm came down on a tower of five as the hand put a block on the table 7 cm from it, and the tower fell (tabletop
    Unstack-6, start 3,000,014). ``stacks``: :func:`stacks_of` the observation, when known."""
    stacks = stacks or stacks_of(scene, observation)
    if stacks is None:
        return action
    _, positions, stacked = stacks
    grip = layout.arm_state(observation)["grip_position"]
    offsets = positions - grip
    near = stacked & (np.abs(offsets[:, :2]) < PALM_REACH).all(axis=1)
    if not near.any():
        return action
    top = float(positions[near, 2].max()) + BLOCK_HALF_SIZE + PALM_CLEARANCE
    palm = grip[2] + PALM_HEIGHT
    if _lowered(palm, action) >= top:
        return action
    _rise_over(action, palm, top)
    away = -offsets[near, :2].mean(axis=0)
    action[:2] = np.where(np.sign(action[:2]) == np.sign(away), action[:2], np.sign(away) * EDGE_NUDGE)
    return action


def held_block_kept_off_stacks(scene: str, observation: np.ndarray, action: np.ndarray, seat: str | None = None,
                               stacks: Stacks | None = None) -> np.ndarray:
    """An actor's command (in the arm's own frame) while the hand holds a block, except that the held block does not
    come down beside a block of a stack (``seat``, the block it is put on, aside) nearer than
    :data:`STACK_CLEARANCE` to its footprint and below its top: it stays at its height and moves away from it.
    Putting a block on the table 5-6 cm beside a tower of three, the held block came down along the tower's side,
    pushed its top block out and off the table (tabletop Unstack-6, start 3,000,024). ``stacks``: :func:`stacks_of`
    the observation, when known."""
    stacks = stacks or stacks_of(scene, observation)
    if stacks is None:
        return action
    held, positions, stacked = stacks
    if seat is not None:
        stacked = stacked.copy()
        stacked[SCENES[scene].objects.index(seat)] = False
    here = positions[held][0]
    then = here + action[:3] * layout.MAX_DISPLACEMENT  # where this command takes it
    offsets = then - positions
    beside = stacked & (np.abs(offsets[:, :2]) < 2 * BLOCK_HALF_SIZE + STACK_CLEARANCE).all(axis=1) & (
        np.hypot(offsets[:, 0], offsets[:, 1]) >= THRESHOLDS.above_xy) & (  # over it: a put on it, or a lift off it
        offsets[:, 2] < 2 * BLOCK_HALF_SIZE + STACK_CLEARANCE) & (here[2] > positions[:, 2] + BLOCK_HALF_SIZE)
    if beside.any():
        action[2] = max(action[2], 0.0)
        away = (here[:2] - positions[beside, :2]).mean(axis=0)
        action[:2] = away / max(float(np.linalg.norm(away)), 1e-9) * CENTRING_SPEED
    return action


def _opening_toward(target: float, opening: float) -> float:
    """The finger command that opens the fingers from ``opening`` to ``target`` (m): a finger command is metres added
    to each finger's target, and a quarter of the way a step comes to rest 3-4 mm past it, no more."""
    return (target - opening) / 4


def _lowered(height: float, action: np.ndarray) -> float:
    """Where a part of the hand at ``height`` (m) is after ``action``, as low as it takes it (a rise counts as none)."""
    return height + min(action[2], 0.0) * layout.MAX_DISPLACEMENT


def _rise_over(action: np.ndarray, height: float, floor: float) -> None:
    """Sets ``action`` to take a part of the hand at ``height`` (m) no lower than ``floor``: up to it where below it, at
    most a full step (the actor's own rise kept where larger)."""
    action[2] = max(action[2], min((floor - height) / layout.MAX_DISPLACEMENT, 1.0))


def _held_back(action: np.ndarray, offset: np.ndarray, axes: np.ndarray) -> np.ndarray:
    """``action`` with the fingers kept from opening and, along ``axes``, the hand moved back against ``offset`` (the
    held block's from the centre it must stay near) at least :data:`EDGE_NUDGE`."""
    action[3] = min(action[3], 0.0)
    action[:2] = np.where(axes, -np.sign(offset) * np.maximum(np.abs(action[:2]), EDGE_NUDGE), action[:2])
    return action


def held_slots(scene: str, observation: np.ndarray) -> np.ndarray:
    """(max_blocks,) bool: the block slots between the fingers (``holding``'s geometry)."""
    arm, blocks = layout.arm_state(observation), layout.block_slots(scene, observation)
    return held_alone(blocks["position"], arm["grip_position"], float(arm["finger_positions"].sum()),
                      blocks["present"][:, 0] > 0.5)


class Idle(StrEnum):
    """What an arm with no sub-goal of its own does."""

    RETREAT = "retreat"
    """The goal is done: let go (keeping what the goal asks to hold) and rise clear of the blocks."""
    MAKE_ROOM = "make_room"
    """Another agent works (a person's step, the other arm's): keep what is in the hand; an empty hand rises to
    :data:`ROOM_HEIGHT` (on a shared table, draws back to its park spot), out of the way of a block put on a tower."""
    HOLD = "hold"
    """Paused, failed or between steps: hold still, keeping what is in the hand."""


def _put_near(literals: list[Literal]) -> SubGoal | None:
    """The put near these literals ask for (:func:`~semgoal_core.vocabulary.subgoal_of`); None for any other."""
    try:
        subgoal = subgoal_of(literals)
    except VocabularyError:
        return None
    return subgoal if subgoal.kind == "put_near" else None


class SubgoalController:
    """Wraps an exported actor for one scene and one arm; every output is finite and within [-1, 1]. Observations
    and commands are in the world frame; the actor, and every rule here, sees the world in the arm's own frame
    (:class:`semgoal_core.arms.ArmFrame`: a second arm's is reflected across the table)."""

    def __init__(self, scene: str, model_dir: Path | str | None = None, mode: str = "sample", arm: int = 0,
                 shared: bool = False) -> None:
        if mode not in ACTION_MODES:
            raise ValueError(f"unknown action mode {mode!r}; valid: {', '.join(ACTION_MODES)}")
        self.scene, self.mode = scene, mode
        self.frame = ArmFrame(scene, arm)
        self.shared = shared
        """The table is shared with another arm: holding still with no block in hand, the arm draws back to
        :data:`semgoal_core.arms.PARK` instead, out of the other's way."""
        self.layout = LAYOUTS[scene]
        self.model_dir = Path(model_dir or actor_io.models_dir() / scene)  # "expert": the scripted expert
        self.actor, self.meta = actor_io.load(self.model_dir, scene)
        self.derived = actor_io.derived_features(self.meta)
        self.bin_shown = features.shown_bin(scene, self.meta["layout"]["scene"])
        """The bin the actor's ``bin_target`` reads: in a scene without one, that of the scene it was trained on."""
        self.goal: np.ndarray | None = None
        self.literals: list[Literal] = []
        self.idling = Idle.RETREAT
        """What the arm does with no sub-goal."""
        self.into_bin = False
        """The sub-goal puts a block into the bin: :func:`let_go_slowly`, :func:`kept_off_the_walls`,
        :func:`held_block_kept_off_the_walls` and :func:`let_go_on_the_bin_floor` apply."""
        self.putting_on: tuple[str, str] | None = None
        """The sub-goal puts one block on another (top, bottom): :func:`placed_gently` applies."""
        self.putting_near: SubGoal | None = None
        """The sub-goal, where it puts a block near others: :func:`let_go_slowly` and :func:`let_go_within_reach`
        apply."""
        self.picking: frozenset[str] = frozenset()
        """The blocks the sub-goal asks to hold: :func:`straddles_a_stack` leaves the hand beside them be."""
        self.keep: frozenset[str] = frozenset()
        """Blocks the goal asks to be held: the retreating arm keeps them in the hand."""
        self.confirmation = Settling()
        self.obs_size = layout.observation_size(scene)

    def set_subgoal(self, literals: list[Literal], idling: Idle = Idle.RETREAT, keep: Iterable[str] = ()) -> None:
        """Condition on a sub-goal's literals; an empty list means no step to act on: ``idling`` says what the arm
        does then (retreating, it keeps the blocks in ``keep`` in the hand). VocabularyError if invalid."""
        goal = None
        if literals:
            target, mask = self.layout.encode(literals)
            goal = np.concatenate([target, mask])
        if goal is None or self.goal is None or not np.array_equal(goal, self.goal):
            self.confirmation.reset()  # a new sub-goal: its confirmation starts over
        self.goal, self.literals, self.idling, self.keep = goal, list(literals), Idle(idling), frozenset(keep)
        self.into_bin = any(lit.name == "in_bin" and lit.value for lit in self.literals)
        self.picking = frozenset(lit.args[0] for lit in self.literals if lit.name == "holding" and lit.value)
        puts = [tuple(lit.args) for lit in self.literals if lit.name == "above" and lit.value]
        self.putting_on = puts[0] if len(puts) == 1 else None
        self.putting_near = _put_near(self.literals)

    def confirmed(self, step: int, semantic_vector: np.ndarray, moving: tuple[str, ...] = ()) -> bool:
        """Whether the sub-goal's literals held at rest (``moving``: the blocks not still) over the last
        ``SETTLE_STEPS`` control steps up to ``step`` (the planner's rule for done); call it once per new
        control step."""
        held = [lit.args[0] for lit in self.layout.true_literals(semantic_vector) if lit.name == "holding"]
        settled = self.achieved(semantic_vector) and at_rest(self.literals, moving, held)
        return self.confirmation.update(settled, step)

    def achieved(self, semantic_vector: np.ndarray) -> bool:
        """Whether the active sub-goal's literals hold in this semantic state (False when there is none)."""
        if self.goal is None:
            return False
        achieved = layout.achieved_goal(semantic_vector, self.goal[self.layout.size:])
        return bool(layout.goal_reward(achieved, self.goal))

    def act(self, observation: np.ndarray, noise_key: tuple[int, ...] = (0,)) -> np.ndarray:
        """The command for an observation; ``noise_key`` (task seed, step) seeds the sampled noise."""
        observation = np.asarray(observation, dtype=np.float32)
        if observation.shape != (self.obs_size,) or not np.isfinite(observation).all():
            return HOLD.copy()
        key = (*noise_key, self.frame.arm) if self.frame.arm else noise_key  # each arm its own noise
        return self.frame.action(self._act(self.frame.observation(observation), key))

    def _act(self, observation: np.ndarray, noise_key: tuple[int, ...]) -> np.ndarray:
        """:meth:`act` in the arm's own frame."""
        if self.goal is None:
            if self.idling == Idle.RETREAT:
                return self.idle(observation)
            return self._hold(observation, make_room=self.idling == Idle.MAKE_ROOM)
        # numpy seeds take non-negative integers; a negative key (a malformed world state) maps into range
        noise = np.random.default_rng([k % 2**64 for k in noise_key]).standard_normal(4) if self.mode == "sample" else None
        inputs = features.augment(self.scene, observation, self.derived, self.goal, self.bin_shown)
        return self.ruled(observation, self.actor.act(inputs, self.goal, noise))

    def ruled(self, observation: np.ndarray, action: np.ndarray) -> np.ndarray:
        """The actor's ``action`` for ``observation`` (both in the arm's own frame) under the rules this controller
        puts on it for the active sub-goal: what :meth:`act` sends, given the actor's output (``eval subgoals
        --shields`` judges the actor so)."""
        if straddles_a_stack(self.scene, observation, self.picking):
            return self._rise(observation, RETREAT_HEIGHT)
        action = np.clip(np.nan_to_num(action, nan=0.0, posinf=0.0, neginf=0.0), -1.0, 1.0).astype(np.float32)
        if self.into_bin or self.putting_near:
            action = let_go_slowly(self.scene, observation, action)
        if self.into_bin:
            action = kept_off_the_walls(self.scene, observation, action)
            action = held_block_kept_off_the_walls(self.scene, observation, action)
            action = let_go_on_the_bin_floor(self.scene, observation, action)
        if self.putting_on:
            action = placed_gently(self.scene, observation, action, *self.putting_on)
        if self.putting_near:
            put = self.putting_near
            action = let_go_within_reach(self.scene, observation, action, put.block, put.references, put.apart)
        for block in self.picking:
            action = grasped_in_place(self.scene, observation, action, block)
            action = closed_across_the_middle(self.scene, observation, action, block)
            action = fingers_kept_off_its_top(self.scene, observation, action, block)
            action = palm_clear_of_stacks(self.scene, observation, action, block)
        stacks = stacks_of(self.scene, observation)
        if stacks is not None:
            action = palm_kept_off_stacks(self.scene, observation, action, stacks)
            seat = self.putting_on[1] if self.putting_on else None
            action = held_block_kept_off_stacks(self.scene, observation, action, seat, stacks)
        action = fingers_spare_neighbours(self.scene, observation, action)
        return kept_on_the_table(self.scene, observation, action)

    def hold(self, observation: np.ndarray) -> np.ndarray:
        """Hold still, keeping a block that sits between the closed fingers (``holding``'s geometry); on a
        :attr:`shared` table, an empty hand draws back to its park spot."""
        observation = np.asarray(observation, dtype=np.float32)
        if observation.shape != (self.obs_size,) or not np.isfinite(observation).all():
            return HOLD.copy()
        return self.frame.action(self._hold(self.frame.observation(observation)))

    def _hold(self, observation: np.ndarray, make_room: bool = False) -> np.ndarray:
        """:meth:`hold` in the arm's own frame; ``make_room``: an empty hand rises as :attr:`Idle.MAKE_ROOM` says."""
        if held_slots(self.scene, observation).any():
            return HOLD_GRIP.copy()
        if make_room and not self.shared:
            return self._rise(observation, ROOM_HEIGHT)
        action = HOLD.copy()
        if self.shared:
            grip = layout.arm_state(observation)["grip_position"]
            action[:3] = np.clip((PARK - grip) * RETREAT_GAIN, -1.0, 1.0)
        return action

    def idle(self, observation: np.ndarray) -> np.ndarray:
        """With nothing to do once a goal is done: where the goal asks to hold a block (:attr:`keep`; the goal
        holds, so it is in the hand), the arm keeps squeezing and holds still, once the grasp is seated (a block held 39 mm under the grip
        site, at the edge of what ``holding`` reads, was let go when this asked the geometry); else it retreats,
        letting go of any block it straddles. The fingers open to :data:`RETREAT_OPENING` if they are narrower;
        once no block moves (a block dropped onto another still tumbled, and fingers rising past it lifted it off
        the table) the grip site rises straight up to :data:`RETREAT_HEIGHT` over the highest block and stays
        there, the fingers as they are."""
        observation = np.asarray(observation, dtype=np.float32)
        if self.keep:
            return self._kept(observation)
        return self._rise(observation, RETREAT_HEIGHT)

    def _rise(self, observation: np.ndarray, height: float) -> np.ndarray:
        """Let go and rise straight up to ``height`` over the highest block's centre, as :meth:`idle` says."""
        arm, blocks = layout.arm_state(observation), layout.block_slots(self.scene, observation)
        grip, opening = arm["grip_position"], float(arm["finger_positions"].sum())
        action = HOLD.copy()
        if opening < RETREAT_OPENING:
            action[3] = _opening_toward(RETREAT_OPENING, opening)
            return action
        action[3] = -float(arm["finger_velocities"].mean())  # (per step) brakes the fingers where they are
        present = blocks["present"][:, 0] > 0.5
        speeds = np.linalg.norm(blocks["velocity"][present], axis=1) / layout.CONTROL_DT
        if (speeds >= REST_SPEED).any():  # a block let go still moves: rising fingers could drag it along
            return action
        if present.any():
            top = float(blocks["position"][present, 2].max()) + height
            action[2] = float(np.clip((top - grip[2]) * RETREAT_GAIN, 0.0, 1.0))  # up only, never onto a block
        return action

    def _kept(self, observation: np.ndarray) -> np.ndarray:
        """Keep the block in the hand: squeeze, and where it hangs below :data:`SEATED_DEPTH` under the grip site
        with no neighbour within :data:`SEATING_CLEARANCE`, come down at :data:`SEATING_SPEED` until it is seated."""
        action = HOLD_GRIP.copy()
        held = held_slots(self.scene, observation)
        if held.any():
            grip = layout.arm_state(observation)["grip_position"]
            blocks = layout.block_slots(self.scene, observation)
            others = blocks["position"][(blocks["present"][:, 0] > 0.5) & ~held]
            clear = (np.linalg.norm(others[:, :2] - grip[:2], axis=1) >= SEATING_CLEARANCE).all()
            if clear and grip[2] - blocks["position"][held][0][2] > SEATED_DEPTH:
                action[2] = -SEATING_SPEED
        return action

__all__ = ["ACTION_MODES", "HOLD", "HOLD_GRIP", "RETREAT_HEIGHT", "RETREAT_OPENING", "ROOM_HEIGHT", "Idle", "SubgoalController",
           "VocabularyError"]
