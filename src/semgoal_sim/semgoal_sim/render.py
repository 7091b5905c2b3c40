"""Offscreen pictures of the world (MuJoCo renderer; OSMesa on machines without a GPU)."""

from __future__ import annotations

import argparse
import os
from pathlib import Path
from typing import ClassVar

import mujoco
import numpy as np

from semgoal_core.arguments import natural
from semgoal_sim.world import FetchWorld


def camera() -> mujoco.MjvCamera:
    """A view from the front-left of the table, the arm and the whole table top in frame."""
    cam = mujoco.MjvCamera()
    cam.lookat[:] = (1.3, 0.75, 0.45)
    cam.distance, cam.azimuth, cam.elevation = 1.25, 150.0, -32.0
    return cam


class FrameRenderer:
    """Renders frames of one world; reuse it across frames (creating a GL context is slow)."""

    def __init__(self, world: FetchWorld, width: int = 480, height: int = 360) -> None:
        self.world = world
        self.renderer = mujoco.Renderer(world.model, height=height, width=width)
        self.camera = camera()

    def frame(self) -> np.ndarray:
        self.renderer.update_scene(self.world.data, self.camera)
        return self.renderer.render()

    def close(self) -> None:
        self.renderer.close()


class RgbArrayRendering:
    """gymnasium's ``render_mode="rgb_array"`` for an env with a ``world``: :meth:`render` returns the frame
    of the world as it is (height x width x 3, uint8), one renderer per world the env switches between."""

    metadata: ClassVar[dict] = {"render_modes": ["rgb_array"], "render_fps": 25}
    world: FetchWorld

    def _set_render_mode(self, render_mode: str | None) -> None:
        if render_mode not in (None, *self.metadata["render_modes"]):
            raise ValueError(f"render_mode {render_mode!r}: this env renders {self.metadata['render_modes']} (or None)")
        self.render_mode = render_mode
        self._renderers: dict[int, FrameRenderer] = {}

    def render(self) -> np.ndarray | None:
        if self.render_mode is None:
            return None
        if id(self.world) not in self._renderers:
            self._renderers[id(self.world)] = FrameRenderer(self.world)
        return self._renderers[id(self.world)].frame()

    def close(self) -> None:
        for renderer in self._renderers.values():
            renderer.close()
        self._renderers.clear()


def main(argv: list[str]) -> int:
    """`./semgoal render --task T [--seed S] [--solved] --out FILE.png`: a picture of a task's start state; with
    ``--solved``, beside it the end the scripted expert reaches (no learned actor: a picture of the scene's goal)."""
    os.environ.setdefault("MUJOCO_GL", "osmesa")
    import imageio.v3 as iio

    from semgoal_core.tasks import get_task
    from semgoal_sim.rollout import solve

    parser = argparse.ArgumentParser(prog="semgoal render", description=main.__doc__)
    parser.add_argument("--task", required=True)
    parser.add_argument("--seed", type=natural, default=0)
    parser.add_argument("--solved", action="store_true", help="the expert's end beside the start")
    parser.add_argument("--out", type=Path, required=True)
    args = parser.parse_args(argv)
    try:
        task = get_task(args.task)
    except KeyError as error:
        parser.error(str(error.args[0]))
    world = FetchWorld(task.scene, task.n_blocks)
    positions, goal = task.initial_state(args.seed)
    world.reset(positions)
    renderer = FrameRenderer(world)
    frames = [renderer.frame()]
    if args.solved:
        result = solve(world, goal)
        print(f"{task.name} seed {args.seed}: the expert {'reached' if result.success else 'did not reach'} the goal "
              f"in {result.steps} control steps")
        frames.append(renderer.frame())
    args.out.parent.mkdir(parents=True, exist_ok=True)
    iio.imwrite(args.out, np.concatenate(frames, axis=1))
    renderer.close()
    print(args.out)
    return 0
