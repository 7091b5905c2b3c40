"""MuJoCo models of the scenes, generated from one parametric description with ``mujoco.MjSpec``.

The Fetch robot, table and materials come from the MJCF that gymnasium-robotics installs (loaded from
the installed package, never copied; its env classes are not used). Its single ``object0`` block is
removed and the scene's coloured blocks (and the bin) are added programmatically. A second arm is a second
copy of the same robot, attached under the name prefix ``robot2/`` across the table, turned half a turn
(``semgoal_core.arms``).
"""

from __future__ import annotations

import functools
import itertools
from dataclasses import dataclass
from pathlib import Path

import mujoco

from semgoal_core.arms import MAX_ARMS, MIRROR_X, arm_namespace
from semgoal_core.geometry import TABLE_TOP
from semgoal_core.vocabulary import BLOCK_COLOURS, BLOCK_HALF_SIZE, SCENES, BinGeometry, Scene

BLOCK_MASS = 2.0
"""kg, as the Fetch benchmark's object0."""
BLOCK_FRICTION = (1.0, 0.005, 0.0001)
"""Sliding, torsional, rolling: MuJoCo's defaults, as the benchmark's object0."""
TOUCHING_LINKS = ("forearm_roll_link", "wrist_flex_link", "wrist_roll_link", "gripper_link",
                  "r_gripper_finger_link", "l_gripper_finger_link")
"""The robot links that can reach the desk; only their meshes collide. Over expert runs of six tasks
only the fingers touched anything but the floor (the base rests on it, held by its slide joints), and
checking the other links' meshes and the base's floor contacts every substep cost a third of the
physics time."""
BLOCK_CONTACT_BIT = 2
"""Collision bit that only the floor's type and the blocks' affinity carry: a block knocked off the desk
lands on the floor, nothing else touches it."""
REACHING_LINKS = ("shoulder_pan_link", "shoulder_lift_link", "upperarm_roll_link", "elbow_flex_link",
                  *TOUCHING_LINKS)
"""The links that can reach over the table, where two arms may meet."""
ARM_CONTACT_BITS = (4, 8)
"""Collision bits of each arm's reaching links: an arm's type with its own bit, its affinity with the other's,
so two arms collide (and are seen to: ``FetchWorld.arm_contacts``) and an arm's links never with each other."""


@dataclass(frozen=True)
class Contact:
    """MuJoCo contact parameters for one kind of geom pair (``solref``, ``solimp``: MuJoCo's "Solver parameters")."""

    solref: tuple[float, float]
    solimp: tuple[float, float, float, float, float]


STACKING_CONTACT = Contact(solref=(0.005, 1.0), solimp=(0.99, 0.999, 0.001, 0.5, 2.0))
"""Block on block where towers stand high (``Scene.stiff_stacking``): with MuJoCo's default soft contacts (timeconst
0.02 s, impedance 0.9-0.95) a tower of six whose upper five blocks overhang the bottom one by 8 mm sinks into the
contact on its overhanging side, tilts and falls, where a rigid one stands until the overhang reaches the block's
half size (2.5 cm). With this impedance near 1 and the time constant at 2.5 physics steps (MuJoCo asks for at least
two) it stands to 2 cm, and blocks at rest stop jittering (``tests/unit/sim/test_tabletop.py``). Only block-block
pairs change: the hand's grasp and the table are the benchmark's, as the actor learned them."""


def fetch_asset_dir() -> Path:
    """The Fetch MJCF folder installed by gymnasium-robotics."""
    import importlib.util

    spec = importlib.util.find_spec("gymnasium_robotics")
    if spec is None or spec.origin is None:
        raise ModuleNotFoundError("gymnasium-robotics is not installed: it provides the Fetch robot assets (make setup)")
    return Path(spec.origin).parent / "envs" / "assets" / "fetch"


ROBOT_BASE_Y = 0.2641 + 0.48
"""y of the first Fetch's base in the world (its body's offset plus the benchmark's slide joint): the second
stands on the same line across the table."""


def arm_prefix(arm: int) -> str:
    """The name prefix of arm ``arm``'s elements in the model: none for the first, ``robot2/`` for the second."""
    return f"{arm_namespace(arm)}/" if arm else ""


def block_body_name(block: str) -> str:
    return f"block_{block}"


def _add_block(spec: mujoco.MjSpec, name: str) -> None:
    body = spec.worldbody.add_body(name=block_body_name(name), pos=[0.0, 0.0, TABLE_TOP + BLOCK_HALF_SIZE])
    body.add_freejoint(name=f"{block_body_name(name)}:joint")
    body.add_geom(
        name=block_body_name(name),
        type=mujoco.mjtGeom.mjGEOM_BOX,
        size=[BLOCK_HALF_SIZE] * 3,
        rgba=list(BLOCK_COLOURS[name]),
        mass=BLOCK_MASS,
        friction=list(BLOCK_FRICTION),
        condim=3,
        conaffinity=1 | BLOCK_CONTACT_BIT,
    )
    body.add_site(name=block_body_name(name), size=[0.005, 0.005, 0.005], rgba=[0, 0, 0, 0])


def _stiffen_stacking(spec: mujoco.MjSpec, blocks: tuple[str, ...]) -> None:
    """Every two blocks meet through an explicit contact pair of :data:`STACKING_CONTACT` instead of the default one
    (excluded): MuJoCo's way to give one kind of geom pair its own contact parameters."""
    sliding, torsional, rolling = BLOCK_FRICTION
    for first, second in itertools.combinations(map(block_body_name, blocks), 2):
        spec.add_exclude(bodyname1=first, bodyname2=second)
        spec.add_pair(geomname1=first, geomname2=second, condim=3, friction=[sliding, sliding, torsional, rolling, rolling],
                      solref=list(STACKING_CONTACT.solref), solimp=list(STACKING_CONTACT.solimp))


def _add_bin(spec: mujoco.MjSpec, geometry: BinGeometry) -> None:
    cx, cy = geometry.center
    hx, hy = geometry.inner_half_size
    t, h, back = geometry.wall_thickness, geometry.wall_height, geometry.back_wall_height
    body = spec.worldbody.add_body(name="bin", pos=[cx, cy, TABLE_TOP])
    colour = [0.45, 0.33, 0.22, 1.0]
    body.add_geom(name="bin_floor", type=mujoco.mjtGeom.mjGEOM_BOX, rgba=colour,
                  size=[hx + t, hy + t, geometry.floor_thickness / 2], pos=[0, 0, geometry.floor_thickness / 2])
    z, back_z = geometry.floor_thickness + h / 2, geometry.floor_thickness + back / 2
    for name, pos, size in (
        ("bin_wall_x_neg", [-(hx + t / 2), 0, z], [t / 2, hy + t, h / 2]),
        ("bin_wall_x_pos", [hx + t / 2, 0, z], [t / 2, hy + t, h / 2]),
        ("bin_wall_y_neg", [0, -(hy + t / 2), z], [hx + t, t / 2, h / 2]),
        ("bin_wall_y_pos", [0, hy + t / 2, back_z], [hx + t, t / 2, back / 2]),
    ):
        body.add_geom(name=name, type=mujoco.mjtGeom.mjGEOM_BOX, pos=pos, size=size, rgba=colour)


def _filter_collisions(spec: mujoco.MjSpec) -> None:
    """Only the links that reach the desk collide; the floor only catches blocks (see TOUCHING_LINKS)."""
    touching = {f"robot0:{link}" for link in TOUCHING_LINKS}
    for geom in spec.geoms:
        if geom.name.startswith("robot0:") and geom.name not in touching:
            geom.contype = geom.conaffinity = 0
    floor = spec.geom("floor0")
    floor.contype, floor.conaffinity = BLOCK_CONTACT_BIT, 0


def _fetch_spec() -> mujoco.MjSpec:
    """The benchmark's Fetch at its table, without its block and target."""
    spec = mujoco.MjSpec.from_file(str(fetch_asset_dir() / "pick_and_place.xml"))
    spec.delete(spec.body("object0"))
    spec.delete(spec.site("target0"))
    _filter_collisions(spec)
    return spec


def _add_arm(spec: mujoco.MjSpec, arm: int) -> None:
    """Another Fetch (its mocap, weld, finger actuators and contact exclusions with it) across the table: turned half
    a turn about the vertical through (MIRROR_X, ROBOT_BASE_Y), so its base stands where the first one's reflection
    about the table's centre line does."""
    robot = _fetch_spec()
    for element in (robot.body("floor0"), robot.body("table0"), *robot.lights):
        robot.delete(element)
    robot.delete(robot.geom("floor0"))
    frame = spec.worldbody.add_frame(pos=[2 * MIRROR_X, 2 * ROBOT_BASE_Y, 0.0], quat=[0.0, 0.0, 0.0, 1.0])
    spec.attach(robot, frame=frame, prefix=arm_prefix(arm))


def _arms_collide(spec: mujoco.MjSpec, arms: int) -> None:
    """Each arm's reaching links collide with the other arm's (:data:`ARM_CONTACT_BITS`)."""
    for arm in range(arms):
        own, other = ARM_CONTACT_BITS[arm], ARM_CONTACT_BITS[1 - arm]
        for link in REACHING_LINKS:
            geom = spec.geom(f"{arm_prefix(arm)}robot0:{link}")
            geom.contype, geom.conaffinity = geom.contype | own, geom.conaffinity | other


def build_spec(scene: Scene, blocks: tuple[str, ...], arms: int = 1) -> mujoco.MjSpec:
    """The MjSpec of ``scene`` with ``blocks`` and ``arms`` Fetch arms: robot and table from the assets, our objects
    added."""
    if not 1 <= arms <= MAX_ARMS:
        raise ValueError(f"a scene has 1 to {MAX_ARMS} arms, not {arms}")
    spec = _fetch_spec()
    spec.modelname = f"semgoal_{scene.name}_{len(blocks)}" + (f"_{arms}arms" if arms > 1 else "")
    for arm in range(1, arms):
        _add_arm(spec, arm)
    if arms > 1:
        _arms_collide(spec, arms)
    for block in blocks:
        _add_block(spec, block)
    if scene.stiff_stacking:
        _stiffen_stacking(spec, blocks)
    if scene.bin is not None:
        _add_bin(spec, scene.bin)
    return spec


@functools.cache
def build_model(scene_name: str, n_blocks: int | None = None, arms: int = 1, sleep: bool = True) -> mujoco.MjModel:
    """Compile the model of a scene (cached: models are immutable in use, data is per world).

    :param n_blocks: desk cleanup only: how many of its blocks to build (2 to 4); None = all.
    :param arms: 1, or 2 for a second arm across the table.
    :param sleep: blocks at rest sleep (MuJoCo's sleeping islands): skipped by the physics until something
        touches them or moves them, which halves the desk's cost per step. On by default: the shipped actors, trained
        awake, succeed as often with it (docs/simulation.md); False keeps every body awake, as they were trained.
    """
    scene = SCENES[scene_name]
    count = scene.max_blocks if n_blocks is None else n_blocks
    if count != scene.max_blocks and count not in scene.block_counts:
        raise ValueError(f"scene {scene_name!r} cannot have {count} blocks (allowed: {scene.block_counts or scene.max_blocks})")
    spec = build_spec(scene, scene.objects[:count], arms)
    if sleep:
        spec.option.enableflags |= int(mujoco.mjtEnableBit.mjENBL_SLEEP)
    return spec.compile()
