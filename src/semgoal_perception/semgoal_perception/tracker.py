"""Block tracks across frames: a small filter per block that smooths the voter's centres into positions
and velocities, and carries a block the camera does not see this frame.

Occlusion is normal: a block under the arm, in the hand or below another block keeps its track. A block in a hand is
carried by that hand's grip site (the arms' kinematics; with two arms, either): across the table at the offset it had
when the fingers closed on it, taken from where it last rested, but centred between the fingers along the axis they
close on (:data:`FINGER_AXIS`), and in height no lower than it rested until it hangs :data:`HELD_HANG` below the
grip, as a lifted block slides down the closed fingers; where the camera sees it in the hand, the offset follows what
it sees (it slips and swings there), never out of the hand's reach (:data:`HELD_BOX`). Filtered as a free block, a
carried block lagged the hand by one to three centimetres (a tower's top block was let go that far off its mark, and
the tower fell); the hand's kinematics do not lag. Seen far from the hand that held it, the block has left it (while
the fingers still close on a block's width, only if it is seen there for a few frames). A block the fingers open on
is let go: it falls onto what is under it (the table, the bin's floor, a block), as the open hand over it still hides
it (a block let go into a crowded bin stayed in the hand's place, above the rim, and the planner waited for it). A
block that no hand is near cannot jump: a detection far from where its track stands is doubted (the Fetch's arm is
blue, and its links near another block have read as the blue block) until it persists for :data:`DOUBT_FRAMES`
frames, as a block that really fell or was knocked does. Any other unseen block stays where it was, presumed still,
its uncertainty growing each frame. After :data:`LOST_FRAMES` unseen frames it is reported lost, with its last
estimate, never dropped. No block lies lower than the table or the bin's floor under it lets it, none sinks into the
block it stands on, and none unseen beyond the table's edges stays above the floor.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from enum import IntEnum
from typing import NamedTuple

import numpy as np

from semgoal_core.geometry import TABLE_CENTER, TABLE_HALF_SIZE, TABLE_TOP
from semgoal_core.layout import CONTROL_DT
from semgoal_core.settling import REST_SPEED
from semgoal_core.vocabulary import BLOCK_HALF_SIZE, THRESHOLDS, BinGeometry
from semgoal_perception.estimator import Detection

ALPHA, BETA = 0.6, 0.12
"""Alpha-beta filter gains (a steady-state Kalman filter of a constant-velocity block): measured voter
noise (about 1 mm per frame) leaves a velocity noise of a few mm/s, well under the rest threshold."""
SIGMA_GROWTH = 0.002
"""Growth of an unseen free block's standard deviation per frame (m)."""
SIGMA_HELD = 0.004
"""Standard deviation of a block carried in the hand (m): the fingers hold it, but it can slip."""
HELD_HANG = -0.018
"""Height of a lifted block's centre above the grip site (m): the scripted expert's grasps (Tower-6, Clean-6, Sort
and two DC-4 starts, 401 control steps held 6 cm or more above the table) read -19.1 +- 2.3 mm on the tabletop and
-15.8 +- 3.6 mm on the desk."""
HELD_GATE = 0.04
"""A held block seen farther than this (m) from where its hand carries it has left the hand (fallen, knocked out);
the votes of a block in the hand stay within about 2.5 cm. While the fingers still close on a block's width, only
once it is seen there for :data:`DOUBT_FRAMES` frames (a lifted block, tracked in the fingers, was once taken out of
them by one stray red vote 18 cm away, and the expert let it fall)."""
OFFSET_GAIN = 0.5
"""Share of a held block's seen offset from where its hand carries it taken each frame: the block slips and swings in
the fingers (a block hanging 2 cm under the grip moved 3 to 4 mm across it, 1 cm as the arm braked over a tower of six,
and the tower fell), while the voter's centre of a lifted block is 1.8 mm from the true one at the median and 8.5 mm
at the 99th percentile (the scripted expert's Tower-7, starts 3,000,000 and 3,000,001, 206 frames with the block
seen). The hand's motion is the kinematics', with no lag; the offset is the camera's. Along :data:`FINGER_AXIS` the
fingers keep it centred."""
HELD_BOX = 0.8
"""Share of ``holding``'s box around the grip site (:data:`~semgoal_core.vocabulary.THRESHOLDS`) that a carried
block's offset is kept within: while a hand carries it, the block is in that hand, as ``holding`` must read. A block
lifted 6 cm between two frames took its offset from where it had rested, 6 cm under the grip, and votes of a block
slipped 2 cm along the fingers drew it past ``holding``'s 3 cm: either way the hand no longer held it, and the block
was let go onto the table while it rode in the fingers (13 such drops in ten Clean-8 starts of the learned actor from
the camera, counted on their recordings' frames, one in five of the camera's: ``eval perception --recordings``)."""
FINGER_AXIS = 1
"""The world axis the fingers close along (y: the Fetch's gripper points down, unturned; the arm across the table
too). Closing, they centre a block between them on it: a block grasped off-centre is pushed there."""
JUMP_GATE = 0.05
"""A detection this far (m) from a free block's predicted position, with no hand within :data:`HAND_REACH` of the
block, is doubted."""
OVERLAP = 0.04
"""Two detections nearer than this (m) cannot be two blocks: a block's centre is at least its size, 5 cm, from another's
(each holds the ball inscribed in it); the margin is the voter's error."""
LANDING_SLACK = 0.015
"""How far (m) a block let go may seem to be below the top of a block under it and still land on it: the estimates'
error. A block let go lower than that beside a block in a crowded bin is beside it, and falls to the floor (it had been
left 2 cm above the bin's floor, over a neighbour's edge, where ``in_bin`` was unsure, and the hand, sent to pick it
again, hid it from the camera for 300 control steps)."""
HAND_REACH = 0.12
"""A hand this near (m) may have moved a block: a jump there is believed at once."""
DOUBT_FRAMES = 5
"""Frames in a row a far detection must persist before the track follows it (0.2 s at 25 Hz)."""
SIGMA_MAX = 0.05
LOST_FRAMES = 75
"""Unseen this many frames in a row (3 s at 25 Hz) and a block is lost (its last estimate still kept)."""


class TrackStatus(IntEnum):
    """What the camera knows of a block now (the wire values of ``BlockEstimate.status``)."""

    VISIBLE = 0
    OCCLUDED = 1
    HELD = 2
    """Unseen in the closed hand: it follows the grip site."""
    LOST = 3
    NEVER_SEEN = 4


class Hand(NamedTuple):
    """One arm's hand as its kinematics give it: grip site (m), its velocity (m/s), finger opening (m)."""

    position: np.ndarray
    velocity: np.ndarray
    opening: float


@dataclass
class Track:
    position: np.ndarray = field(default_factory=lambda: np.full(3, np.nan))
    velocity: np.ndarray = field(default_factory=lambda: np.zeros(3))
    sigma: np.ndarray = field(default_factory=lambda: np.full(3, SIGMA_MAX))
    status: TrackStatus = TrackStatus.NEVER_SEEN
    unseen: int = 0
    pixels: int = 0
    grip_offset: np.ndarray | None = None
    """Block centre minus grip site while it is in a closed hand; None when it is not."""
    rest_position: np.ndarray | None = None
    """Where it was last seen at rest, out of any hand: a grasp's offset is taken from there."""
    doubted: int = 0
    """Frames in a row its detection was too far from it to believe (:data:`JUMP_GATE`)."""
    lifted_from: float = np.nan
    """Its centre's height when the hand that holds it took it (m)."""
    hand: int | None = None
    """Which hand of the frame's ``hands`` holds it (0: the own arm's); None when none does."""


def in_hand(position: np.ndarray, grip: np.ndarray, opening: float) -> bool:
    """The geometry of ``holding`` for one block (the thresholds of :mod:`semgoal_core.vocabulary`)."""
    rel = position - grip
    t = THRESHOLDS
    return bool(t.closed_on_a_block(opening) and np.linalg.norm(rel[:2]) < t.holding_xy and abs(rel[2]) < t.holding_z)


def _jumps(track: Track, detection: Detection, dt: float, lost_too: bool = False) -> bool:
    """Whether ``detection`` lies more than :data:`JUMP_GATE` from where its known track predicts the block; with
    ``lost_too``, from a lost track's last estimate too."""
    unknown = (TrackStatus.NEVER_SEEN,) if lost_too else (TrackStatus.NEVER_SEEN, TrackStatus.LOST)
    return (track.status not in unknown
            and np.linalg.norm(detection.centre - track.position - track.velocity * dt) > JUMP_GATE)


def _within_the_hand(offset: np.ndarray) -> None:
    """Pull a carried block's ``offset`` from the grip site into :data:`HELD_BOX` of ``holding``'s box, in place."""
    reach_xy, reach_z = HELD_BOX * THRESHOLDS.holding_xy, HELD_BOX * THRESHOLDS.holding_z
    across = float(np.linalg.norm(offset[:2]))
    if across > reach_xy:
        offset[:2] *= reach_xy / across
    offset[2] = np.clip(offset[2], -reach_z, reach_z)


def _over_top_face(upper: np.ndarray, lower: np.ndarray) -> bool:
    """Whether a block centred at ``upper`` has its centre over the top face of one centred at ``lower`` (it can rest
    on it; overlapping less, it tips off)."""
    return bool((np.abs(upper[:2] - lower[:2]) < BLOCK_HALF_SIZE).all())


def furniture_height(xy: np.ndarray, bin_geometry: BinGeometry | None) -> float | None:
    """The top of what stands under ``xy`` (m): the bin's floor inside its walls, else the table; None beyond the
    table's edges."""
    if any(abs(xy[i] - TABLE_CENTER[i]) > TABLE_HALF_SIZE[i] for i in range(2)):
        return None
    if bin_geometry is not None and bin_geometry.inside(xy):
        return TABLE_TOP + bin_geometry.floor_thickness
    return TABLE_TOP


class BlockTracker:
    """Tracks of the blocks of one scene (by colour index), updated once per frame; ``bin_geometry``: the scene's
    bin, whose floor holds the blocks in it."""

    def __init__(self, colours: list[int], dt: float = CONTROL_DT, bin_geometry: BinGeometry | None = None) -> None:
        self.colours = list(colours)
        self.dt = dt
        self.bin_geometry = bin_geometry
        self.tracks = {colour: Track() for colour in self.colours}

    def update(self, found: list[Detection], hands: Sequence[Hand], frames: int = 1) -> dict[int, Track]:
        """Fold one frame's detections in; ``hands``: every arm's hand, the own arm's first; ``frames`` control
        steps since the last update."""
        dt = self.dt * frames
        stacked = self._stacked()
        seen = self._believable({d.colour: d for d in found if d.colour in self.tracks}, dt)
        for colour, track in self.tracks.items():
            detection, rested = seen.get(colour), track.rest_position  # before this frame: the fingers may move it
            carried = track.hand is not None and track.hand < len(hands) and not self._left_hand(track, hands, detection)
            if carried:
                self._carry(track, hands[track.hand], detection, frames)
            elif detection is not None and self._holder(colour, detection.centre, hands) is not None:
                self._measure(track, detection, dt)  # seen in a hand: where the hand has it, not where a filter lags
                track.position, track.doubted = detection.centre.copy(), 0
            elif detection is not None and not self._doubtful(track, hands, detection, dt):
                self._measure(track, detection, dt)
            else:
                self._predict(track, frames)
            holder = None if track.status == TrackStatus.NEVER_SEEN else self._holder(colour, track.position, hands)
            if holder is None:
                if carried:
                    self._let_go(track)
                track.grip_offset, track.hand = None, None
            elif track.grip_offset is None or track.hand != holder:
                hand = hands[holder]
                grasped = rested if rested is not None and in_hand(rested, hand.position, hand.opening) else track.position
                track.grip_offset, track.hand = grasped - hand.position, holder
                track.grip_offset[FINGER_AXIS] = 0.0
                track.lifted_from = float(grasped[2])
                self._carry(track, hand, detection, 0)
            if track.status != TrackStatus.NEVER_SEEN:
                self._above_furniture(track)
        self._stacks_stand(stacked)
        return self.tracks

    def _stacked(self) -> list[tuple[Track, Track]]:
        """(upper, lower) of the free blocks that stand one on the other now, lowest first: the upper's centre over the
        lower's top face, one block higher (:data:`LANDING_SLACK` aside)."""
        free = [track for track in self.tracks.values() if track.hand is None and track.status != TrackStatus.NEVER_SEEN]
        pairs = [(upper, lower) for upper in free for lower in free
                 if _over_top_face(upper.position, lower.position)
                 and abs(upper.position[2] - lower.position[2] - 2 * BLOCK_HALF_SIZE) < LANDING_SLACK]
        return sorted(pairs, key=lambda pair: pair[1].position[2])

    def _stacks_stand(self, stacked: list[tuple[Track, Track]]) -> None:
        """A block that stood on another still does while no hand holds either and it is still over it: the fingers
        coming down on a tower's top block hide its top and push its votes down, and its estimate had sunk 4 cm into
        the block under it; the hand, sent there, pressed on the tower and it fell (Unstack-6 from the camera)."""
        for upper, lower in stacked:
            if (upper.hand is None and lower.hand is None and _over_top_face(upper.position, lower.position)
                    and upper.position[2] < lower.position[2] + 2 * BLOCK_HALF_SIZE):
                upper.position[2] = lower.position[2] + 2 * BLOCK_HALF_SIZE
                upper.velocity[2] = max(upper.velocity[2], 0.0)

    def _holder(self, colour: int, position: np.ndarray, hands: Sequence[Hand]) -> int | None:
        """The hand that would hold block ``colour`` at ``position``: one closed on it, carrying no other block (a hand
        holds one). A block is first taken as held where the camera sees it in the hand, too: it rises faster than
        its filter follows (a block lifted 9 cm between two frames, its filtered centre 5 cm under the grip, was
        never taken as held, and its detections, moving with the hand, were doubted until the hand had put it down)."""
        busy = {track.hand for c, track in self.tracks.items() if c != colour and track.hand is not None}
        return next((i for i, hand in enumerate(hands)
                     if i not in busy and in_hand(position, hand.position, hand.opening)), None)

    def _believable(self, seen: dict[int, Detection], dt: float) -> dict[int, Detection]:
        """``seen`` without a block's detection that jumped from its track into another block, seen there this frame
        or standing there by its track: two blocks cannot be in one place (:data:`OVERLAP`), so it is that block
        misread. Part of a red block read as orange, 4 cm from red's centre and 20 cm from orange's, took orange's track
        there while the hand came down on orange, which it hid, and the hand went back and forth between the two; a
        yellow block lifted high in the hand read as orange while orange on the table read as yellow, and each took
        the other's place. A lost block is no exception: pink in a full bin's far corner, which the voter read as
        background for good, was lost, and eight pink votes on purple beside it took pink's track there; the expert
        then put yellow onto pink, where it rested tilted, out of ``in_bin``, and put it again for 300 steps."""
        places = [(c, other.centre) for c, other in seen.items()]
        places += [(c, track.position) for c, track in self.tracks.items()
                   if track.status not in (TrackStatus.NEVER_SEEN, TrackStatus.LOST)]
        return {colour: detection for colour, detection in seen.items()
                if not (_jumps(self.tracks[colour], detection, dt, lost_too=True)
                        and any(c != colour and np.linalg.norm(detection.centre - place) < OVERLAP for c, place in places))}

    @staticmethod
    def _left_hand(track: Track, hands: Sequence[Hand], detection: Detection | None) -> bool:
        """Whether ``detection`` shows a held block away from its hand; it is then a free block again."""
        hand = hands[track.hand]
        if detection is None or np.linalg.norm(detection.centre - hand.position - track.grip_offset) <= HELD_GATE:
            track.doubted = 0
            return False
        if THRESHOLDS.closed_on_a_block(hand.opening):
            track.doubted += 1
            if track.doubted < DOUBT_FRAMES:
                return False
        track.doubted = 0
        track.grip_offset, track.hand, track.status = None, None, TrackStatus.LOST  # measured afresh
        return True

    @staticmethod
    def _doubtful(track: Track, hands: Sequence[Hand], detection: Detection, dt: float) -> bool:
        """Whether ``detection`` puts a block no hand is near too far from its track to believe yet."""
        if not _jumps(track, detection, dt) or any(np.linalg.norm(hand.position - track.position) < HAND_REACH for hand in hands):
            track.doubted = 0
            return False
        track.doubted += 1
        if track.doubted < DOUBT_FRAMES:
            return True
        track.doubted, track.status = 0, TrackStatus.LOST  # it did move: measured afresh
        return False

    def _measure(self, track: Track, detection: Detection, dt: float) -> None:
        if track.status in (TrackStatus.NEVER_SEEN, TrackStatus.LOST):
            track.position, track.velocity = detection.centre.copy(), np.zeros(3)
        else:
            predicted = track.position + track.velocity * dt
            residual = detection.centre - predicted
            track.position = predicted + ALPHA * residual
            track.velocity = track.velocity + BETA / dt * residual
        track.sigma = detection.sigma.copy()
        track.status, track.unseen, track.pixels = TrackStatus.VISIBLE, 0, detection.pixels
        if np.linalg.norm(track.velocity) < REST_SPEED:
            track.rest_position = track.position.copy()

    @staticmethod
    def _carry(track: Track, hand: Hand, detection: Detection | None, frames: int) -> None:
        """A block in ``hand``: where the hand carries it, seen or not (``frames`` since the last update), at the
        offset it keeps from the grip site, which its detections near there correct (:data:`OFFSET_GAIN`)."""
        if detection is not None and frames:
            residual = detection.centre - hand.position - track.grip_offset
            residual[FINGER_AXIS] = 0.0
            if np.linalg.norm(residual) <= HELD_GATE:
                track.grip_offset = track.grip_offset + OFFSET_GAIN * residual
        track.grip_offset[2] = min(track.grip_offset[2], max(track.lifted_from - hand.position[2], HELD_HANG))
        _within_the_hand(track.grip_offset)
        track.position = hand.position + track.grip_offset
        track.velocity = np.asarray(hand.velocity, dtype=float).copy()
        track.sigma = np.maximum(track.sigma, SIGMA_HELD)
        track.rest_position = None
        if detection is None:
            track.unseen += frames
            track.status, track.pixels = TrackStatus.HELD, 0
        else:
            track.status, track.unseen, track.pixels = TrackStatus.VISIBLE, 0, detection.pixels

    def _let_go(self, track: Track) -> None:
        """The fingers opened on ``track``'s block: it falls onto the highest of the furniture and the tops of the other
        blocks under it (their tops no higher than its bottom, :data:`LANDING_SLACK` aside) and lies there, until the
        camera sees it elsewhere. It rests on a block only with its centre over that block's top face; overlapping one
        less, it tips off it and lands beside it (a block let go 3 cm off a block's centre in a crowded bin slid off it
        onto the floor, while its estimate stayed on top, above the rim, and the hand was sent to put it in again).
        A block with its centre over a lower block's top face lands on it however deep the estimates overlap: the
        hand brought it from above, so it cannot be inside it (green, let go onto red with its estimate 2 cm low,
        "fell" to the table inside red, and the planner, reading red on green, lifted red with green on it: Swap-2)."""
        xy, centre = track.position[:2], track.position[2]
        under = [other for other in self.tracks.values()
                 if other is not track and other.hand is None and np.isfinite(other.position).all()
                 and (np.abs(other.position[:2] - xy) < 2 * BLOCK_HALF_SIZE).all()
                 and (other.position[2] + BLOCK_HALF_SIZE <= centre - BLOCK_HALF_SIZE + LANDING_SLACK
                      or (_over_top_face(track.position, other.position) and other.position[2] < centre))]
        tops = [other.position[2] + BLOCK_HALF_SIZE for other in under if _over_top_face(track.position, other.position)]
        furniture = furniture_height(xy, self.bin_geometry)
        supports = tops if furniture is None else [furniture, *tops]
        if supports:  # beyond the table's edges, with nothing under it, it falls out of reach: the camera will say where
            track.position[2] = max(supports) + BLOCK_HALF_SIZE
        for other in under:  # one it overlaps below its landing, it tipped off: beside it
            if other.position[2] > track.position[2] - BLOCK_HALF_SIZE:
                away = xy - other.position[:2]
                track.position[:2] = other.position[:2] + away * (2 * BLOCK_HALF_SIZE / max(np.abs(away).max(), 1e-6))
        track.velocity = np.zeros(3)

    def _above_furniture(self, track: Track) -> None:
        """No block lies lower than the furniture under it lets it: votes pushed into the table by the fingers over a
        block once put it 14 mm under the table's top, and the hand, unable to reach that low, never closed on it."""
        floor = furniture_height(track.position[:2], self.bin_geometry)
        if floor is not None and track.position[2] < floor + BLOCK_HALF_SIZE:
            track.position[2] = floor + BLOCK_HALF_SIZE
            track.velocity[2] = max(track.velocity[2], 0.0)

    def _predict(self, track: Track, frames: int) -> None:
        """An unseen free block stays where it was, unless nothing holds it up there: beyond the table's edges it fell to
        the floor (a block knocked off the table was last seen falling, 7 cm under the table's top; its estimate stayed
        in mid-air, and the hand tried to pick it there for 150 steps)."""
        if track.status == TrackStatus.NEVER_SEEN:
            return
        if furniture_height(track.position[:2], self.bin_geometry) is None:
            track.position[2] = BLOCK_HALF_SIZE
        track.unseen += frames
        track.pixels = 0
        track.velocity = np.zeros(3)
        track.sigma = np.minimum(track.sigma + SIGMA_GROWTH * frames, SIGMA_MAX)
        track.status = TrackStatus.LOST if track.unseen >= LOST_FRAMES else TrackStatus.OCCLUDED

    def arrays(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Positions, velocities and standard deviations, (N, 3) each, in ``colours`` order."""
        tracks = [self.tracks[c] for c in self.colours]
        return (np.array([t.position for t in tracks]), np.array([t.velocity for t in tracks]),
                np.array([t.sigma for t in tracks]))
