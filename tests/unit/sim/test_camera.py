"""The RGB-D camera: its depth and intrinsics put every block pixel on that block's surface, its labels
name the right block, its looks change what it sees but never the geometry it reports."""

import numpy as np
import pytest

from semgoal_core.tasks import get_task
from semgoal_core.vocabulary import BLOCK_COLOURS, BLOCK_HALF_SIZE
from semgoal_perception.geometry import PinholeCamera
from semgoal_sim.camera import CONDITIONS, Appearance, RgbdCamera, SimCamera, block_label
from semgoal_sim.world import FetchWorld


def world_of(task_name: str, seed: int) -> FetchWorld:
    task = get_task(task_name)
    world = FetchWorld(task.scene, task.n_blocks)
    world.reset(task.initial_state(seed)[0])
    return world


def pixels_on_surfaces(world: FetchWorld, camera: RgbdCamera) -> dict[str, float]:
    """Per block: the largest distance (inf-norm, m) of its labelled pixels' back-projections from its centre."""
    frame = camera.frame(labels=True)
    k = frame.intrinsics
    points, valid = PinholeCamera(k.fx, k.fy, k.cx, k.cy, frame.world_from_camera).world_points(frame.depth)
    reach = {}
    for block, centre in zip(world.blocks, world.snapshot().block_positions, strict=True):
        mask = (frame.labels == block_label(block)) & valid
        assert mask.sum() > 20, f"{block} is not in view"
        reach[block] = float(np.abs(points[mask] - centre).max())
    return reach


@pytest.mark.parametrize("task_name", ["DC-4", "MC-3"])
def test_every_block_pixel_lies_on_its_block(task_name: str) -> None:
    world = world_of(task_name, 3)
    camera = RgbdCamera(world)
    try:
        for block, reach in pixels_on_surfaces(world, camera).items():
            assert reach < BLOCK_HALF_SIZE + 0.001, block
    finally:
        camera.close()


def test_a_random_look_moves_the_camera_and_its_reported_pose_with_it() -> None:
    world = world_of("MC-3", 5)
    camera = RgbdCamera(world)
    try:
        nominal = camera.frame()
        camera.set_appearance(Appearance.randomised(np.random.default_rng(3)), noise_seed=3)
        moved = camera.frame()
        assert not np.allclose(nominal.world_from_camera, moved.world_from_camera)
        assert not np.array_equal(nominal.rgb, moved.rgb)
        camera.set_appearance(Appearance(placement=Appearance.randomised(np.random.default_rng(3)).placement))
        for reach in pixels_on_surfaces(world, camera).values():
            assert reach < BLOCK_HALF_SIZE + 0.001
    finally:
        camera.close()


def test_depth_has_no_return_beyond_range_and_an_unknown_condition_is_refused() -> None:
    world = world_of("MC-2", 1)
    camera = SimCamera(64, 48)
    try:
        depth = camera.frame(world, episode=0, seed=1).depth
        assert depth.dtype == np.float32 and depth.min() >= 0.0 and depth.max() < 3.0
    finally:
        camera.close()
    with pytest.raises(ValueError, match="unknown camera condition"):
        SimCamera(64, 48, condition="foggy")
    assert set(CONDITIONS) >= {"nominal", "moved"}


def test_a_repainted_block_looks_and_is_labelled_as_its_paint() -> None:
    world = world_of("Tower-3", 2)
    camera = RgbdCamera(world)
    try:
        own = camera.frame(labels=True)
        look = Appearance.randomised(np.random.default_rng(7), strength=0.0, repaint=True)
        assert sorted(look.paint) == list(range(len(look.paint))) and look.paint != tuple(range(len(look.paint)))
        camera.set_appearance(look)
        repainted = camera.frame(labels=True)
        for block in world.blocks:
            paint = look.painted(block)
            mask = own.labels == block_label(block)
            assert np.array_equal(repainted.labels == block_label(paint), mask), block
            hue = np.median(repainted.rgb[mask].astype(float), axis=0)
            others = [c for c in BLOCK_COLOURS if c != paint]
            assert paint == min([paint, *others], key=lambda c: np.linalg.norm(
                hue / hue.max() - np.asarray(BLOCK_COLOURS[c][:3]) / max(BLOCK_COLOURS[c][:3]))), block
    finally:
        camera.close()
    assert Appearance.randomised(np.random.default_rng(7)).paint == ()
