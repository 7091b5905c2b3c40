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

from semgoal_core import layout
from semgoal_core.geometry import GRASP_OPENING, TABLE_TOP
from semgoal_core.layout import CONTROL_DT
from semgoal_core.settling import motion_bits
from semgoal_core.vocabulary import BLOCK_HALF_SIZE, LAYOUTS, SCENES, evaluate, fallen_blocks, held_alone
from semgoal_sim.expert import WorldView
from semgoal_sim.scene import block_body_name, build_model

N_SUBSTEPS = 20
MAX_DISPLACEMENT = 0.05
"""End-effector displacement (m) per control step for an action of 1 (Fetch benchmark)."""
GRIPPER_HOME_OFFSET = np.array([-0.498, 0.005, -0.431 + 0.2])
"""Fetch benchmark: grip site moved by this from the initial joint pose (gripper_extra_height 0.2)."""
GRIPPER_QUAT = np.array([1.0, 0.0, 1.0, 0.0]) / np.sqrt(2.0)
"""Gripper pointing down, fixed orientation (the benchmark's mocap rotation)."""
INITIAL_QPOS = {"robot0:slide0": 0.405, "robot0:slide1": 0.48, "robot0:slide2": 0.0}
WORKSPACE_LOW = np.array([1.0, 0.35, TABLE_TOP + 0.005])
WORKSPACE_HIGH = np.array([1.6, 1.15, TABLE_TOP + 0.35])
"""The mocap target is kept in this box so the arm never drives into the table or out of reach."""


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

    @property
    def finger_opening(self) -> float:
        return float(self.finger_positions.sum())


class FetchWorld:
    """One scene's physics: seeded placement of blocks, Fetch-style control, state and predicates."""

    def __init__(self, scene: str, n_blocks: int | None = None) -> None:
        self.scene = SCENES[scene]
        self.layout = LAYOUTS[scene]
        self.model = build_model(scene, n_blocks)
        self.data = mujoco.MjData(self.model)
        self.blocks = self.scene.objects[: n_blocks or self.scene.max_blocks]
        self.present = np.array([obj in self.blocks for obj in self.scene.objects])
        m = self.model
        self._block_qpos = [m.joint(f"{block_body_name(b)}:joint").qposadr[0] for b in self.blocks]
        self._block_qvel = [m.joint(f"{block_body_name(b)}:joint").dofadr[0] for b in self.blocks]
        self._block_velocity_index = (np.asarray(self._block_qvel, dtype=int)[:, None] + np.arange(6)).reshape(-1)
        """Every block's six velocity entries in ``qvel``, in block order: one gather per snapshot."""
        self._block_body = np.array([m.body(block_body_name(b)).id for b in self.blocks])
        self._grip_site = m.site("robot0:grip").id
        self._gripper_body = m.body("robot0:gripper_link").id
        fingers = ("robot0:r_gripper_finger_joint", "robot0:l_gripper_finger_joint")
        self._finger_qpos = np.array([m.joint(f).qposadr[0] for f in fingers])
        self._finger_qvel = np.array([m.joint(f).dofadr[0] for f in fingers])
        self._finger_actuators = np.array([m.actuator(f).id for f in fingers])
        robot = [i for i in range(m.njnt) if m.joint(i).name.startswith("robot0:")]
        self.robot_joint_names = [m.joint(i).name for i in robot]
        """The robot's joints, in model order (what /joint_states names)."""
        self._robot_qpos, self._robot_qvel = m.jnt_qposadr[robot], m.jnt_dofadr[robot]
        entries, args = self.layout.groundings["holding"]
        self._holding_entries = entries[np.argsort(args[:, 0])][: len(self.blocks)]
        """The semantic vector's ``holding(block)`` entry of each block built, in block order."""
        self.step_count = 0
        self._home_state = self._settle_home()

    # -- reset ---------------------------------------------------------------------------------------
    def _settle_home(self) -> np.ndarray:
        """Put the arm in the benchmark's home pose once; later resets restore this state."""
        m, d = self.model, self.data
        mujoco.mj_resetData(m, d)
        weld = m.eq_type == mujoco.mjtEq.mjEQ_WELD  # the mocap weld: no offset between mocap and gripper
        m.eq_data[weld, :7] = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0]
        for name, value in INITIAL_QPOS.items():
            d.qpos[m.joint(name).qposadr[0]] = value
        for i, addr in enumerate(self._block_qpos):  # park blocks apart, off the arm's way, during settling
            d.qpos[addr: addr + 7] = [1.1 + 0.1 * i, 0.45, TABLE_TOP + BLOCK_HALF_SIZE, 1, 0, 0, 0]
        mujoco.mj_forward(m, d)
        d.mocap_pos[0] = d.site_xpos[self._grip_site] + GRIPPER_HOME_OFFSET
        d.mocap_quat[0] = GRIPPER_QUAT
        for _ in range(10):
            mujoco.mj_step(m, d, nstep=N_SUBSTEPS)
        self.home_grip_position = d.site_xpos[self._grip_site].copy()
        state = np.empty(mujoco.mj_stateSize(m, mujoco.mjtState.mjSTATE_INTEGRATION))
        mujoco.mj_getState(m, d, state, mujoco.mjtState.mjSTATE_INTEGRATION)
        return state

    def reset(self, block_positions: np.ndarray, settle_steps: int = 10) -> Snapshot:
        """Arm at home, blocks at ``block_positions`` (N, 3) upright and at rest, then let them settle.

        Settling (arm held still) lets stacked starts come to rest before the first observation.
        """
        m, d = self.model, self.data
        mujoco.mj_setState(m, d, self._home_state, mujoco.mjtState.mjSTATE_INTEGRATION)
        for addr, dof, pos in zip(self._block_qpos, self._block_qvel, np.asarray(block_positions), strict=True):
            d.qpos[addr: addr + 7] = [*pos, 1.0, 0.0, 0.0, 0.0]
            d.qvel[dof: dof + 6] = 0.0
        mujoco.mj_forward(m, d)
        self.step_count = 0
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

    def open_fingers(self, opening: float = GRASP_OPENING) -> None:
        """Open the fingers to ``opening`` (m, both together) at once and keep them there: a hand let go of."""
        self.data.qpos[self._finger_qpos] = opening / 2
        self.data.qvel[self._finger_qvel] = 0.0
        self.data.ctrl[self._finger_actuators] = opening / 2
        mujoco.mj_forward(self.model, self.data)

    def place_in_gripper(self, block: str, steps: int = 6) -> Snapshot:
        """Put ``block`` between the fingers and close them on it: start states for put-* sub-goals."""
        self.set_block_pose(block, self.data.site_xpos[self._grip_site].copy())
        self.data.qpos[self._finger_qpos] = BLOCK_HALF_SIZE
        mujoco.mj_forward(self.model, self.data)
        for _ in range(steps):
            self.step(np.array([0.0, 0.0, 0.0, -1.0]), count=False)
        return self.snapshot()

    # -- control -------------------------------------------------------------------------------------
    def step(self, action: np.ndarray, count: bool = True) -> None:
        """One control step. Non-finite entries count as 0; the rest is clipped to [-1, 1]."""
        action = np.asarray(action, dtype=np.float64)
        if not np.isfinite(action).all():
            action = np.nan_to_num(action, nan=0.0, posinf=0.0, neginf=0.0)
        action = np.minimum(np.maximum(action, -1.0), 1.0)
        m, d = self.model, self.data
        target = d.xpos[self._gripper_body] + action[:3] * MAX_DISPLACEMENT
        d.mocap_pos[0] = np.clip(target, WORKSPACE_LOW + (d.xpos[self._gripper_body] - d.site_xpos[self._grip_site]),
                                 WORKSPACE_HIGH)
        d.mocap_quat[0] = GRIPPER_QUAT
        d.ctrl[self._finger_actuators] = d.qpos[self._finger_qpos] + action[3]
        mujoco.mj_step(m, d, nstep=N_SUBSTEPS)
        if count:
            self.step_count += 1

    # -- read-out ------------------------------------------------------------------------------------
    def snapshot(self) -> Snapshot:
        d = self.data
        velocities = d.qvel[self._block_velocity_index].reshape(len(self.blocks), 6)
        grip_velocity = np.empty(6)
        mujoco.mj_objectVelocity(self.model, d, mujoco.mjtObj.mjOBJ_SITE, self._grip_site, grip_velocity, 0)
        return Snapshot(
            step=self.step_count,
            time=self.step_count * CONTROL_DT,
            block_positions=d.xpos[self._block_body].copy(),
            block_quaternions=d.xquat[self._block_body].copy(),
            block_velocities=velocities,
            grip_position=d.site_xpos[self._grip_site].copy(),
            grip_velocity=grip_velocity[3:].copy(),
            finger_positions=d.qpos[self._finger_qpos].copy(),
            finger_velocities=d.qvel[self._finger_qvel].copy(),
        )

    def grip_pose(self) -> np.ndarray:
        """4x4 pose of the grip site in the world (what /tf publishes as the gripper's frame)."""
        return _pose(self.data.site_xpos[self._grip_site], self.data.site_xmat[self._grip_site])

    def base_pose(self) -> np.ndarray:
        """4x4 pose of the robot's base in the world."""
        body = self.model.body("robot0:base_link").id
        return _pose(self.data.xpos[body], self.data.xmat[body])

    def robot_joint_state(self) -> tuple[np.ndarray, np.ndarray]:
        """Positions and velocities of :attr:`robot_joint_names`, now."""
        return self.data.qpos[self._robot_qpos], self.data.qvel[self._robot_qvel]

    def padded_positions(self, snapshot: Snapshot) -> np.ndarray:
        """(max_blocks, 3) block centres with absent slots at zero: the scene-wide layout."""
        positions = np.zeros((self.scene.max_blocks, 3))
        positions[: len(self.blocks)] = snapshot.block_positions
        return positions

    def semantic_vector(self, snapshot: Snapshot | None = None) -> np.ndarray:
        snapshot = snapshot or self.snapshot()
        return evaluate(self.layout, self.padded_positions(snapshot), snapshot.grip_position,
                        snapshot.finger_opening, TABLE_TOP, self.present)

    def motion(self, snapshot: Snapshot | None = None, vector: np.ndarray | None = None) -> np.ndarray:
        """(2 * max_blocks,) per block slot: moving, then held (:func:`semgoal_core.settling.motion_bits`);
        ``vector``: the snapshot's semantic vector, whose ``holding`` entries say what is held."""
        snapshot = snapshot or self.snapshot()
        speeds = np.linalg.norm(snapshot.block_velocities[:, :3], axis=1)
        held = (held_alone(snapshot.block_positions, snapshot.grip_position, snapshot.finger_opening) if vector is None
                else vector[self._holding_entries])
        return motion_bits(speeds, held, self.scene.max_blocks)

    def fallen_blocks(self, snapshot: Snapshot | None = None) -> list[str]:
        """The blocks that fell off the table, out of the arm's reach."""
        snapshot = snapshot or self.snapshot()
        return fallen_blocks(self.blocks, snapshot.block_positions, TABLE_TOP)

    def view(self, snapshot: Snapshot | None = None) -> WorldView:
        """The expert's view of the world: block centres by name, grip, finger opening, bin."""
        snapshot = snapshot or self.snapshot()
        return WorldView(dict(zip(self.blocks, snapshot.block_positions, strict=True)), snapshot.grip_position,
                         snapshot.finger_opening, self.scene.bin)

    def observation(self, snapshot: Snapshot | None = None) -> np.ndarray:
        """The policy observation (layout: :mod:`semgoal_core.layout`)."""
        snapshot = snapshot or self.snapshot()
        return layout.observation(self.scene.name, snapshot.grip_position, snapshot.grip_velocity,
                                  snapshot.finger_positions, snapshot.finger_velocities,
                                  snapshot.block_positions, snapshot.block_velocities)
