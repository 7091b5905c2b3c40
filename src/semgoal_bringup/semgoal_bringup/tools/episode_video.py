"""A video of an episode seen over ROS (an animated GIF, or MP4 / H.264 through PyAV): joint states and block
poses replayed into a local MuJoCo model and rendered offscreen, with the active sub-goal written on every
frame."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import mujoco
import numpy as np

from semgoal_sim.render import FrameRenderer
from semgoal_sim.scene import arm_prefix
from semgoal_sim.world import FetchWorld


@dataclass
class Frame:
    step: int
    joints: dict[str, float]
    block_poses: dict[str, np.ndarray]
    """name -> (x, y, z, qw, qx, qy, qz)."""
    caption: str


def frames_from(worlds, joints: dict[tuple[int, int], dict[str, float]], decisions: dict[tuple[int, int], object],
                every: int = 2) -> list[Frame]:
    """Frames of the last episode among ``worlds`` (WorldState messages), one per ``every`` steps: the arm's
    joints at the same stamp (``joints``: joint name -> position by (sec, nanosec)), the blocks' poses, and
    as caption the sub-goal the policy followed there (``decisions``: SubGoal by (episode, step),
    :func:`semgoal_core.lockstep.followed_decision`), or the planner's status."""
    from semgoal_core.lockstep import followed_decision
    from semgoal_ros.messages import block_poses

    worlds = list(worlds)
    episode = worlds[-1].episode if worlds else None
    frames, seen = [], set()
    for msg in worlds:
        arm = joints.get((msg.header.stamp.sec, msg.header.stamp.nanosec))
        if msg.episode != episode or arm is None or msg.step in seen or msg.step % every:  # a heartbeat repeats a step
            continue
        seen.add(msg.step)
        followed = followed_decision(decisions, episode, msg.step)
        decision = decisions.get((episode, msg.step))
        caption = followed.action if followed else f"({decision.status})" if decision else ""
        frames.append(Frame(int(msg.step), arm, dict(zip(msg.block_names, block_poses(msg), strict=True)), caption))
    return frames


def write_video(scene: str, n_blocks: int, frames: list[Frame], path: Path, fps: float = 12.5) -> Path:
    """``path`` as an animated GIF, or as MP4 when it ends in ``.mp4``."""
    images = render(scene, n_blocks, frames)
    path.parent.mkdir(parents=True, exist_ok=True)
    if path.suffix.lower() == ".mp4":
        _write_mp4(images, path, fps)
    else:
        import imageio.v3 as iio

        iio.imwrite(path, np.stack(images), duration=1000.0 / fps, loop=0)
    return path


def render(scene: str, n_blocks: int, frames: list[Frame]) -> list[np.ndarray]:
    """An RGB image per frame, captioned with its step and sub-goal (both arms where the joints name a second)."""
    painter = FramePainter(scene, n_blocks, arms_named(joint for frame in frames for joint in frame.joints))
    try:
        return [painter.image(frame) for frame in frames]
    finally:
        painter.close()


def arms_named(joints) -> int:
    """How many arms joint names from /joint_states belong to: 2 where one is the second arm's (``robot2/...``)."""
    return 2 if any(name.startswith(arm_prefix(1)) for name in joints) else 1


class FramePainter:
    """One scene's world and offscreen renderer, for many frames (an episode's, the console's live view)."""

    def __init__(self, scene: str, n_blocks: int, arms: int = 1, width: int = 400, height: int = 300) -> None:
        self.world = FetchWorld(scene, n_blocks, arms)
        self.renderer = FrameRenderer(self.world, width=width, height=height)
        self._joint_qpos = {name: self.world.model.joint(name).qposadr[0] for name in self.world.robot_joint_names}

    def image(self, frame: Frame) -> np.ndarray:
        """``frame`` rendered, its step and caption on a black band at the top."""
        from PIL import Image, ImageDraw

        world = self.world
        model, data = world.model, world.data
        for name, value in frame.joints.items():
            if name in self._joint_qpos:  # another arm's joints than this model has are not drawn
                data.qpos[self._joint_qpos[name]] = value
        for name, pose in frame.block_poses.items():
            if name in world.blocks:
                world.set_block_pose(name, pose[:3], pose[3:])
        mujoco.mj_forward(model, data)
        image = Image.fromarray(self.renderer.frame())
        draw = ImageDraw.Draw(image)
        draw.rectangle((0, 0, image.width, 22), fill=(0, 0, 0))
        draw.text((6, 5), f"step {frame.step:4d}  {frame.caption}", fill=(255, 255, 255))
        return np.asarray(image)

    def close(self) -> None:
        self.renderer.close()


def _write_mp4(images: list[np.ndarray], path: Path, fps: float) -> None:
    """H.264 in yuv420p (what browsers and players take), at ``fps``."""
    from fractions import Fraction

    import av

    height, width = images[0].shape[:2]
    with av.open(str(path), "w") as container:
        stream = container.add_stream("libx264", rate=Fraction(fps).limit_denominator(1000))
        stream.width, stream.height, stream.pix_fmt = width, height, "yuv420p"
        for image in images:
            container.mux(stream.encode(av.VideoFrame.from_ndarray(image, format="rgb24")))
        container.mux(stream.encode())
