"""MuJoCo models of the scenes, generated from one parametric description with ``mujoco.MjSpec``.

The Fetch robot, table and materials come from the MJCF that gymnasium-robotics installs (loaded from
the installed package, never copied; its env classes are not used). Its single ``object0`` block is
removed and the scene's coloured blocks (and the bin) are added programmatically.
"""

from __future__ import annotations

import functools
from pathlib import Path

import mujoco

from semgoal_core.geometry import TABLE_TOP
from semgoal_core.vocabulary import BLOCK_COLOURS, BLOCK_HALF_SIZE, SCENES, BinGeometry, Scene

BLOCK_MASS = 2.0
"""kg, as the Fetch benchmark's object0."""
TOUCHING_LINKS = ("forearm_roll_link", "wrist_flex_link", "wrist_roll_link", "gripper_link",
                  "r_gripper_finger_link", "l_gripper_finger_link")
"""The robot links that can reach the desk; only their meshes collide. Over expert runs of six tasks
only the fingers touched anything but the floor (the base rests on it, held by its slide joints), and
checking the other links' meshes and the base's floor contacts every substep cost a third of the
physics time."""
BLOCK_CONTACT_BIT = 2
"""Collision bit that only the floor's type and the blocks' affinity carry: a block knocked off the desk
lands on the floor, nothing else touches it."""


def fetch_asset_dir() -> Path:
    """The Fetch MJCF folder installed by gymnasium-robotics."""
    import importlib.util

    spec = importlib.util.find_spec("gymnasium_robotics")
    if spec is None or spec.origin is None:
        raise ModuleNotFoundError("gymnasium-robotics is not installed: it provides the Fetch robot assets (make setup)")
    return Path(spec.origin).parent / "envs" / "assets" / "fetch"


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
        condim=3,
        conaffinity=1 | BLOCK_CONTACT_BIT,
    )
    body.add_site(name=block_body_name(name), size=[0.005, 0.005, 0.005], rgba=[0, 0, 0, 0])


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


def build_spec(scene: Scene, blocks: tuple[str, ...]) -> mujoco.MjSpec:
    """The MjSpec of ``scene`` with ``blocks``: Fetch robot and table from the assets, our objects added."""
    spec = mujoco.MjSpec.from_file(str(fetch_asset_dir() / "pick_and_place.xml"))
    spec.modelname = f"semgoal_{scene.name}_{len(blocks)}"
    spec.delete(spec.body("object0"))
    spec.delete(spec.site("target0"))
    _filter_collisions(spec)
    for block in blocks:
        _add_block(spec, block)
    if scene.bin is not None:
        _add_bin(spec, scene.bin)
    return spec


@functools.cache
def build_model(scene_name: str, n_blocks: int | None = None) -> mujoco.MjModel:
    """Compile the model of a scene (cached: models are immutable in use, data is per world).

    :param n_blocks: desk cleanup only: how many of its blocks to build (2 to 4); None = all.
    """
    scene = SCENES[scene_name]
    count = scene.max_blocks if n_blocks is None else n_blocks
    if count != scene.max_blocks and count not in scene.block_counts:
        raise ValueError(f"scene {scene_name!r} cannot have {count} blocks (allowed: {scene.block_counts or scene.max_blocks})")
    return build_spec(scene, scene.objects[:count]).compile()
