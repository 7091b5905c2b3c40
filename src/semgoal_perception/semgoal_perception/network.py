"""The block voter: a small fully convolutional network that labels every pixel with a block colour (or
none) and, for a block's pixels, the offset from the pixel's 3-D point to the block's centre. Each block's
centre is then the median of its pixels' votes (:mod:`semgoal_perception.estimator`): a block seen only in
part (under the arm, in the hand, below another block) still gets its centre, not its visible face's.

Inputs per pixel: colour, and the pixel's world point relative to the table (from depth and the camera's
pose), so one network serves a camera moved within the training range.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np
import torch
from torch import nn
from torch.nn import functional

from semgoal_core.vocabulary import BLOCK_COLOURS

TABLE_CENTRE = np.array([1.30, 0.75, 0.40], dtype=np.float32)
"""Where world points are taken from (m): the table top's centre."""
POINT_SCALE = 10.0
"""World points enter the network in decimetres: table-top coordinates of order one."""
OFFSET_SCALE = 0.025
"""Offsets leave the network in half block edges."""
INPUT_CHANNELS = 7  # colour (3), world point (3), depth valid (1)


@dataclass(frozen=True)
class VoterConfig:
    """The architecture (saved beside the weights)."""

    classes: int = 1 + len(BLOCK_COLOURS)
    """No block, then the first ``classes - 1`` block colours in ``BLOCK_COLOURS`` order (the paper's scenes use the
    first four)."""
    width: int = 16
    """Channels at full resolution; half resolution has 2x, quarter 3x."""


def _conv(c_in: int, c_out: int, stride: int = 1, dilation: int = 1) -> nn.Sequential:
    return nn.Sequential(nn.Conv2d(c_in, c_out, 3, stride=stride, padding=dilation, dilation=dilation),
                         nn.BatchNorm2d(c_out), nn.ReLU(inplace=True))


class BlockVoter(nn.Module):
    """A two-level encoder-decoder (U-Net shape): full, half and quarter resolution; outputs
    ``classes`` logits and 3 offset channels per pixel, at the input's resolution."""

    def __init__(self, config: VoterConfig | None = None) -> None:
        super().__init__()
        self.config = config = config or VoterConfig()
        w = config.width
        self.enc_full = nn.Sequential(_conv(INPUT_CHANNELS, w), _conv(w, w))
        self.enc_half = nn.Sequential(_conv(w, 2 * w, stride=2), _conv(2 * w, 2 * w, dilation=2))
        self.enc_quarter = nn.Sequential(_conv(2 * w, 3 * w, stride=2), _conv(3 * w, 3 * w, dilation=2))
        self.up_half = _conv(5 * w, 2 * w)
        self.up_full = nn.Sequential(nn.Conv2d(3 * w, w, 1), nn.BatchNorm2d(w), nn.ReLU(inplace=True))
        self.head = nn.Conv2d(w, config.classes + 3, 1)

    def forward(self, x: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        full = self.enc_full(x)
        half = self.enc_half(full)
        quarter = self.enc_quarter(half)
        up = functional.interpolate(quarter, size=half.shape[-2:], mode="bilinear", align_corners=False)
        half = self.up_half(torch.cat([up, half], 1))
        up = functional.interpolate(half, size=full.shape[-2:], mode="bilinear", align_corners=False)
        out = self.head(self.up_full(torch.cat([up, full], 1)))
        return out[:, : self.config.classes], out[:, self.config.classes:]

    def describe(self) -> dict:
        return asdict(self.config)


def network_input(rgb: np.ndarray, points: np.ndarray, valid: np.ndarray) -> np.ndarray:
    """(7, H, W) float32 from one frame: colour in [-0.5, 0.5], world point about the table (dm), valid."""
    colour = rgb.astype(np.float32).transpose(2, 0, 1) / 255.0 - 0.5
    point = ((points - TABLE_CENTRE) * POINT_SCALE).transpose(2, 0, 1) * valid[None]
    return np.concatenate([colour, point, valid[None].astype(np.float32)]).astype(np.float32)
