"""The camera's frame with the perception's estimates drawn on it (the console's view from the camera): a
cross at each estimated centre, in the block's colour, named, with its status when the camera does not see it."""

from __future__ import annotations

import numpy as np
from PIL import Image, ImageDraw

from semgoal_perception.geometry import PinholeCamera
from semgoal_perception.tracker import TrackStatus

SCALE = 3
"""The 160x120 frame is shown at three times its size (nearest neighbour: the pixels the voter saw)."""
COLOURS = {"red": (230, 40, 40), "green": (40, 190, 60), "blue": (50, 90, 240), "yellow": (240, 200, 20)}


def draw_estimates(rgb: np.ndarray, camera: PinholeCamera, blocks: list[tuple[str, np.ndarray, int]],
                   scale: int = SCALE) -> Image.Image:
    """``blocks``: (name, estimated centre in the world, ``TrackStatus`` value) each."""
    image = Image.fromarray(rgb).resize((rgb.shape[1] * scale, rgb.shape[0] * scale), Image.Resampling.NEAREST)
    pen = ImageDraw.Draw(image)
    for name, centre, status in blocks:
        if not np.isfinite(centre).all():
            continue
        u, v = (camera.project(centre[None])[0] + 0.5) * scale - 0.5
        colour = COLOURS.get(name, (255, 255, 255))
        size = 7
        for dx, dy in ((size, size), (size, -size)):
            pen.line([(u - dx, v - dy), (u + dx, v + dy)], fill=(0, 0, 0), width=5)
            pen.line([(u - dx, v - dy), (u + dx, v + dy)], fill=colour, width=3)
        label = name if status == TrackStatus.VISIBLE else f"{name} ({TrackStatus(status).name.lower().replace('_', ' ')})"
        pen.text((u + size + 3, v - size - 3), label, fill=(0, 0, 0), stroke_width=2, stroke_fill=(255, 255, 255))
    return image
