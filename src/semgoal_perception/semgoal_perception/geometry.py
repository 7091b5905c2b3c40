"""Pixels to points: pinhole back-projection of a depth image into the world frame (numpy only)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class PinholeCamera:
    """Intrinsics (pixels) and the optical frame's pose in the world (4x4: x right, y down, z ahead)."""

    fx: float
    fy: float
    cx: float
    cy: float
    world_from_camera: np.ndarray

    def world_points(self, depth: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(H, W, 3) world points of the pixels and (H, W) bool: the pixel has a depth return (> 0, finite)."""
        height, width = depth.shape
        v, u = np.mgrid[0:height, 0:width].astype(np.float32)
        z = np.nan_to_num(depth.astype(np.float32), nan=0.0, posinf=0.0, neginf=0.0)
        valid = z > 0
        camera = np.stack([(u - self.cx) * z / self.fx, (v - self.cy) * z / self.fy, z], axis=-1)
        rotation, origin = self.world_from_camera[:3, :3], self.world_from_camera[:3, 3]
        world = camera @ rotation.T.astype(np.float32) + origin.astype(np.float32)
        world[~valid] = 0.0
        return world, valid

    def project(self, points: np.ndarray) -> np.ndarray:
        """(N, 2) pixel coordinates (u, v) of world points (N, 3) in front of the camera."""
        camera = (np.asarray(points) - self.world_from_camera[:3, 3]) @ self.world_from_camera[:3, :3]
        z = camera[:, 2:3]
        return np.column_stack([self.fx * camera[:, 0] / z[:, 0] + self.cx, self.fy * camera[:, 1] / z[:, 0] + self.cy])
