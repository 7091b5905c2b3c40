"""The live view's scene is the simulated world: posed from what the sim publishes (joint states, block
poses), every geom lands where the simulation has it; blocks absent from the world are not drawn; meshes
come out as well-formed STL of the compiled model."""

import mujoco
import numpy as np
import pytest

from semgoal_sim.scene_view import SceneView, mesh_stl
from semgoal_sim.world import FetchWorld


def published_state(world: FetchWorld) -> tuple[dict[str, float], dict]:
    """What /joint_states and /semgoal/world_state carry, as the foxglove node reads them."""
    positions, _ = world.robot_joint_state()
    snapshot = world.snapshot()
    blocks = {name: (position, quaternion) for name, position, quaternion
              in zip(world.blocks, snapshot.block_positions, snapshot.block_quaternions, strict=True)}
    return dict(zip(world.robot_joint_names, positions.tolist(), strict=True)), blocks


@pytest.mark.parametrize(("scene", "arms"), [("two_blocks", 1), ("desk_cleanup", 1), ("desk_cleanup", 2)])
def test_geoms_are_where_the_simulation_puts_them(scene: str, arms: int) -> None:
    world = FetchWorld(scene, arms=arms)
    rng = np.random.default_rng(5)
    world.reset(np.array([[1.2 + 0.1 * i, 0.6 + 0.05 * i, 0.445] for i in range(len(world.blocks))]))
    for _ in range(30):  # the arm somewhere else than home, the fingers moved, the blocks possibly pushed
        world.step(rng.uniform(-1, 1, (arms, 4)))
    mujoco.mj_kinematics(world.model, world.data)  # after mj_step, geom poses are a substep behind qpos
    view = SceneView(scene, arms)
    before = {g.name: g.position for g in view.geoms()}
    view.pose(*published_state(world))
    geoms = {g.name: g for g in view.geoms()}
    links = ("robot0:gripper_link", "robot0:l_gripper_finger_link", "robot0:shoulder_pan_link")
    for name in (*links, *(f"robot2/{link}" for link in links if arms == 2), *(f"block_{b}" for b in world.blocks)):
        geom_id = world.model.geom(name).id
        np.testing.assert_allclose(geoms[name].position, world.data.geom_xpos[geom_id], atol=1e-9, err_msg=name)
        rotation = np.empty(9)
        mujoco.mju_quat2Mat(rotation, np.array(geoms[name].quaternion))
        np.testing.assert_allclose(rotation, world.data.geom_xmat[geom_id], atol=1e-9, err_msg=name)
    assert np.linalg.norm(np.subtract(geoms["robot0:gripper_link"].position, before["robot0:gripper_link"])) > 0.01
    assert geoms["robot0:gripper_link"].shape == "mesh" and geoms["robot0:gripper_link"].mesh


def test_absent_blocks_are_not_drawn_and_bad_input_is_ignored() -> None:
    view = SceneView("desk_cleanup")
    view.pose({"no_such_joint": 1.0, "robot0:torso_lift_joint": float("nan")},
              {"red": ((1.2, 0.7, 0.445), (1, 0, 0, 0)), "purple": ((0, 0, 0), (1, 0, 0, 0))})
    names = {g.name for g in view.geoms()}
    assert "block_red" in names and not names & {"block_green", "block_blue", "block_yellow"}
    assert {"bin_floor", "robot0:base_link"} <= names
    assert all(np.isfinite(g.position).all() for g in view.geoms())


def test_meshes_are_binary_stl_of_the_compiled_model() -> None:
    view = SceneView("two_blocks")
    for name in view.meshes():
        stl = mesh_stl(view.model, name)
        mesh = view.model.mesh(name)
        triangles = int(np.frombuffer(stl, "<u4", count=1, offset=80)[0])
        assert triangles == int(mesh.facenum[0]) and len(stl) == 84 + 50 * triangles
        records = np.frombuffer(stl, dtype=[("normal", "<f4", 3), ("vertices", "<f4", (3, 3)), ("attribute", "<u2")],
                                offset=84)
        first = int(mesh.vertadr[0])
        vertices = view.model.mesh_vert[first:first + int(mesh.vertnum[0])]
        np.testing.assert_allclose(records["vertices"].reshape(-1, 3).min(axis=0), vertices.min(axis=0), atol=1e-6)
        lengths = np.linalg.norm(records["normal"], axis=1)
        assert np.all((np.abs(lengths - 1) < 1e-4) | (lengths == 0))
    with pytest.raises(KeyError):
        view.mesh_stl("no_such_mesh")
