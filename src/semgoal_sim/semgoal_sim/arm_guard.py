"""Two arms at one table keep apart: a separation guard on their commands, below the policies. No MuJoCo.

Each arm is taken, in the table plane, as the segment from its shoulder to its grip site: over random motions of the
Fetch arm under the mocap, every link from the shoulder to the gripper stayed within 5.3 cm of it (the elbow rises
above the segment, not beside it). Two arms keep :data:`SEPARATION` between their segments. When a command would
bring them closer, one arm yields: not one with a block in hand, then not one at work (reaching, or going down to
grasp: two arms reaching for blocks nearer together than the separation took turns drawing back, each one's descent
counted as holding still), then the one whose own move does it, then the second. It rises off the table and draws
back towards its shoulder, its fingers keeping what they hold (a block in hand is drawn back no further than its own
table edge), while the other keeps its right of way until the two are :data:`RELEASE` apart again, and holds still in
the plane where its move would close in on the other before that has drawn back. A yielding arm's step goes on
afterwards (the executive's stall rule bounds the wait), as a person on a shared bench waits for the other's hand.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from semgoal_core.geometry import TABLE_TOP

SEPARATION = 0.2
"""Least distance (m) between two arms' segments: two 5.3 cm envelopes, the links' 3 cm half-thickness each, and
a margin."""
RELEASE = SEPARATION + 0.01
"""Distance (m) at which the arm with the right of way gives it up again: 1 cm past the separation, so the yielding arm
draws back no further than it must (4 cm past it, DC-4's two arms took 1-2 % more control steps)."""
MIN_GAP = 0.06
"""Least distance (m) between the two arms' links themselves (their meshes): forearms touched with their chains
19.5 cm apart, one arm drawn back as far as it goes."""
DISTAL_POINTS = 3
"""The chain's points a command moves at once (wrist, gripper, grip site); the shoulder and the elbow follow."""
STILL = 0.1
"""A command this small (5 mm a step) is an arm holding still: idle, or closing its fingers."""
YIELD_SPEED = 0.5
"""A yielding arm draws back at 2.5 cm a step: at full speed a block hanging low in its fingers slid out."""
CLEAR_HEIGHT = TABLE_TOP + 0.12
"""A yielding arm first rises to this grip height (m): it draws back over the blocks, not through them."""


def segment_distance(p0: np.ndarray, p1: np.ndarray, q0: np.ndarray, q1: np.ndarray) -> float:
    """Least distance between the segments p0-p1 and q0-q1 (points in 2-D or 3-D): the closest pair by the clamped
    closed form (each parameter clamped to [0, 1], the other one recomputed)."""
    d1, d2, r = p1 - p0, q1 - q0, p0 - q0
    a, e, f = float(d1 @ d1), float(d2 @ d2), float(d2 @ r)
    if a < 1e-12 and e < 1e-12:
        return float(np.linalg.norm(r))
    if a < 1e-12:
        s, t = 0.0, np.clip(f / e, 0.0, 1.0)
    else:
        c = float(d1 @ r)
        if e < 1e-12:
            s, t = np.clip(-c / a, 0.0, 1.0), 0.0
        else:
            b = float(d1 @ d2)
            denominator = a * e - b * b
            s = np.clip((b * f - c * e) / denominator, 0.0, 1.0) if denominator > 1e-12 else 0.0
            t = (b * s + f) / e
            if t < 0.0:
                s, t = np.clip(-c / a, 0.0, 1.0), 0.0
            elif t > 1.0:
                s, t = np.clip((b - c) / a, 0.0, 1.0), 1.0
    return float(np.linalg.norm(p0 + d1 * s - q0 - d2 * t))


def chain_distance(a: np.ndarray, b: np.ndarray) -> float:
    """Least distance between two polylines (K, 3)."""
    return min(segment_distance(a[i], a[i + 1], b[j], b[j + 1]) for i in range(len(a) - 1) for j in range(len(b) - 1))


@dataclass
class ArmGuard:
    """The separation guard of two arms (module doc)."""

    step_size: float
    """Metres a command of 1 moves the grip in one control step."""
    edges: np.ndarray = field(default_factory=lambda: np.full(2, np.nan))
    """(2,) x (m) of each arm's own table edge, less a margin: a yielding arm with a block in hand draws back no
    further (drawn back over the edge, a block low in the fingers fell off the table); NaN: no limit."""
    distal: int = DISTAL_POINTS
    right_of_way: int | None = None
    yields: int = 0
    """Control steps on which an arm yielded, since :meth:`reset`."""

    def reset(self) -> None:
        self.right_of_way, self.yields = None, 0

    def _moved(self, chains: np.ndarray, actions: np.ndarray, arms: tuple[int, ...] = (0, 1)) -> np.ndarray:
        """The chains after ``arms`` move by their commands: their last :attr:`distal` points (wrist to grip)."""
        moved = chains.copy()
        for arm in arms:
            moved[arm, -self.distal:] += actions[arm, :3] * self.step_size
        return moved

    @staticmethod
    def apart(chains: np.ndarray) -> float:
        return chain_distance(chains[0], chains[1])

    def _too_close(self, moved: np.ndarray, near: bool) -> bool:
        """Whether the arms at ``moved`` are too close: their chains less than :data:`SEPARATION` apart, or their
        links within :data:`MIN_GAP` (``near``)."""
        return near or self.apart(moved) < SEPARATION

    def __call__(self, chains: np.ndarray, actions: np.ndarray, heights: np.ndarray, holding: np.ndarray,
                 clearance: float = np.inf, towards: np.ndarray | None = None) -> np.ndarray:
        """The commands (2, 4) to send, given each arm's chain (2, K, 3: shoulder first, grip last), its command
        (2, 4), its grip's height (2,), whether it holds a block (2,), the least distance between the two arms'
        links now (``clearance``, m) and the unit vector from the first arm's nearest point to the second's."""
        near = clearance < MIN_GAP
        if self.right_of_way is not None and self.apart(chains) >= RELEASE and clearance >= MIN_GAP:
            self.right_of_way = None
        if self.right_of_way is None and not self._too_close(self._moved(chains, actions), near):
            return actions
        if self.right_of_way is None:
            closes = [self._too_close(self._moved(chains, actions, (arm,)), False) for arm in (0, 1)]
            moving = np.linalg.norm(actions[:, :3], axis=1) > STILL  # reaching, or going down to grasp
            # who goes on: the arm with a block in hand, then one at work (moving), then one whose own move keeps
            # the distance, then the first
            ranks = [(bool(holding[arm]), bool(moving[arm]), not closes[arm], arm == 0) for arm in (0, 1)]
            self.right_of_way = int(ranks[1] > ranks[0])
        first, yielder = self.right_of_way, 1 - self.right_of_way
        actions = np.array(actions, dtype=np.float64)
        back = chains[yielder, 0, :2] - chains[yielder, -1, :2]
        if near and towards is not None:  # the links within MIN_GAP: away from the other's nearest point, in the plane
            away = (-towards if yielder == 0 else towards)[:2]
            back = away if float(np.linalg.norm(away)) > 1e-6 else back
        shoulder_x, grip_x, edge = chains[yielder, 0, 0], chains[yielder, -1, 0], self.edges[yielder]
        at_edge = holding[yielder] and abs(grip_x - shoulder_x) <= abs(edge - shoulder_x)  # NaN: never
        actions[yielder, :2] = 0.0 if at_edge else YIELD_SPEED * back / max(float(np.linalg.norm(back)), 1e-9)
        actions[yielder, 2] = 1.0 if heights[yielder] < CLEAR_HEIGHT else 0.0
        actions[yielder, 3] = -1.0 if holding[yielder] else 0.0
        apart = self.apart(self._moved(chains, actions))
        if near:  # the first moves no nearer the other while the links are within MIN_GAP, closing in or not
            normal = np.zeros(3) if towards is None else (towards if first == 0 else -towards)
            actions[first, :3] -= max(0.0, float(actions[first, :3] @ normal)) * normal
        elif apart < SEPARATION and apart < self.apart(chains):  # the first waits in the plane until there is room
            actions[first, :2] = 0.0
        self.yields += 1
        return actions
