"""The simulated Fetch block world: reset, one control step, state read-out. No rclpy.

Control as in the Fetch benchmark (gymnasium-robotics ``MujocoFetchEnv``): a 4-D action in [-1, 1];
the first three move the end effector by up to 0.05 m per step through the mocap body welded to the
gripper, the fourth drives both fingers' position targets (relative to their current opening); each
control step runs 20 physics substeps of 0.002 s (25 Hz).
"""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np

from semgoal_core.arms import ArmFrame, arm_observation, holder_of, robot_name, takers
from semgoal_core.expert import WorldView
from semgoal_core.geometry import GRASP_OPENING, TABLE_CENTER, TABLE_HALF_SIZE, TABLE_TOP, grip_ceiling
from semgoal_core.layout import CONTROL_DT, MAX_DISPLACEMENT
from semgoal_core.settling import motion_bits
from semgoal_core.vocabulary import BLOCK_HALF_SIZE, LAYOUTS, SCENES, evaluate, fallen_blocks, held_alone
from semgoal_sim.arm_guard import ArmGuard
from semgoal_sim.scene import REACHING_LINKS, arm_prefix, block_body_name, build_model

N_SUBSTEPS = 20
GRIPPER_HOME_OFFSET = np.array([-0.498, 0.005, -0.431 + 0.2])
"""Fetch benchmark: grip site moved by this from the initial joint pose (gripper_extra_height 0.2)."""
GRIPPER_QUAT = np.array([1.0, 0.0, 1.0, 0.0]) / np.sqrt(2.0)
"""Gripper pointing down, fixed orientation (the benchmark's mocap rotation)."""
CLEARANCE_RANGE = 0.3
"""How far (m) the arms' links are looked at for :meth:`FetchWorld.arm_clearance`: beyond, the guard needs no more."""
CARRY_EDGE_MARGIN = 0.045
"""How far inside its own table edge (m) a yielding arm stops drawing back a block in its hand (the policy's
edge margin, ``semgoal_policy.controller.EDGE_MARGIN``)."""
CHAIN_LINKS = ("shoulder_pan_link", "elbow_flex_link", "wrist_flex_link", "gripper_link")
SHARED_HOME_SETBACK = np.array([0.17, 0.0, 0.0])
"""With two arms, each arm's home is this much nearer its own base: the benchmark's home reaches 4 cm past the
table's centre line, where the other arm's home would be."""
GRIP_BELOW_BODY = 0.02
"""The grip site sits about this far (m) below the gripper body, which the workspace box holds."""
INITIAL_QPOS = {"robot0:slide0": 0.405, "robot0:slide1": 0.48, "robot0:slide2": 0.0}
WORKSPACE_LOW = np.array([1.0, 0.35, TABLE_TOP + 0.005])
WORKSPACE_HIGH = np.array([1.6, 1.15, TABLE_TOP])
"""The mocap target is kept in this box so the arm never drives into the table or out of reach; its top is the
scene's ``reach_height`` above this."""


def _pose(position: np.ndarray, rotation: np.ndarray) -> np.ndarray:
    pose = np.eye(4)
    pose[:3, :3], pose[:3, 3] = np.reshape(rotation, (3, 3)), position
    return pose


@dataclass(frozen=True)
class Snapshot:
    """Everything observable after a control step, as plain arrays (world frame, m, m/s)."""

    step: int
    time: float
    block_positions: np.ndarray  # (N, 3) for the blocks built, canonical order
    block_quaternions: np.ndarray  # (N, 4) w, x, y, z
    block_velocities: np.ndarray  # (N, 6) linear, angular
    grip_position: np.ndarray  # (3,)
    grip_velocity: np.ndarray  # (3,)
    finger_positions: np.ndarray  # (2,) right, left joint positions; opening = sum
    finger_velocities: np.ndarray  # (2,)
    other_hands: tuple[tuple[np.ndarray, float], ...] = ()
    """Each other arm's grip position and finger opening (a second arm's hand may hold a block too)."""

    @property
    def finger_opening(self) -> float:
        return float(self.finger_positions.sum())


@dataclass(frozen=True)
class _Arm:
    """Where one arm's parts sit in the model."""

    mocap: int
    grip_site: int
    gripper_body: int
    base_body: int
    finger_qpos: np.ndarray
    finger_qvel: np.ndarray
    finger_actuators: np.ndarray
    geoms: np.ndarray
    """Its geoms' ids: the contacts between two arms' (:attr:`FetchWorld.arm_contacts`)."""
    chain: np.ndarray
    """Its shoulder, elbow, wrist and gripper bodies: with the grip site, the chain the guard keeps apart."""
    hand_geoms: np.ndarray
    """The colliding geoms of its gripper and fingers: what a block set down must keep clear of
    (:meth:`FetchWorld.hand_boxes`)."""
    quaternion: np.ndarray
    """The gripper's fixed orientation: pointing down, turned as the arm's base is."""


class FetchWorld:
    """One scene's physics: seeded placement of blocks, Fetch-style control, state and predicates.

    With ``arms=2`` a second Fetch stands across the table (``semgoal_core.arms``): :meth:`step` takes one command per
    arm, :meth:`snapshot` and :meth:`observation` read any arm's hand, ``holding`` is in either hand, and contacts
    between the two arms are counted (:attr:`arm_contacts`)."""

    def __init__(self, scene: str, n_blocks: int | None = None, arms: int = 1, sleep: bool = True) -> None:
        """``sleep``: blocks at rest sleep (:func:`semgoal_sim.scene.build_model`); False: every body awake."""
        self.scene = SCENES[scene]
        self._workspace_high = WORKSPACE_HIGH + np.array([0.0, 0.0, self.scene.reach_height])
        self.layout = LAYOUTS[scene]
        self.model = build_model(scene, n_blocks, arms, sleep)
        self.data = mujoco.MjData(self.model)
        self.blocks = self.scene.objects[: n_blocks or self.scene.max_blocks]
        self.present = np.array([obj in self.blocks for obj in self.scene.objects])
        self._partial = None if self.present.all() else self.present
        """:attr:`present` where a slot is empty, else None: a full scene's vector needs no masking, nor padding."""
        m = self.model
        self._block_qpos = [m.joint(f"{block_body_name(b)}:joint").qposadr[0] for b in self.blocks]
        self._block_qvel = [m.joint(f"{block_body_name(b)}:joint").dofadr[0] for b in self.blocks]
        self._block_velocity_index = (np.asarray(self._block_qvel, dtype=int)[:, None] + np.arange(6)).reshape(-1)
        """Every block's six velocity entries in ``qvel``, in block order: one gather per snapshot."""
        self._block_body = np.array([m.body(block_body_name(b)).id for b in self.blocks])
        self.arms = [self._arm(arm) for arm in range(arms)]
        prefixes = tuple(f"{arm_prefix(arm)}robot0:" for arm in range(arms))
        robot = [i for i in range(m.njnt) if m.joint(i).name.startswith(prefixes)]
        self.robot_joint_names = [m.joint(i).name for i in robot]
        """Every arm's joints, in model order (what /joint_states names): the second arm's under ``robot2/``."""
        self._robot_qpos, self._robot_qvel = m.jnt_qposadr[robot], m.jnt_dofadr[robot]
        entries, args = self.layout.groundings["holding"]
        self._holding_entries = entries[np.argsort(args[:, 0])][: len(self.blocks)]
        """The semantic vector's ``holding(block)`` entry of each block built, in block order."""
        self.step_count = 0
        self.arm_contacts = 0
        """Physics substeps since the last reset with two arms touching."""
        self._arm_of_geom = np.full(m.ngeom, -1)
        for index, arm in enumerate(self.arms):
            self._arm_of_geom[arm.geoms] = index
        self._home_state = self._settle_home()
        edge = TABLE_CENTER[0] - TABLE_HALF_SIZE[0] + CARRY_EDGE_MARGIN  # the first arm's; the second's reflected
        edges = np.array([ArmFrame(scene, arm).positions(np.array([edge, 0.0, 0.0]))[0] for arm in range(arms)])
        self.guard = ArmGuard(MAX_DISPLACEMENT, edges) if arms == 2 else None
        """Keeps two arms apart (:mod:`semgoal_sim.arm_guard`)."""
        self._reaching = [[m.geom(f"{arm_prefix(arm)}robot0:{link}").id for link in REACHING_LINKS] for arm in range(arms)]
        """Each arm's links that reach over the table: :meth:`arm_clearance` measures between them."""

    def _arm(self, arm: int) -> _Arm:
        m, prefix = self.model, arm_prefix(arm)
        fingers = [f"{prefix}robot0:{side}_gripper_finger_joint" for side in ("r", "l")]
        base = m.body(f"{prefix}robot0:base_link").id
        quaternion = GRIPPER_QUAT.copy()
        if arm:  # turned half a turn about the vertical, as its base
            mujoco.mju_mulQuat(quaternion, np.array([0.0, 0.0, 0.0, 1.0]), GRIPPER_QUAT)
        return _Arm(
            mocap=int(m.body(f"{prefix}robot0:mocap").mocapid[0]),
            grip_site=m.site(f"{prefix}robot0:grip").id,
            gripper_body=m.body(f"{prefix}robot0:gripper_link").id,
            base_body=base,
            finger_qpos=np.array([m.joint(f).qposadr[0] for f in fingers]),
            finger_qvel=np.array([m.joint(f).dofadr[0] for f in fingers]),
            finger_actuators=np.array([m.actuator(f).id for f in fingers]),
            geoms=np.flatnonzero(m.body_rootid[m.geom_bodyid] == m.body_rootid[base]),
            chain=np.array([m.body(f"{prefix}robot0:{link}").id for link in CHAIN_LINKS]),
            quaternion=quaternion,
            hand_geoms=np.flatnonzero(np.isin(m.geom_bodyid, self._subtree(m.body(f"{prefix}robot0:gripper_link").id))
                                      & (m.geom_contype > 0)),
        )

    def _subtree(self, body: int) -> list[int]:
        """``body`` and every body below it."""
        below = [body]
        for child in range(body + 1, self.model.nbody):  # MuJoCo numbers a body's children after it
            if self.model.body_parentid[child] in below:
                below.append(child)
        return below

    # -- reset ---------------------------------------------------------------------------------------
    def _shared_home(self) -> tuple[dict[str, float], np.ndarray]:
        """One arm's joint positions and mocap target at its home set back by :data:`SHARED_HOME_SETBACK`: where two
        arms start, bent and clear of each other, not stretched out across the table into each other."""
        alone = FetchWorld(self.scene.name, len(self.blocks))
        alone.data.mocap_pos[0] -= SHARED_HOME_SETBACK
        for _ in range(10):
            mujoco.mj_step(alone.model, alone.data, nstep=N_SUBSTEPS)
        return (dict(zip(alone.robot_joint_names, alone.robot_joint_state()[0], strict=True)),
                alone.data.mocap_pos[0].copy())

    def _settle_home(self) -> np.ndarray:
        """Put the arms in the benchmark's home pose once (a second arm in the first's reflection across the table);
        later resets restore this state."""
        m, d = self.model, self.data
        mujoco.mj_resetData(m, d)
        weld = m.eq_type == mujoco.mjtEq.mjEQ_WELD  # the mocap welds: no offset between mocap and gripper
        m.eq_data[weld, :7] = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0]
        joints, home = self._shared_home() if len(self.arms) > 1 else (INITIAL_QPOS, None)
        for index in range(len(self.arms)):
            for name, value in joints.items():
                d.qpos[m.joint(f"{arm_prefix(index)}{name}").qposadr[0]] = value
        for i, addr in enumerate(self._block_qpos):  # park blocks apart, off the arm's way, during settling
            d.qpos[addr: addr + 7] = [1.1 + 0.1 * i, 0.45, TABLE_TOP + BLOCK_HALF_SIZE, 1, 0, 0, 0]
        mujoco.mj_forward(m, d)
        if home is None:
            home = d.site_xpos[self.arms[0].grip_site] + GRIPPER_HOME_OFFSET
        for index, arm in enumerate(self.arms):
            d.mocap_pos[arm.mocap] = ArmFrame(self.scene.name, index).positions(home)
            d.mocap_quat[arm.mocap] = arm.quaternion
        for _ in range(10):
            mujoco.mj_step(m, d, nstep=N_SUBSTEPS)
        self.home_grip_position = d.site_xpos[self.arms[0].grip_site].copy()
        state = np.empty(mujoco.mj_stateSize(m, mujoco.mjtState.mjSTATE_INTEGRATION))
        mujoco.mj_getState(m, d, state, mujoco.mjtState.mjSTATE_INTEGRATION)
        return state

    def reset(self, block_positions: np.ndarray, settle_steps: int = 10) -> Snapshot:
        """Arm at home, blocks at ``block_positions`` (N, 3) upright and at rest, then let them settle.

        Settling (arm held still) lets stacked starts come to rest before the first observation.
        """
        m, d = self.model, self.data
        mujoco.mj_resetData(m, d)  # every body awake: sleeping is no part of the state set below
        mujoco.mj_setState(m, d, self._home_state, mujoco.mjtState.mjSTATE_INTEGRATION)
        for addr, dof, pos in zip(self._block_qpos, self._block_qvel, np.asarray(block_positions), strict=True):
            d.qpos[addr: addr + 7] = [*pos, 1.0, 0.0, 0.0, 0.0]
            d.qvel[dof: dof + 6] = 0.0
        mujoco.mj_forward(m, d)
        self.step_count = self.arm_contacts = 0
        if self.guard is not None:
            self.guard.reset()
        for _ in range(settle_steps):
            self.step(np.zeros(4), count=False)
        return self.snapshot()

    def set_block_pose(self, block: str, position: np.ndarray, quaternion=(1.0, 0.0, 0.0, 0.0)) -> None:
        """Teleport a block (upright unless told, at rest): operator intervention, perturbation tests, replay."""
        i = self.blocks.index(block)
        addr, dof = self._block_qpos[i], self._block_qvel[i]
        self.data.qpos[addr: addr + 7] = [*position, *quaternion]
        self.data.qvel[dof: dof + 6] = 0.0
        mujoco.mj_forward(self.model, self.data)

    def open_fingers(self, opening: float = GRASP_OPENING, arm: int = 0) -> None:
        """Open an arm's fingers to ``opening`` (m, both together) at once and keep them there: a hand let go of."""
        arm = self.arms[arm]
        self.data.qpos[arm.finger_qpos] = opening / 2
        self.data.qvel[arm.finger_qvel] = 0.0
        self.data.ctrl[arm.finger_actuators] = opening / 2
        mujoco.mj_forward(self.model, self.data)

    def place_in_gripper(self, block: str, steps: int = 6) -> Snapshot:
        """Put ``block`` between the first arm's fingers and close them on it: start states for put-* sub-goals."""
        arm = self.arms[0]
        self.set_block_pose(block, self.data.site_xpos[arm.grip_site].copy())
        self.data.qpos[arm.finger_qpos] = BLOCK_HALF_SIZE
        mujoco.mj_forward(self.model, self.data)
        for _ in range(steps):
            self.step(np.array([0.0, 0.0, 0.0, -1.0]), count=False)
        return self.snapshot()

    # -- control -------------------------------------------------------------------------------------
    def step(self, action: np.ndarray, count: bool = True) -> None:
        """One control step: ``action`` (4,) for the first arm (any other holds still), or (arms, 4), one per arm, each
        in the world frame. Non-finite entries count as 0; the rest is clipped to [-1, 1]."""
        given = np.atleast_2d(np.asarray(action, dtype=np.float64))
        actions = np.zeros((len(self.arms), 4))
        actions[: len(given)] = given
        if not np.isfinite(actions).all():
            actions = np.nan_to_num(actions, nan=0.0, posinf=0.0, neginf=0.0)
        actions = np.minimum(np.maximum(actions, -1.0), 1.0)
        m, d = self.model, self.data
        if self.guard is not None:
            grips = d.site_xpos[[arm.grip_site for arm in self.arms]]
            chains = np.concatenate([d.xpos[[arm.chain for arm in self.arms]], grips[:, None]], axis=1)
            holding = [held_alone(d.xpos[self._block_body], grip, opening).any() for grip, opening in self.hands()]
            actions = self.guard(chains, actions, grips[:, 2], np.array(holding), *self.arm_clearance())
        for arm, action in zip(self.arms, actions, strict=True):
            target = d.xpos[arm.gripper_body] + action[:3] * MAX_DISPLACEMENT
            d.mocap_pos[arm.mocap] = np.clip(
                target, WORKSPACE_LOW + (d.xpos[arm.gripper_body] - d.site_xpos[arm.grip_site]), self._workspace_high)
            d.mocap_quat[arm.mocap] = arm.quaternion
            d.ctrl[arm.finger_actuators] = d.qpos[arm.finger_qpos] + action[3]
        if len(self.arms) == 1:
            mujoco.mj_step(m, d, nstep=N_SUBSTEPS)
        else:  # substep by substep, to see every touch between the arms
            for _ in range(N_SUBSTEPS):
                mujoco.mj_step(m, d)
                arms = self._arm_of_geom[d.contact.geom[: d.ncon]]
                self.arm_contacts += bool(((arms >= 0).all(axis=1) & (arms[:, 0] != arms[:, 1])).any())
        if count:
            self.step_count += 1

    def arm_clearance(self, within: float = CLEARANCE_RANGE) -> tuple[float, np.ndarray]:
        """The least distance (m) between the two arms' reaching links now (their meshes; ``within`` where they are
        farther apart than that), and the unit vector from the first arm's nearest point to the second's."""
        m, d = self.model, self.data
        best, direction, fromto = within, np.zeros(3), np.zeros(6)
        for a in self._reaching[0]:
            for b in self._reaching[1]:
                distance = mujoco.mj_geomDistance(m, d, a, b, best, fromto)
                if distance < best:
                    best, gap = distance, fromto[3:] - fromto[:3]
                    direction = gap / max(float(np.linalg.norm(gap)), 1e-9)
        return best, direction

    # -- read-out ------------------------------------------------------------------------------------
    def snapshot(self, arm: int = 0) -> Snapshot:
        """The world now, with arm ``arm``'s hand (the others' in :attr:`Snapshot.other_hands`)."""
        d, hand = self.data, self.arms[arm]  # take() copies, as a fancy index does, at a third of its cost
        velocities = d.qvel.take(self._block_velocity_index).reshape(len(self.blocks), 6)
        grip_velocity = np.empty(6)
        mujoco.mj_objectVelocity(self.model, d, mujoco.mjtObj.mjOBJ_SITE, hand.grip_site, grip_velocity, 0)
        return Snapshot(
            step=self.step_count,
            time=self.step_count * CONTROL_DT,
            block_positions=d.xpos.take(self._block_body, axis=0),
            block_quaternions=d.xquat.take(self._block_body, axis=0),
            block_velocities=velocities,
            grip_position=d.site_xpos[hand.grip_site].copy(),
            grip_velocity=grip_velocity[3:],
            finger_positions=d.qpos.take(hand.finger_qpos),
            finger_velocities=d.qvel.take(hand.finger_qvel),
            other_hands=() if len(self.arms) == 1 else tuple(
                (d.site_xpos[other.grip_site].copy(), float(d.qpos[other.finger_qpos].sum()))
                for other in self.arms if other is not hand),
        )

    def hands(self) -> list[tuple[np.ndarray, float]]:
        """Each arm's grip position and finger opening now."""
        d = self.data
        return [(d.site_xpos[arm.grip_site].copy(), float(d.qpos[arm.finger_qpos].sum())) for arm in self.arms]

    def hand_boxes(self, arm: int = 0) -> list[tuple[np.ndarray, np.ndarray]]:
        """A world-aligned box (centre, half extents) around each colliding part of an arm's hand now."""
        m, d = self.model, self.data
        boxes = []
        for geom in self.arms[arm].hand_geoms:
            rotation = d.geom_xmat[geom].reshape(3, 3)
            local = m.geom_aabb[geom]
            boxes.append((d.geom_xpos[geom] + rotation @ local[:3], np.abs(rotation) @ local[3:]))
        return boxes

    def holder(self, block: str) -> int | None:
        """The arm whose hand holds ``block`` now (``holding``'s geometry), or None."""
        return holder_of(self.blocks.index(block), self.data.xpos[self._block_body], self.hands())

    def reach(self, block: str) -> tuple[str, ...]:
        """The robots that may take a step on ``block`` where it is now, the nearer first
        (:func:`semgoal_core.arms.takers`)."""
        return tuple(robot_name(arm) for arm in takers(self.blocks.index(block), self.data.xpos[self._block_body],
                                                       self.hands()))

    def grip_pose(self, arm: int = 0) -> np.ndarray:
        """4x4 pose of an arm's grip site in the world (what /tf publishes as the gripper's frame)."""
        site = self.arms[arm].grip_site
        return _pose(self.data.site_xpos[site], self.data.site_xmat[site])

    def base_pose(self, arm: int = 0) -> np.ndarray:
        """4x4 pose of an arm's base in the world."""
        body = self.arms[arm].base_body
        return _pose(self.data.xpos[body], self.data.xmat[body])

    def robot_joint_state(self) -> tuple[np.ndarray, np.ndarray]:
        """Positions and velocities of :attr:`robot_joint_names`, now."""
        return self.data.qpos[self._robot_qpos], self.data.qvel[self._robot_qvel]

    def padded_positions(self, snapshot: Snapshot) -> np.ndarray:
        """(max_blocks, 3) block centres with absent slots at zero: the scene-wide layout."""
        if self._partial is None:
            return snapshot.block_positions
        positions = np.zeros((self.scene.max_blocks, 3))
        positions[: len(self.blocks)] = snapshot.block_positions
        return positions

    def semantic_vector(self, snapshot: Snapshot | None = None) -> np.ndarray:
        snapshot = snapshot or self.snapshot()
        return evaluate(self.layout, self.padded_positions(snapshot), snapshot.grip_position,
                        snapshot.finger_opening, TABLE_TOP, self._partial, other_hands=snapshot.other_hands)

    def motion(self, snapshot: Snapshot | None = None, vector: np.ndarray | None = None) -> np.ndarray:
        """(2 * max_blocks,) per block slot: moving, then held (:func:`semgoal_core.settling.motion_bits`);
        ``vector``: the snapshot's semantic vector, whose ``holding`` entries say what is held."""
        snapshot = snapshot or self.snapshot()
        vx, vy, vz = snapshot.block_velocities[:, :3].T
        speeds = np.sqrt(vx * vx + vy * vy + vz * vz)  # np.linalg.norm's, a column at a time
        held = (self.semantic_vector(snapshot) if vector is None else vector).take(self._holding_entries)
        return motion_bits(speeds, held, self.scene.max_blocks)

    def fallen_blocks(self, snapshot: Snapshot | None = None) -> list[str]:
        """The blocks that fell off the table, out of the arm's reach."""
        snapshot = snapshot or self.snapshot()
        return fallen_blocks(self.blocks, snapshot.block_positions, TABLE_TOP)

    def view(self, snapshot: Snapshot | None = None) -> WorldView:
        """The expert's view of the world: block centres by name, grip, finger opening, bin."""
        snapshot = snapshot or self.snapshot()
        return WorldView(dict(zip(self.blocks, snapshot.block_positions, strict=True)), snapshot.grip_position,
                         snapshot.finger_opening, self.scene.bin, grip_ceiling(self.scene))

    def observation(self, snapshot: Snapshot | None = None, arm: int = 0) -> np.ndarray:
        """The policy observation of arm ``arm``'s hand, in the world frame (:func:`semgoal_core.arms.arm_observation`:
        a block in another arm's hand shown at rest on the table under it)."""
        snapshot = snapshot or self.snapshot(arm)
        return arm_observation(self.scene.name, snapshot.grip_position, snapshot.grip_velocity,
                               snapshot.finger_positions, snapshot.finger_velocities, snapshot.block_positions,
                               snapshot.block_velocities, snapshot.other_hands)
