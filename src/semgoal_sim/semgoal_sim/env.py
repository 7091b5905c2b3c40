"""A goal-conditioned gymnasium environment over any scene, for training the low-level policy.

Each episode draws a start state and a sub-goal of the scene's types (paper, table of goals), e.g.
``put_near(red,green)``; the reward is 1 when the sub-goal's literals hold with the world at rest (sparse,
semantic; :mod:`semgoal_core.settling`): a block in free fall earns nothing. ``info["motion"]`` carries what
HER needs to judge rest for a relabelled goal, ``info["is_success"]`` the reward as a flag. Episodes
start where the previous step of a plan leaves the arm: a put starts once a pick of its block has been
confirmed (the scripted expert picks it, with a little noise); a pick starts at the home pose, with the arm
moved somewhere over the table, or right where the expert's put of another block was confirmed: open
fingers just above that block, the desk as that put left it (in a bin, next to another block, ...).
Training may also start a put near where a put that let go just out of reach left the block
(``missed_put_share``), so that the actor learns to try again. Episodes never start with the sub-goal already
achieved. ``reset(options=...)`` takes
``{"subgoal": "pick(red)"}`` or ``{"kind": "pick"}`` (a sub-goal type: the training curriculum picks types).
"""

from __future__ import annotations

import itertools
from typing import Any

import gymnasium as gym
import numpy as np

from semgoal_core import features, layout, tasks
from semgoal_core.expert import DROP_CLEARANCE, HOVER, RELEASE, clear_of, destination, expert_action, move_to
from semgoal_core.settling import MotionReward, at_rest, info_motion, moving_blocks
from semgoal_core.vocabulary import (
    BLOCK_HALF_SIZE,
    SCENES,
    TAKE_OUT,
    THRESHOLDS,
    BinGeometry,
    Literal,
    SubGoal,
    parse_subgoal,
    rests_on,
)
from semgoal_sim.render import RgbArrayRendering
from semgoal_sim.rollout import held_blocks, run_subgoal, satisfied
from semgoal_sim.world import FetchWorld, Snapshot

EPISODE_STEPS = 50
"""Control steps per sub-goal episode (2 s of sim time; the expert needs about 15 to 25)."""
HANDOVER_NOISE = 0.1
"""Gaussian noise on the expert's actions while it picks the block a put starts with: varied grasps."""
PLACED_START_SHARE = 0.2
"""Share of put episodes that start with the block set straight into the closed gripper at the home pose
instead (the grasp a person hands over; cheaper, and it keeps that start in the data)."""
ARM_START_LOW = np.array([tasks.SPAWN_LOW[0] - 0.05, tasks.SPAWN_LOW[1] - 0.05, tasks.TABLE_TOP + 0.09])
ARM_START_HIGH = np.array([tasks.SPAWN_HIGH[0] + 0.05, tasks.SPAWN_HIGH[1] + 0.05, tasks.TABLE_TOP + 0.22])
"""Where a pick episode's grip site starts when it does not start at home: above block height (m)."""
STACKED_START_SHARE = {"two_blocks": 0.4, "three_blocks": 0.15}
"""Share of starts with one block resting on another. three_blocks: a put_near that lets go over its
reference leaves one (close holds), and the pick and put after it must cope (most MC-3 failures otherwise).
two_blocks: Swap-2 starts stacked, and an arm that swept across at the height it starts from knocked the
top block off the table."""
BIN_SLOT_JITTER = np.array([0.012, 0.008])
"""Largest offset (m, x and y) of a block started in the bin from its slot: slots are 8 cm apart, so binned
blocks stay at least 5.6 cm apart, and a block in an end slot keeps 3 mm from the end wall."""
NEAR_BOTH_SHARE = 0.3
"""With three blocks: the share of put_near sub-goals next to two references (MC-3's last move). Where the two
references are apart, the expert first puts one next to the other, as the plan's earlier put leaves them."""
PARTIAL_PUT_SHARE = 0.2
"""With three blocks: the share of other puts that name one reference and nothing more, as an operator may
type them. The rest promise what the planner's steps promise, where the block ends up with respect to every
other block: ``put_near(x,y,not z)``, ``put_away(x,y,z)``."""
TOWER_START_SHARE = {"tabletop": 0.35}
"""Share of starts with a tower among the blocks, in scenes with towers: puts onto towers and picks off them.
Training may draw more (``tower_share``); evaluation draws these."""
MAX_TOWER_SHARE = 0.8
"""Largest ``tower_share``: starts with the blocks scattered stay a fifth of the draws."""
TALLEST_START_TOWER = 5
"""The highest tower a start has (a sixth block goes on top of it)."""
BINNED_START_SHARE = 0.5
"""With a bin: the share of starts with some blocks already in it."""
FULL_BIN_SHARE = 0.5
"""Share of binned starts with every block but one in the bin, the rest drawing 1 to count-1 binned blocks
alike: DC-4's last put (three blocks binned) was rare otherwise, and actors hovered over the middle instead
of heading for the free end."""
UNTIDY_BIN_SHARE = 0.5
"""Share of binned starts whose blocks lie anywhere on the bin floor, not in slots: actors let go wherever
in_bin holds, so a last put must find the gap that untidy neighbours leave."""
BINNED_TARGET_SHARE = 0.1
"""With a bin: the share of sub-goals whose block is drawn from every block, a binned one included; the
others take a block outside the bin, as desk plans do (they never take a block out again). Drawn alike,
three picks in four lifted a block out of a bin holding three, and DC-4's last pick was rare in training."""
TAKE_OUT_SHARE = 0.5
"""With blocks in the bin: the share of put_on_table sub-goals that take a binned block back out, so
operators' take-outs are in the training distribution (an actor that had rarely lifted a block
out let it go over the bin, where it landed back in)."""
MAX_SPAWN_MARGIN = 0.1
"""Largest ``spawn_margin`` (m): 1.05..1.55 in x, still inside the workspace and within the expert's reach."""
MAX_MISSED_PUT_SHARE = 0.5
"""Largest ``missed_put_share``: most put_near episodes still start with the block held."""
MISSED_PUT_REACH = (THRESHOLDS.close_distance + 0.002, THRESHOLDS.close_distance + 0.025)
"""A missed put_near start: the block rests this far (centre, m) from one reference, just beyond close, as
the actors' misses left it (0.101 to 0.121 m, then the open fingers hovered over it for good)."""
MISSED_PUT_TURN = np.pi / 6
"""Largest angle (rad) between a missed block's bearing from its reference and the expert's spot's bearing."""
MISSED_GRIP_OFFSET = 0.03
"""Largest offset (m, x and y) of the open fingers from straight above a missed block (the misses: up to 5 cm)."""
PICK_START_SHARES = {"home": 0.3, "over_table": 0.3, "after_put": 0.4}
"""Where pick episodes start. ``after_put`` is where a plan hands the next pick over: the open fingers
just above a block that was just put (in the bin, say), which no training pick had started from before."""


class SubgoalEnv(RgbArrayRendering, gym.Env):
    """Dict observation (observation / achieved_goal / desired_goal), 4-D action in [-1, 1]."""

    def __init__(self, scene: str, n_blocks: int | None = None, subgoal_types: tuple[str, ...] | None = None,
                 max_steps: int = EPISODE_STEPS, derived: tuple[str, ...] = (), spawn_margin: float = 0.0,
                 missed_put_share: float = 0.0, tower_share: float | None = None, max_blocks: int | None = None,
                 render_mode: str | None = None, sleep: bool = True, shown_bin: BinGeometry | None = None) -> None:
        """:param derived: features (``semgoal_core.features``) appended to the observation.
        :param shown_bin: the bin ``bin_target`` reads where the scene has none (``semgoal_core.features.shown_bin``:
            an actor trained with a bin judged as the policy node runs it).
        :param spawn_margin: how far (m, along x) blocks may start beyond the tasks' spawn area, near and far
            edge alike, so that the area's edge is not the edge of the training data (actors stalled over
            blocks at its far edge). y stays: the bin lies beyond it. Evaluation sets it to 0.
        :param missed_put_share: share of put_near episodes that start where a put that let go just out of
            reach left the world (:meth:`_miss`), so that actors learn to pick the block again instead of
            hovering over it. Evaluation sets it to 0.
        :param tower_share: share of starts with a tower among the blocks (None: the scene's
            :data:`TOWER_START_SHARE`), so that training meets tall towers more often than the sub-goal types alone
            bring them. Scenes with towers only; evaluation sets it to None.
        :param max_blocks: the most blocks an episode has (None: every count the scene allows), so that tasks with
            more (the tabletop's Tower-7 and Clean-8) test an actor on counts it never met.
        :param sleep: blocks at rest sleep (:func:`semgoal_sim.scene.build_model`); False: awake, as the actors were trained.
        """
        if not 0.0 <= spawn_margin <= MAX_SPAWN_MARGIN:
            raise ValueError(f"spawn_margin {spawn_margin} is outside [0, {MAX_SPAWN_MARGIN}] m")
        if not 0.0 <= missed_put_share <= MAX_MISSED_PUT_SHARE:
            raise ValueError(f"missed_put_share {missed_put_share} is outside [0, {MAX_MISSED_PUT_SHARE}]")
        self._set_render_mode(render_mode)
        self.spawn_margin = spawn_margin
        self.missed_put_share = missed_put_share
        self.scene = SCENES[scene]
        self.tower_share = tower_share
        self.derived = features.check(derived)
        self.shown_bin = shown_bin
        counts = (n_blocks,) if n_blocks else self.scene.block_counts or (self.scene.max_blocks,)
        self.block_counts = tuple(count for count in counts if max_blocks is None or count <= max_blocks)
        if not self.block_counts:
            raise ValueError(f"max_blocks {max_blocks} leaves no episode: scene {scene!r} has {', '.join(map(str, counts))}")
        self.worlds = {count: FetchWorld(scene, count, sleep=sleep) for count in self.block_counts}
        self.world = self.worlds[self.block_counts[-1]]
        self.layout = self.world.layout
        self.motion_reward = MotionReward(self.layout)
        self.subgoal_types = subgoal_types or self.scene.subgoal_types
        self.max_steps = max_steps
        obs_size = layout.observation_size(scene) + features.width(self.derived)
        goal_size = layout.goal_size(scene)
        self.observation_space = gym.spaces.Dict({
            "observation": gym.spaces.Box(-np.inf, np.inf, (obs_size,), np.float32),
            "achieved_goal": gym.spaces.Box(0.0, 1.0, (goal_size,), np.float32),
            "desired_goal": gym.spaces.Box(0.0, 1.0, (goal_size,), np.float32),
        })
        self.action_space = gym.spaces.Box(-1.0, 1.0, (4,), np.float32)
        self.subgoal: SubGoal | None = None
        self._subgoal_text = "None"
        """``str(self.subgoal)``, as each step's info carries it."""
        self._encode_goal(np.zeros(self.layout.size, dtype=np.float32), np.zeros(self.layout.size, dtype=np.float32))
        self._steps = 0
        self._achieved = False
        """Whether the sub-goal's literals held after the latest reset or step, at rest or not (the expert's
        label reads it: once they hold, it backs away instead of picking a falling block up again)."""

    # -- gymnasium API -------------------------------------------------------------------------------
    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None):
        super().reset(seed=seed)
        options = options or {}
        take_out = options.get("kind") == TAKE_OUT
        if take_out and self.scene.bin is None:
            raise ValueError(f"{TAKE_OUT} needs a bin; scene {self.scene.name!r} has none")
        for _ in range(100):
            self.world = self.worlds[int(self.np_random.choice(self.block_counts))]
            self.world.reset(self._sample_positions(binned=take_out))
            subgoal = (parse_subgoal(options["subgoal"], self.scene) if "subgoal" in options
                       else self._sample_subgoal("put_on_table", take_out=True) if take_out
                       else self._sample_subgoal(options.get("kind")))
            if subgoal is None or not self._start_for(subgoal):
                continue
            self._set_subgoal(subgoal)
            if not self._success() or "subgoal" in options:
                break
        self._steps = 0
        obs, _, info = self._read()
        return obs, info

    @property
    def tower_share(self) -> float | None:
        return self._tower_share

    @tower_share.setter
    def tower_share(self, share: float | None) -> None:
        """A share is for scenes with towers, at most :data:`MAX_TOWER_SHARE` (a training phase sets it too)."""
        if share is not None and (self.scene.name not in TOWER_START_SHARE or not 0.0 <= share <= MAX_TOWER_SHARE):
            raise ValueError(f"tower_share {share} needs a scene with towers ({', '.join(TOWER_START_SHARE)}) and a value "
                             f"in [0, {MAX_TOWER_SHARE}]")
        self._tower_share = share

    def step(self, action: np.ndarray):
        self.world.step(action)
        self._steps += 1
        obs, reward, info = self._read()
        return obs, reward, False, self._steps >= self.max_steps, info

    def _read(self) -> tuple[dict[str, np.ndarray], float, dict[str, Any]]:
        """The observation, reward and info of the world now, from one read of it (a snapshot and its vector)."""
        snapshot = self.world.snapshot()
        vector = self.world.semantic_vector(snapshot)
        return self._obs(snapshot, vector), *self._reward(snapshot, vector)

    def _reward(self, snapshot: Snapshot, vector: np.ndarray) -> tuple[float, dict[str, Any]]:
        motion = self.world.motion(snapshot, vector)
        self._achieved = self._holds(vector)
        reward = float(self._achieved and self.motion_reward.at_rest(self._asked, motion))  # compute_reward's
        return reward, {"subgoal": self._subgoal_text, "subgoal_type": self.kind, "is_success": reward > 0,
                        "motion": motion}

    def compute_reward(self, achieved_goal: np.ndarray, desired_goal: np.ndarray, info: Any) -> np.ndarray:
        """Vectorised sparse semantic reward at rest, for HER relabelling: ``info`` is a step's info dict,
        or a sequence of them, one per row (as Stable-Baselines3's HER passes them)."""
        return self.motion_reward(achieved_goal, desired_goal, info_motion(info))

    # -- sampling ------------------------------------------------------------------------------------
    def _sample_positions(self, binned: bool = False) -> np.ndarray:
        """Scattered, clustered or (with a bin) partly binned starts, so every sub-goal meets variety;
        ``binned``: always some blocks in the bin."""
        rng, count = self.np_random, len(self.world.blocks)
        area = self.spawn_area()
        if binned:
            positions = tasks.scatter(rng, count, **area)
            self._bin_some(positions)
            return positions
        kind = rng.uniform()
        default = TOWER_START_SHARE.get(self.scene.name, 0.0)
        towers = default if self.tower_share is None else self.tower_share
        if kind > 1.0 - towers:
            return self._tower_among(count)
        # the other starts keep the shares they have beside the default towers: a larger tower share takes from each
        # alike (drawn over the binned starts' range, it had left none)
        kind *= (1.0 - default) / (1.0 - towers)
        if kind < 0.3 and count >= 2:
            positions = tasks.scatter(rng, count, **area)
            positions[:2] = tasks.cluster(rng, 2, **area)
            if count > 2 and min(np.linalg.norm(positions[i, :2] - positions[j, :2])
                                 for i, j in itertools.combinations(range(count), 2)) < tasks.MIN_SEPARATION:
                positions = tasks.scatter(rng, count, **area)
            return positions[rng.permutation(count)] if kind < 0.15 else positions
        if kind > 1.0 - STACKED_START_SHARE.get(self.scene.name, 0.0):
            return tasks.stack_among(rng, count, **area)
        positions = tasks.scatter(rng, count, **area)
        if self.scene.bin is not None and kind > 1.0 - BINNED_START_SHARE:
            self._bin_some(positions)
        return positions

    def spawn_area(self) -> dict[str, np.ndarray]:
        """``low`` and ``high`` (x, y) corners of the area blocks start in: the tasks' widened by the margin."""
        widen = np.array([self.spawn_margin, 0.0])
        low, high = ((tasks.TABLETOP_SPAWN_LOW, tasks.TABLETOP_SPAWN_HIGH) if self.scene.name in TOWER_START_SHARE
                     else (tasks.SPAWN_LOW, tasks.SPAWN_HIGH))
        return {"low": low - widen, "high": high + widen}

    def _tower_among(self, count: int) -> np.ndarray:
        """A tower of 2 to :data:`TALLEST_START_TOWER` random blocks, the others spread around it, in random order."""
        rng = self.np_random
        height = int(rng.integers(2, min(count, TALLEST_START_TOWER) + 1))
        positions = tasks.spread(rng, count - height + 1, tasks.MIN_SEPARATION, **self.spawn_area())
        tower = tasks.tower(rng, height, positions[0, :2], positions[0, :2])
        return np.vstack([tower, positions[1:]])[rng.permutation(count)]

    def _bin_some(self, positions: np.ndarray) -> None:
        """Move 1 to count-1 random blocks (see :data:`FULL_BIN_SHARE`) into the bin as a plan's earlier puts leave them:
        in random slots, a little off-centre, as the expert puts them, or (:data:`UNTIDY_BIN_SHARE`) each on
        a random free spot of the floor, as an actor lets go anywhere in_bin holds."""
        rng, count, bin_ = self.np_random, len(positions), self.scene.bin
        size = count - 1 if rng.uniform() < FULL_BIN_SHARE else int(rng.integers(1, count))
        binned = rng.choice(count, size=size, replace=False)
        if rng.uniform() < UNTIDY_BIN_SHARE:
            spots = self._untidy_spots(len(binned))
            binned = binned[:len(spots)]
        else:
            slots = bin_.slots()
            spots = slots[rng.choice(len(slots), size=len(binned), replace=False)]
            spots = spots + rng.uniform(-1, 1, size=(len(binned), 2)) * BIN_SLOT_JITTER
        resting = tasks.TABLE_TOP + bin_.floor_thickness + 0.0251
        positions[binned] = np.column_stack([spots, np.full(len(binned), resting)])

    def _untidy_spots(self, count: int) -> np.ndarray:
        """Up to ``count`` (M, 2) floor spots in the bin, each drawn among those still free, stopping early
        when none is."""
        floor, spots = self.scene.bin.interior(), []
        for _ in range(count):
            free = floor[clear_of(floor, spots)]
            if not len(free):
                break
            spots.append(free[self.np_random.integers(len(free))])
        return np.array(spots).reshape(-1, 2)

    def _start_for(self, subgoal: SubGoal) -> bool:
        """Bring the arm to where a plan would hand ``subgoal`` over; False when that failed (resample)."""
        rng = self.np_random
        if subgoal.kind == "pick":
            start = rng.choice(list(PICK_START_SHARES), p=list(PICK_START_SHARES.values()))
            if start == "over_table":
                self._move_grip(rng.uniform(ARM_START_LOW, ARM_START_HIGH))
            elif start == "after_put":
                return self._put_another(subgoal.block)
            return True
        near_both = subgoal.kind == "put_near" and len(subgoal.args) == 3
        if near_both and (not self._join(subgoal.args[1:], subgoal.block)
                          or destination(subgoal, self.world.view()) is None):
            return False
        # drawn only when on: evaluation's starts must not depend on a training-only setting
        if subgoal.kind == "put_near" and self.missed_put_share and rng.uniform() < self.missed_put_share:
            return self._miss(subgoal)
        if rng.uniform() < PLACED_START_SHARE:
            self.world.place_in_gripper(subgoal.block)
            return True
        return self._pick_up(subgoal.block)

    def _join(self, refs: tuple[str, ...], block: str) -> bool:
        """Near both fits only where its references are close to each other (MC-3's last move): where they
        are apart, the expert puts the first next to the second, as the plan's earlier put leaves them."""
        if self._close(self.world.semantic_vector(), refs):
            return True
        return self._expert_put(SubGoal("put_near", refs), block)

    def _miss(self, subgoal: SubGoal) -> bool:
        """The world a put_near leaves that let go just out of reach: the block at rest on the table a little
        beyond close of one reference, roughly where the expert would put it, the open fingers above it."""
        rng, view = self.np_random, self.world.view()
        spot = destination(subgoal, view)
        if spot is None:
            return False
        reference = view.positions[str(rng.choice(subgoal.references))][:2]
        bearing = np.arctan2(*(spot[:2] - reference)[::-1]) + rng.uniform(-MISSED_PUT_TURN, MISSED_PUT_TURN)
        miss = reference + rng.uniform(*MISSED_PUT_REACH) * np.array([np.cos(bearing), np.sin(bearing)])
        others = list(view.others(subgoal.block).values())
        low, high = ARM_START_LOW[:2], ARM_START_HIGH[:2]
        if not (np.all((low <= miss) & (miss <= high)) and clear_of(miss[None], others, DROP_CLEARANCE)[0]):
            return False
        rest = np.array([*miss, tasks.TABLE_TOP + BLOCK_HALF_SIZE])
        self._move_grip(rest + np.array([0.0, 0.0, HOVER + 2 * BLOCK_HALF_SIZE]), steps=25)  # over the blocks
        self.world.set_block_pose(subgoal.block, rest)
        offset = rng.uniform(-MISSED_GRIP_OFFSET, MISSED_GRIP_OFFSET, 2)
        self._move_grip(rest + np.array([*offset, HOVER]), steps=8)
        return not self._under_another(subgoal.block)

    def _put_another(self, block: str) -> bool:
        """The expert puts some other block (a sampled put sub-goal), as the step before a pick of ``block``
        leaves the world."""
        kinds = [kind for kind in self.subgoal_types if kind != "pick"]
        other = self._sample_subgoal(str(self.np_random.choice(kinds)), exclude=block)
        return other is not None and self._expert_put(other, block)

    def _expert_put(self, put: SubGoal, block: str) -> bool:
        """The expert picks and puts as a plan's earlier step would, until the put is confirmed; False where
        that failed or left ``block`` under another."""
        if not self._pick_up(put.block) or not run_subgoal(self.world, put, self._noisy_expert, EPISODE_STEPS)[0]:
            return False
        return not self._under_another(block)

    def _move_grip(self, target: np.ndarray, steps: int = 12) -> None:
        """Move the grip site toward ``target``, fingers opening."""
        for _ in range(steps):
            self.world.step(move_to(self.world.view().grip, target, RELEASE))

    def _pick_up(self, block: str) -> bool:
        """The expert picks ``block`` (with a little noise) until holding it is confirmed, as the planner
        confirms a pick."""
        pick = SubGoal("pick", (block,))
        return run_subgoal(self.world, pick, self._noisy_expert, EPISODE_STEPS)[0]

    def _noisy_expert(self, subgoal: SubGoal, world: FetchWorld) -> np.ndarray:
        """The expert as the trained actor behaves: once a put holds it backs away (over the steps that
        confirm it), it does not pick the block again. Picks ignore ``achieved``: no semantic vector for them."""
        achieved = subgoal.kind != "pick" and satisfied(world.layout, world.semantic_vector(), subgoal.literals())
        noise = HANDOVER_NOISE * self.np_random.standard_normal(4)
        return expert_action(subgoal, world.view(), achieved=achieved) + noise

    def _under_another(self, block: str) -> bool:
        """Whether a block rests on ``block``, from the geometry (three_blocks has no above predicate)."""
        positions = self.world.view().positions
        others = [p for name, p in positions.items() if name != block]
        return bool(rests_on(np.array(others), positions[block]).any())

    def _sample_subgoal(self, kind: str | None = None, exclude: str | None = None, take_out: bool = False
                        ) -> SubGoal | None:
        """A sub-goal of ``kind`` (default: any type) for a random block other than ``exclude``; ``take_out``:
        a binned block (None when none is)."""
        rng = self.np_random
        kind = kind or str(rng.choice(self.subgoal_types))
        vector = self.world.semantic_vector()
        candidates = [b for b in self.world.blocks if b != exclude]
        if self.scene.bin is not None:
            binned = [b for b in candidates if vector[self.layout.index(Literal("in_bin", (b,)))]]
            if take_out or (kind == "put_on_table" and binned and rng.uniform() < TAKE_OUT_SHARE):
                candidates = binned
            elif rng.uniform() >= BINNED_TARGET_SHARE:
                candidates = [b for b in candidates if b not in binned] or candidates
        if not candidates:
            return None
        x = str(rng.choice(candidates))
        others = rng.permutation([b for b in self.world.blocks if b != x]).tolist()
        if self._under_another(x):  # a block under another cannot be picked: the plan would clear it first
            return None
        if kind in ("put_near", "put_away") and len(others) >= 2:
            whole_effect = rng.uniform() >= PARTIAL_PUT_SHARE
            if kind == "put_near" and rng.uniform() < NEAR_BOTH_SHARE:
                subgoal = SubGoal(kind, (x, *others[:2]))
            elif kind == "put_near":
                subgoal = SubGoal(kind, (x, others[0]), tuple(others[1:]) if whole_effect else ())
            else:
                subgoal = SubGoal(kind, (x, *(others if whole_effect else others[:1])))
        else:
            subgoal = SubGoal(kind, (x, others[0]) if kind in ("put_near", "put_away", "put_on") else (x,))
        return subgoal if self._plannable(subgoal) else None

    def _plannable(self, subgoal: SubGoal) -> bool:
        """Whether a plan could hand ``subgoal`` over in this world, so that it is worth drawing. Where blocks stack
        and go in a bin (the tabletop), its domain's preconditions: a block is put on or near only one outside the
        bin with nothing on it (the moved block aside), and near only one that stands on the table. And a put near
        or away needs a spot that fits (:func:`destination`; a put near both references is looked at once they are
        joined, :meth:`_start_for`). Drawn otherwise, the expert held the block to the end (10 % of the tabletop's
        put nears, 7 % of its put aways), and the actor learned to do the same."""
        x, references = subgoal.block, subgoal.references
        if subgoal.kind in ("put_near", "put_on") and self.scene.bin is not None and "above" in self.scene.predicates:
            preconditions = [Literal("in_bin", (ref,), False) for ref in references]
            preconditions += [Literal("above", (b, ref), False) for ref in references for b in self.world.blocks
                              if b not in (x, ref)]
            if subgoal.kind == "put_near":  # standing on the table
                preconditions += [Literal("above", (ref, b), False) for ref in references for b in self.world.blocks
                                  if b != ref]
            if not satisfied(self.layout, self.world.semantic_vector(), preconditions):
                return False
        near_both = subgoal.kind == "put_near" and len(references) == 2
        if subgoal.kind in ("put_near", "put_away") and not near_both:
            return destination(subgoal, self.world.view()) is not None
        return True

    def _close(self, vector: np.ndarray, pair: tuple[str, str]) -> bool:
        return bool(vector[self.layout.index(Literal("close", pair))])

    def _set_subgoal(self, subgoal: SubGoal) -> None:
        self.subgoal, self._subgoal_text = subgoal, str(subgoal)
        self._encode_goal(*self.layout.encode(subgoal.literals()))

    def _encode_goal(self, target: np.ndarray, mask: np.ndarray) -> None:
        """The sub-goal's (target, mask) and what each step reads of them, worked out once per sub-goal."""
        self._target, self._mask = target, mask
        self._goal = np.concatenate([target, mask])
        self._asked = self.motion_reward.asked(self._goal)
        self._constrained = np.flatnonzero(mask > 0.5)
        self._wanted = target[self._constrained] > 0.5

    def _holds(self, vector: np.ndarray) -> bool:
        """The sub-goal's literals hold in the semantic ``vector`` (:func:`layout.goal_reward` of it, at rest or not)."""
        return bool((vector[self._constrained] == self._wanted).all())

    @property
    def kind(self) -> str:
        """The current sub-goal's type: what the training curriculum and evaluation group by."""
        return self.subgoal.kind if self.subgoal else ""

    def expert_action(self) -> np.ndarray:
        """The scripted expert's action for the current sub-goal: the label for behaviour cloning."""
        return expert_action(self.subgoal, self.world.view(), achieved=self._achieved)

    # -- read-out ------------------------------------------------------------------------------------
    def _success(self) -> bool:
        """The sub-goal's literals hold (at rest or not): a start that already meets them is drawn again."""
        return self._holds(self.world.semantic_vector())

    def shortfall(self) -> list[str]:
        """Why the sub-goal is not achieved at rest now, in words (``eval-subgoals --misses``): each of its
        literals that does not hold, a close one with the centre distance it was judged on, and what keeps
        the world from rest. Empty when it is achieved at rest."""
        snapshot = self.world.snapshot()
        vector, positions = self.world.semantic_vector(snapshot), self.world.view().positions
        literals, reasons = self.subgoal.literals(), []
        for literal in literals:
            if bool(vector[self.layout.index(literal)]) != literal.value:
                distance = (f" ({np.linalg.norm(positions[literal.args[0]] - positions[literal.args[1]]):.3f} m)"
                            if literal.name == "close" else "")
                reasons.append(f"{literal} is false{distance}")
        moving = moving_blocks(self.world.blocks, snapshot.block_velocities)
        held = held_blocks(self.world, vector)
        if not at_rest(literals, moving, held):
            reasons.append(f"not at rest (moving: {', '.join(moving) or 'none'}; held: {', '.join(held) or 'none'})")
        return reasons

    def _obs(self, snapshot: Snapshot, vector: np.ndarray) -> dict[str, np.ndarray]:
        goal = self._goal.copy()
        return {
            "observation": features.augment(self.scene.name, self.world.observation(snapshot), self.derived, goal,
                                            self.shown_bin),
            "achieved_goal": layout.achieved_goal(vector, self._mask),
            "desired_goal": goal,
        }
