"""The semantic layer, defined once: scenes, predicates, literals, the semantic vector and sub-goal types.

Imports neither rclpy nor MuJoCo: the planner, the policy, the nodes and the tests all read the
vocabulary from here.

Predicates (paper, "Semantic goal representations"), evaluated on block centres, the grip site and the
finger opening. Thresholds (see :class:`Thresholds`) follow DECSTR (Akakzia et al. 2021), which uses the
same predicates on the same Fetch blocks (5 cm cubes), except for close:

- ``close(a, b)``: centre distance <= 0.10 m (symmetric; one vector entry per unordered pair). DECSTR
  uses 0.09 m; the Fetch fingers open along y and reach 5.5 cm to each side, so a block released next
  to another needs some room, and three blocks close to each other (MC-3) only fit a triangle with
  sides up to 0.09 m when the threshold leaves a margin. 0.10 m still means "at most one block width
  between them".
- ``above(a, b)``: ``a`` rests on ``b``: xy distance < 0.05 m and 0.03 m < z_a - z_b < 0.07 m.
- ``holding(a)``: ``a`` sits between the fingers (xy within 0.03 m of the grip site, z within 0.04 m:
  a block grasped near its top edge hangs 3.4 cm below the grip site and is lifted all the same)
  and the fingers are closed on it (opening between 0.03 and 0.07 m: a 5 cm block, with give), and
  no other block sits between them: the hand holds one block, as the planner's domain has it. A grasp
  low on a stacked block pinches the top of the one below too and lifts both; that is no pick of
  either. A grasped block still touching the table is held.
- ``in_bin(a)``: the centre lies inside the bin walls (xy) and below the rim: a block lying on the rim
  is not in the bin.
"""

from __future__ import annotations

import functools
import itertools
import re
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field

import numpy as np

BLOCK_HALF_SIZE = 0.025
"""Half edge of every block (m): the Fetch benchmark's 5 cm cube."""

BLOCK_COLOURS: dict[str, tuple[float, float, float, float]] = {
    "red": (0.85, 0.12, 0.12, 1.0),
    "green": (0.13, 0.70, 0.20, 1.0),
    "blue": (0.15, 0.30, 0.90, 1.0),
    "yellow": (0.95, 0.80, 0.10, 1.0),
    "orange": (0.98, 0.50, 0.08, 1.0),
    "purple": (0.55, 0.20, 0.75, 1.0),
    "cyan": (0.10, 0.80, 0.85, 1.0),
    "pink": (0.97, 0.55, 0.75, 1.0),
}
"""Block names in canonical order, with their RGBA colours: the paper's four, then the tabletop's (names an operator
says, hues apart from the first four's)."""
PAPER_BLOCKS = 4
"""The paper's scenes use the first four colours; the camera's randomisation draws a shade for these only."""

SYMMETRIC_PREDICATES = frozenset({"close"})
"""Predicates whose two arguments may come in either order: the state stores them in object order."""
PREDICATE_ARITY = {"close": 2, "above": 2, "holding": 1, "in_bin": 1}
ONE_AGENT_REGIONS = {"put_in_bin": "bin"}
"""Sub-goal types whose place a person's hand keeps out of while an arm works there, and that place's name."""


@dataclass(frozen=True)
class Thresholds:
    """Geometric thresholds of the predicates (m). Defaults follow DECSTR's Fetch blocks."""

    close_distance: float = 0.10
    """close(a, b) when the block centres are at most this far apart (DECSTR: 0.09; see module doc)."""
    above_xy: float = 0.05
    """above(a, b) needs the centres closer than this in the table plane..."""
    above_dz_min: float = 0.03
    """...and a above b by more than this..."""
    above_dz_max: float = 0.07
    """...and by less than this (one block height is 0.05)."""
    holding_xy: float = 0.03
    """holding(a): block centre within this of the grip site in the table plane..."""
    holding_z: float = 0.04
    """...and vertically..."""
    holding_opening_min: float = 0.03
    """...and finger opening (sum of both finger joints, 0 = shut, 0.1 = open) at least this..."""
    holding_opening_max: float = 0.07
    """...and at most this: closed on a 5 cm block."""
    fallen_depth: float = 0.10
    """A block whose centre lies this far below the table top has fallen off the table (see :func:`fallen_blocks`)."""

    def closed_on_a_block(self, finger_opening: float) -> bool:
        """Whether fingers this far open are closed on a block (neither open nor shut on nothing)."""
        return self.holding_opening_min <= finger_opening <= self.holding_opening_max


THRESHOLDS = Thresholds()


def _once_per_bin(method):
    """A frozen geometry's pure method, worked out once per bin and argument (the controller asks for the bin's spots
    every step); the arrays it hands out are read-only, as all share them."""
    @functools.cache
    def kept(self, *args):
        result = method(self, *args)
        result.setflags(write=False)
        return result

    return functools.wraps(method)(kept)


@dataclass(frozen=True)
class BinGeometry:
    """The open bin of the desk-cleanup scene: a floor and four walls on the table."""

    center: tuple[float, float] = (1.30, 1.00)
    """Centre of the bin in the table plane (m)."""
    inner_half_size: tuple[float, float] = (0.16, 0.065)
    """Half of the inner extent in x and y (m): a row of four blocks along x, 8 cm apart, so the last
    block still has 3 cm of play between two binned ones (at 6.5 cm, puts into a three-quarter-full
    bin missed); in y the open fingers (outer faces 5.5 cm from the block's centre) clear the walls."""
    wall_height: float = 0.04
    """Height of the walls above the floor's top (m): low, so blocks are dropped in from above."""
    back_wall_height: float = 0.10
    """Height of the far wall (+y, away from the robot) above the floor's top (m): a backboard. The bin
    stands 3.5 cm from the desk's far edge, and a block let go moving, or pushed, over a low far wall fell
    off the desk, out of reach (once most DC-4 failures). The rim (``contains``) stays at
    :attr:`wall_height`."""
    wall_thickness: float = 0.01
    floor_thickness: float = 0.01
    rows: int = 1
    """Rows of :meth:`slots` along y (the tabletop's bin takes two)."""
    keep_out: float = 0.06
    """How far outside the inner walls (m) a block put on the table stays (the expert's table spots)."""
    row_slots: int = 4
    """Slots in a row."""

    @_once_per_bin
    def slots(self, count: int | None = None) -> np.ndarray:
        """(count, 2) resting spots for blocks (all :attr:`rows` x :attr:`row_slots` when None): a row along x,
        evenly spaced; with more rows, each row's spots between the next row's (fingers opening along y clear a
        neighbour half a spacing off in x). With one row, ``count`` spots spread over its length."""
        if self.rows == 1:
            count = self.row_slots if count is None else count
            spacing = 2 * self.inner_half_size[0] / count
            xs = self.center[0] - self.inner_half_size[0] + spacing * (np.arange(count) + 0.5)
            return np.column_stack([xs, np.full(count, self.center[1])])
        spacing = 2 * self.inner_half_size[0] / (self.row_slots + 0.5)
        row_gap = 2 * self.inner_half_size[1] / self.rows
        spots = [np.column_stack([self.center[0] - self.inner_half_size[0] + spacing * (np.arange(self.row_slots) + 0.5 + 0.5 * (row % 2)),
                                  np.full(self.row_slots, self.center[1] - self.inner_half_size[1] + row_gap * (row + 0.5))])
                 for row in range(self.rows)]
        return np.vstack(spots)[:count]

    @_once_per_bin
    def interior(self, step: float = 0.005, margin: float = 0.003) -> np.ndarray:
        """(M, 2) grid of block centres at which a block lies on the floor, ``margin`` clear of the walls."""
        reach = np.asarray(self.inner_half_size) - BLOCK_HALF_SIZE - margin
        xs, ys = (np.arange(-r, r + 1e-9, step) + c for r, c in zip(reach, self.center, strict=True))
        return np.array(np.meshgrid(xs, ys, indexing="ij")).reshape(2, -1).T

    def inside(self, points: np.ndarray) -> np.ndarray:
        """Whether ``points`` (..., 2 or more: x, y first) lie inside the inner walls in the table plane."""
        return np.all(np.abs(np.asarray(points)[..., :2] - self.center) < self.inner_half_size, axis=-1)

    def contains(self, positions: np.ndarray, table_height: float) -> np.ndarray:
        """in_bin for block centres ``positions`` (N, 3): inside the walls and below the rim."""
        positions = np.asarray(positions)
        rim_top = table_height + self.floor_thickness + self.wall_height
        return self.inside(positions) & (positions[:, 2] < rim_top)


TABLETOP_BIN = BinGeometry(center=(1.30, 0.955), inner_half_size=(0.18, 0.11), back_wall_height=0.10, rows=2,
                           keep_out=0.1)
"""The tabletop's bin takes eight blocks: two rows of four, 8 cm apart in a row as on the desk, each row's spots
between the other's; rows 11 cm apart, so the open fingers (5.5 cm each side of a block) clear a block in the
other row and the walls. It stands 2.5 cm from the table's far edge, as the desk's does. Table puts stay 10 cm off
its inner walls: at 6 cm the open fingers, coming down on a block there, stood on the front wall."""


@dataclass(frozen=True)
class Scene:
    """A scene: its blocks, the predicates of its semantic state, its sub-goal types, a bin or not."""

    name: str
    objects: tuple[str, ...]
    predicates: tuple[str, ...]
    subgoal_types: tuple[str, ...]
    bin: BinGeometry | None = None
    block_counts: tuple[int, ...] = field(default=())
    """Numbers of blocks the scene can be built with (desk cleanup: 2 to 4); empty = all objects."""
    reach_height: float = 0.35
    """How high above the table top (m) the gripper may be driven: the Fetch benchmark's box; the tabletop's towers
    of eight need more (the arm reaches 0.67 m above the table there)."""
    stiff_stacking: bool = False
    """Blocks meet blocks through stiff contacts (``semgoal_sim.scene.STACKING_CONTACT``), so that a tower of six
    stands as a real one does; the paper's scenes keep the Fetch benchmark's soft contacts, as Table 1 was measured
    with them."""

    @property
    def max_blocks(self) -> int:
        return len(self.objects)


SCENES: dict[str, Scene] = {
    scene.name: scene
    for scene in (
        # Paper, "Experiments": 2 blocks use close, above, holding; 3 blocks close, holding;
        # desk cleanup holding and in-bin. Sub-goal types from the paper's table of goals.
        Scene("two_blocks", ("red", "green"), ("close", "above", "holding"),
              ("pick", "put_near", "put_away", "put_on")),
        Scene("three_blocks", ("red", "green", "blue"), ("close", "holding"),
              ("pick", "put_near", "put_away")),
        Scene("desk_cleanup", ("red", "green", "blue", "yellow"), ("holding", "in_bin"),
              ("pick", "put_on_table", "put_in_bin"), bin=BinGeometry(), block_counts=(2, 3, 4)),
        # Beyond the paper: one table for every predicate, towers of any height and a bin for eight.
        Scene("tabletop", tuple(BLOCK_COLOURS), tuple(PREDICATE_ARITY),
              ("pick", "put_near", "put_away", "put_on", "put_on_table", "put_in_bin"), bin=TABLETOP_BIN,
              block_counts=tuple(range(2, len(BLOCK_COLOURS) + 1)), reach_height=0.5, stiff_stacking=True),
    )
}
PAPER_SCENES = ("two_blocks", "three_blocks", "desk_cleanup")
TAKE_OUT = "take_out"
"""A pseudo sub-goal type for scenes with a bin: ``put_on_table`` of a block that starts in the bin, reported apart
by evaluation (training draws it only from starts with blocks in the bin, and can forget it)."""
"""The paper's scenes (Table 1), each with its own trained actor."""


@dataclass(frozen=True, order=True)
class Literal:
    """A grounded predicate with a truth value: ``close(red,green)`` or ``not close(red,green)``."""

    name: str
    args: tuple[str, ...]
    value: bool = True

    def __str__(self) -> str:
        atom = f"{self.name}({','.join(self.args)})"
        return atom if self.value else f"not {atom}"

    def negated(self) -> Literal:
        return Literal(self.name, self.args, not self.value)


class VocabularyError(ValueError):
    """A literal or goal that does not fit the scene; the message says what is wrong and what is valid."""


_LITERAL = re.compile(r"^\s*(?P<neg>not\s+|!\s*|~\s*|¬\s*)?(?P<name>[A-Za-z_][\w-]*)\s*\((?P<args>[^()]*)\)\s*$", re.IGNORECASE)
_NEGATED = re.compile(r"^\s*(?:not|!|~|¬)\s*\((?P<literal>[^()]*\([^()]*\)\s*)\)\s*$", re.IGNORECASE)
"""A negation written as a call: ``not(in_bin(red))``."""
PREDICATE_ALIASES = {"on": "above", "near": "close", "inbin": "in_bin", "held": "holding"}
"""Other names people give the predicates in a literal (blocksworld's ``on(a,b)``): read as the predicate itself."""
BIN_NAMES = ("bin", "box", "basket", "trash")
"""What a literal may call the bin, as its second argument: ``in(red,bin)``."""


def parse_literal(text: str) -> Literal:
    """Parse ``close(red,green)``, ``not in_bin(red)``, ``!holding(blue)``, ``not(in_bin(red))`` into a
    :class:`Literal`."""
    if wrapped := _NEGATED.match(text):
        return parse_literal(wrapped["literal"]).negated()
    match = _LITERAL.match(text)
    if not match:
        raise VocabularyError(f"cannot read literal {text!r}: expected e.g. 'close(red,green)' or 'not in_bin(red)'")
    args = tuple(arg.strip().lower() for arg in match["args"].split(",")) if match["args"].strip() else ()
    name = match["name"].lower().replace("-", "_")
    if name in ("in", "inside") and len(args) == 2 and args[1] in BIN_NAMES:  # "in(red,bin)", as planning domains say it
        name, args = "in_bin", args[:1]
    return Literal(PREDICATE_ALIASES.get(name, name), args, value=match["neg"] is None)


_ABSENT = {"close": "it does not say which blocks are near each other", "above": "no block stands on another there",
           "holding": "it does not say which block is in the hand", "in_bin": "it has no bin"}
"""What a scene without a predicate lacks, as a person would say it."""


class SemanticLayout:
    """The canonical semantic vector of one scene: which literal each entry holds, and conversions.

    Entry order: for each predicate of the scene in vocabulary order, its groundings in object order
    (close over unordered pairs, above over ordered pairs, unary predicates over objects).
    """

    def __init__(self, scene: Scene) -> None:
        self.scene = scene
        self.objects = scene.objects
        atoms: list[tuple[str, tuple[str, ...]]] = []
        for name in scene.predicates:
            if name == "close":
                atoms += [(name, pair) for pair in itertools.combinations(scene.objects, 2)]
            elif name == "above":
                atoms += [(name, pair) for pair in itertools.permutations(scene.objects, 2)]
            else:
                atoms += [(name, (obj,)) for obj in scene.objects]
        self.atoms: tuple[tuple[str, tuple[str, ...]], ...] = tuple(atoms)
        self._index = {atom: i for i, atom in enumerate(self.atoms)}
        # Per predicate: vector entries and object indices of their arguments, for vectorised evaluation.
        self.groundings: dict[str, tuple[np.ndarray, np.ndarray]] = {}
        for name in scene.predicates:
            entries = [k for k, (n, _) in enumerate(self.atoms) if n == name]
            args = [[scene.objects.index(a) for a in self.atoms[k][1]] for k in entries]
            self.groundings[name] = (np.array(entries), np.array(args))
        self.spans: dict[str, tuple[slice, tuple[np.ndarray, ...]]] = {
            name: (slice(int(entries[0]), int(entries[-1]) + 1) if len(entries) else slice(0, 0),
                   tuple(np.ascontiguousarray(column) for column in args.T))
            for name, (entries, args) in self.groundings.items()}
        """Per predicate: its entries as one slice (each predicate's are contiguous) and each argument's object
        indices, for :func:`evaluate`."""
        self._present_entries: dict[bytes, np.ndarray] = {}

    def present_entries(self, present: np.ndarray) -> np.ndarray:
        """(size,) bool: the entries whose arguments are all ``present`` (a world's blocks; kept per set of them,
        as a world asks for its own every step)."""
        key = present.tobytes()
        entries = self._present_entries.get(key)
        if entries is None:
            entries = np.ones(self.size, dtype=bool)
            for indices, args in self.groundings.values():
                if len(indices):
                    entries[indices] = present[args].all(axis=1)
            self._present_entries[key] = entries
        return entries

    @property
    def size(self) -> int:
        return len(self.atoms)

    def canonical(self, name: str, args: Sequence[str]) -> tuple[str, tuple[str, ...]]:
        """The atom as stored (close is symmetric: its arguments in object order)."""
        args = tuple(args)
        if name in SYMMETRIC_PREDICATES and len(args) == 2 and all(a in self.objects for a in args):
            args = tuple(sorted(args, key=self.objects.index))
        return name, args

    def validate(self, literal: Literal, objects: Iterable[str] | None = None) -> Literal:
        """Check a literal against the scene; raise :class:`VocabularyError` naming what is valid."""
        allowed = tuple(objects) if objects is not None else self.objects
        if literal.name not in PREDICATE_ARITY:
            raise VocabularyError(f"unknown predicate {literal.name!r} in {literal}: known are {', '.join(PREDICATE_ARITY)}")
        if literal.name not in self.scene.predicates:
            raise VocabularyError(f"predicate {literal.name!r} is not used in scene {self.scene.name!r} "
                                  f"(it uses {', '.join(self.scene.predicates)}): {_ABSENT[literal.name]}")
        arity = PREDICATE_ARITY[literal.name]
        if len(literal.args) != arity:
            raise VocabularyError(f"{literal}: {literal.name} takes {arity} argument(s), got {len(literal.args)}")
        for arg in literal.args:
            if arg not in allowed:
                raise VocabularyError(f"unknown object {arg!r} in {literal}: objects are {', '.join(allowed)}")
        if arity == 2 and literal.args[0] == literal.args[1]:
            raise VocabularyError(f"{literal}: a block cannot be related to itself")
        name, args = self.canonical(literal.name, literal.args)
        return Literal(name, args, literal.value)

    def index(self, literal: Literal) -> int:
        return self._index[self.canonical(literal.name, literal.args)]

    def index_of_atom(self, atom: tuple[str, tuple[str, ...]]) -> int:
        """The entry of an atom as stored (:meth:`canonical`)."""
        return self._index[atom]

    def check_state(self, objects: Sequence[str], literals: Iterable[Literal], named: Iterable[str] = ()) -> None:
        """Raise :class:`VocabularyError` unless a semantic state could be one of this scene's: its objects
        distinct blocks of the scene, as many as it is built with, every literal valid in the scene (the vector
        covers absent blocks too, as false), every one that holds and every block named (fallen, moving) among
        the objects. A state that fails is not planned on."""
        counts = self.scene.block_counts or (len(self.objects),)
        if len(set(objects)) != len(objects) or not set(objects) <= set(self.objects) or len(objects) not in counts:
            raise VocabularyError(f"objects [{', '.join(objects)}]: scene {self.scene.name!r} has "
                                  f"{' or '.join(map(str, counts))} distinct blocks of {', '.join(self.objects)}")
        for literal in literals:
            self.validate(literal, objects if literal.value else None)
        for name in named:
            if name not in objects:
                raise VocabularyError(f"block {name!r} is named but not among the objects [{', '.join(objects)}]")

    def encode(self, literals: Iterable[Literal]) -> tuple[np.ndarray, np.ndarray]:
        """(target, mask) float32 vectors: mask 1 where a literal constrains the entry, target its value.

        Raises :class:`VocabularyError` for contradictory literals (the same atom true and false).
        """
        target = np.zeros(self.size, dtype=np.float32)
        mask = np.zeros(self.size, dtype=np.float32)
        for literal in literals:
            literal = self.validate(literal)
            i = self.index(literal)
            if mask[i] and bool(target[i]) != literal.value:
                raise VocabularyError(f"contradictory goal: both {literal} and {literal.negated()}")
            mask[i], target[i] = 1.0, float(literal.value)
        return target, mask

    def decode(self, target: np.ndarray, mask: np.ndarray | None = None) -> list[Literal]:
        """Literals of the entries selected by ``mask`` (all entries when None)."""
        selected = range(self.size) if mask is None else np.flatnonzero(np.asarray(mask) > 0.5)
        return [Literal(*self.atoms[i], bool(target[i] > 0.5)) for i in selected]

    def true_literals(self, vector: np.ndarray) -> list[Literal]:
        """The literals that hold, e.g. for display: ``[close(red,green), holding(red)]``."""
        return [Literal(*self.atoms[i]) for i in np.flatnonzero(np.asarray(vector) > 0.5)]

    def readable(self, vector: np.ndarray) -> str:
        return " & ".join(map(str, self.true_literals(vector))) or "(nothing holds)"


LAYOUTS: dict[str, SemanticLayout] = {name: SemanticLayout(scene) for name, scene in SCENES.items()}


def rests_on(top: np.ndarray, bottom: np.ndarray, thresholds: Thresholds = THRESHOLDS) -> np.ndarray:
    """The geometry of ``above``, for block centres (..., 3): also where a scene has no above predicate."""
    return _rests_on(np.asarray(top) - np.asarray(bottom), thresholds)


def _rests_on(delta: np.ndarray, thresholds: Thresholds) -> np.ndarray:
    """:func:`rests_on` of the offsets top - bottom (..., 3); one column at a time, as np.linalg.norm sums them."""
    dx, dy, dz = delta[..., 0], delta[..., 1], delta[..., 2]
    return (np.sqrt(dx * dx + dy * dy) < thresholds.above_xy) & (dz > thresholds.above_dz_min) & (dz < thresholds.above_dz_max)


def held_alone(block_positions: np.ndarray, grip_position: np.ndarray, finger_opening: float,
               present: np.ndarray | None = None, thresholds: Thresholds = THRESHOLDS) -> np.ndarray:
    """(N,) bool: which block the closed fingers hold, alone (the geometry of ``holding``, module doc)."""
    positions = np.asarray(block_positions, dtype=np.float64)
    if not thresholds.closed_on_a_block(finger_opening):
        return np.zeros(len(positions), dtype=bool)  # fingers open, or shut on nothing: most states, at once
    rel = positions - np.asarray(grip_position)
    flat = rel[:, :2]
    between = ((np.sqrt((flat * flat).sum(axis=1)) < thresholds.holding_xy)  # np.linalg.norm's sums
               & (np.abs(rel[:, 2]) < thresholds.holding_z))
    if present is not None:
        between &= np.asarray(present, dtype=bool)
    return between & (between.sum() == 1)


def evaluate(
    layout: SemanticLayout,
    block_positions: np.ndarray,
    grip_position: np.ndarray,
    finger_opening: float,
    table_height: float,
    present: np.ndarray | None = None,
    thresholds: Thresholds = THRESHOLDS,
    other_hands: Sequence[tuple[np.ndarray, float]] = (),
) -> np.ndarray:
    """The semantic vector (bool) of one world state.

    :param block_positions: (N, 3) block centres in the scene's object order (m).
    :param grip_position: (3,) grip site between the fingers (m).
    :param finger_opening: sum of both finger joint positions (m).
    :param table_height: z of the table top (m).
    :param present: (N,) bool, False for a block slot the scene was built without (its entries stay false).
    :param other_hands: grip position and finger opening of each other arm: ``holding`` is in any hand.
    """
    positions = np.asarray(block_positions, dtype=np.float64)
    present = None if present is None else np.asarray(present, dtype=bool)
    vector = np.empty(layout.size, dtype=bool)
    for name, (span, columns) in layout.spans.items():  # take(): a fancy index costs three times as much here
        if name == "close":
            delta = positions.take(columns[0], axis=0) - positions.take(columns[1], axis=0)
            vector[span] = np.sqrt((delta * delta).sum(axis=1)) <= thresholds.close_distance  # np.linalg.norm's sums
        elif name == "above":
            vector[span] = _rests_on(positions.take(columns[0], axis=0) - positions.take(columns[1], axis=0), thresholds)
        elif name == "holding":
            held = held_alone(positions, grip_position, finger_opening, present, thresholds)
            for grip, opening in other_hands:
                held = held | held_alone(positions, grip, opening, present, thresholds)
            vector[span] = held[columns[0]]
        else:  # in_bin
            vector[span] = layout.scene.bin.contains(positions.take(columns[0], axis=0), table_height)
    if present is not None:
        vector &= layout.present_entries(present)
    return vector


def threshold_margins(layout: SemanticLayout, block_positions: np.ndarray, grip_position: np.ndarray,
                      table_height: float, thresholds: Thresholds = THRESHOLDS) -> np.ndarray:
    """(layout.size,) how far (m) each grounded predicate's geometry is from its nearest threshold: a literal
    within a few millimetres of one can flip under that much position error (an estimate's accuracy is
    reported apart for such cases). Absent blocks' entries are meaningless."""
    positions = np.asarray(block_positions, dtype=np.float64)
    t = thresholds
    margins = np.full(layout.size, np.inf)
    for name, (entries, args) in layout.groundings.items():
        a = positions[args[:, 0]]
        if name == "close":
            value = np.abs(np.linalg.norm(a - positions[args[:, 1]], axis=1) - t.close_distance)
        elif name == "above":
            delta = a - positions[args[:, 1]]
            value = np.minimum.reduce([np.abs(np.linalg.norm(delta[:, :2], axis=1) - t.above_xy),
                                       np.abs(delta[:, 2] - t.above_dz_min), np.abs(delta[:, 2] - t.above_dz_max)])
        elif name == "holding":
            rel = a - np.asarray(grip_position)
            value = np.minimum(np.abs(np.linalg.norm(rel[:, :2], axis=1) - t.holding_xy), np.abs(np.abs(rel[:, 2]) - t.holding_z))
        else:  # in_bin
            geometry = layout.scene.bin
            offset = np.abs(a[:, :2] - np.asarray(geometry.center))
            rim = table_height + geometry.floor_thickness + geometry.wall_height
            value = np.minimum(np.abs(offset - np.asarray(geometry.inner_half_size)).min(axis=1), np.abs(a[:, 2] - rim))
        margins[entries] = value
    return margins


def fallen_blocks(names: Sequence[str], block_positions: np.ndarray, table_height: float,
                  thresholds: Thresholds = THRESHOLDS) -> list[str]:
    """The blocks among ``names`` (centres ``block_positions``, (N, 3)) that fell off the table: out of the
    arm's reach for good. Not a predicate (the policy never sees it): the planner fails a step that needs
    such a block with that reason, instead of re-planning for it until the step budget runs out."""
    low = np.asarray(block_positions, dtype=np.float64)[:, 2] < table_height - thresholds.fallen_depth
    return [name for name, fell in zip(names, low, strict=True) if fell]


# Sub-goal types (paper, table of goals): each is a symbolic action with the literals it must make
# true. The planner's PDDL operators carry the same names; Plan2Goals and training both read them here.
SUBGOAL_ARITY: dict[str, tuple[int, int]] = {
    "pick": (1, 1), "put_near": (2, 3), "put_away": (2, 3), "put_on": (2, 2), "put_on_table": (1, 1),
    "put_in_bin": (1, 1),
}
"""(min, max) arguments of each sub-goal type. put_near / put_away take one or two reference blocks:
``put_near(blue,red,green)`` means near red and near green (MC-3's last move needs both)."""

@dataclass(frozen=True)
class SubGoal:
    """A sub-goal: a typed symbolic action such as put_near(red,green).

    ``apart`` (put_near only): blocks the moved block must end up not close to, as the planned step
    promises: ``put_near(red,green,not blue)`` is close(red,green) & not close(red,blue). The actor is sent
    a step's whole effect, so that a put near one block does not land near another the plan counts on
    staying away.
    """

    kind: str
    args: tuple[str, ...]
    apart: tuple[str, ...] = ()

    def __str__(self) -> str:
        return f"{self.kind}({','.join([*self.args, *(f'not {a}' for a in self.apart)])})"

    @property
    def block(self) -> str:
        """The block the action moves."""
        return self.args[0]

    @property
    def references(self) -> tuple[str, ...]:
        return self.args[1:]

    def literals(self) -> list[Literal]:
        """The literals this sub-goal must make true, e.g. put_near(red,green): close, not holding."""
        x, refs = self.block, self.references
        released = Literal("holding", (x,), False)
        if self.kind == "pick":
            return [Literal("holding", (x,))]
        if self.kind == "put_near":
            return [*(Literal("close", (x, y)) for y in refs), *(Literal("close", (x, a), False) for a in self.apart),
                    released]
        if self.kind == "put_away":
            return [*(Literal("close", (x, y), False) for y in refs), released]
        if self.kind == "put_on":
            return [Literal("above", (x, refs[0])), released]
        if self.kind == "put_on_table":
            return [Literal("in_bin", (x,), False), released]
        return [Literal("in_bin", (x,)), released]  # put_in_bin


def _unordered(literals: Iterable[Literal]) -> set[tuple]:
    """Literals with the arguments of symmetric predicates in no order."""
    return {(lit.name, frozenset(lit.args) if lit.name in SYMMETRIC_PREDICATES else lit.args, lit.value)
            for lit in literals}


def subgoal_of(literals: Iterable[Literal]) -> SubGoal:
    """The sub-goal whose :meth:`SubGoal.literals` these are (in any order): the one ``holding`` literal names the
    block it moves, the rest its type and references. VocabularyError for literals no sub-goal asks for together."""
    literals = list(literals)
    holding = [lit for lit in literals if lit.name == "holding"]
    if len(holding) != 1:
        raise VocabularyError(f"{' & '.join(map(str, literals)) or 'no literals'}: a sub-goal names the block it moves "
                              f"in one holding literal")
    x = holding[0].args[0]
    rest = [lit for lit in literals if lit.name != "holding"]
    other = lambda lit: lit.args[1] if lit.args[0] == x else lit.args[0]  # noqa: E731
    if holding[0].value and not rest:
        candidate = SubGoal("pick", (x,))
    elif any(lit.name == "above" for lit in rest):
        candidate = SubGoal("put_on", (x, rest[0].args[1]))
    elif any(lit.name == "in_bin" for lit in rest):
        candidate = SubGoal("put_in_bin" if rest[0].value else "put_on_table", (x,))
    elif any(lit.name == "close" and lit.value for lit in rest):
        candidate = SubGoal("put_near", (x, *(other(lit) for lit in rest if lit.value)),
                            tuple(other(lit) for lit in rest if not lit.value))
    else:
        candidate = SubGoal("put_away", (x, *(other(lit) for lit in rest)))
    if _unordered(candidate.literals()) != _unordered(literals):
        raise VocabularyError(f"{' & '.join(map(str, literals))}: no sub-goal asks for exactly these literals")
    return candidate


def parse_subgoal(text: str, scene: Scene | None = None) -> SubGoal:
    """Read ``put_near(red,green)`` or ``put_near(red,green,not blue)``; check the type, the arity and (given a
    scene) type and objects."""
    match = _LITERAL.match(text)
    if not match or match["neg"]:
        raise VocabularyError(f"cannot read action {text!r}: expected e.g. 'pick(red)' or 'put_near(red,green)'")
    kind = match["name"].lower()
    words = [" ".join(arg.lower().split()) for arg in match["args"].split(",")] if match["args"].strip() else []
    apart = tuple(word[4:] for word in words if word.startswith("not "))
    args = tuple(word for word in words if not word.startswith("not "))
    if kind not in SUBGOAL_ARITY:
        raise VocabularyError(f"unknown action {kind!r}: known are {', '.join(SUBGOAL_ARITY)}")
    if apart and (kind != "put_near" or words[len(args):] != [f"not {a}" for a in apart]):
        raise VocabularyError(f"{text.strip()}: only put_near takes blocks to keep apart from, after its references "
                              f"(e.g. 'put_near(red,green,not blue)')")
    low, high = SUBGOAL_ARITY[kind]
    if not low <= len(args) <= high:
        expected = str(low) if low == high else f"{low} to {high}"
        raise VocabularyError(f"{text.strip()}: {kind} takes {expected} argument(s), got {len(args)}")
    if len(set(args + apart)) != len(args) + len(apart):
        raise VocabularyError(f"{text.strip()}: a block appears twice")
    if scene is not None:
        if kind not in scene.subgoal_types:
            raise VocabularyError(f"action {kind!r} is not available in scene {scene.name!r} "
                                  f"(it has {', '.join(scene.subgoal_types)})")
        for arg in args + apart:
            if arg not in scene.objects:
                raise VocabularyError(f"unknown object {arg!r} in {text.strip()}: objects are {', '.join(scene.objects)}")
    return SubGoal(kind, args, apart)
