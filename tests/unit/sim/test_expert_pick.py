"""How the scripted expert approaches a block it picks: nearby states get nearby labels, so that an actor
cloning them cannot settle between two that disagree (labels 1 mm apart said rise and
descend, and actors stalled over blocks 1 to 1.5 cm off in xy)."""

import numpy as np
import pytest

from semgoal_core.expert import ALIGN_XY, CLOSE, FUNNEL_XY, GRASP_OPENING, HOVER, WorldView, expert_action
from semgoal_core.tasks import TABLE_TOP
from semgoal_core.vocabulary import BLOCK_HALF_SIZE, SubGoal

BLOCK = np.array([1.40, 0.83, TABLE_TOP + BLOCK_HALF_SIZE])
PICK = SubGoal("pick", ("red",))


def label_at(xy_offset: float, height: float) -> np.ndarray:
    """The pick label with the open grip ``height`` over the block's centre, ``xy_offset`` off it in y."""
    grip = BLOCK + np.array([0.0, xy_offset, height])
    return expert_action(PICK, WorldView({"red": BLOCK, "green": np.array([1.2, 0.6, BLOCK[2]])}, grip, GRASP_OPENING))


@pytest.mark.parametrize("height", [0.02, 0.05, 0.08])
def test_pick_labels_change_little_between_nearby_offsets(height: float) -> None:
    """Across the funnel, 1 mm more offset changes the vertical label by little. Before the funnel it
    jumped by more than 1 (descend at full speed / rise) at 8 mm."""
    offsets = np.arange(0.0, FUNNEL_XY + 1e-9, 0.001)
    vertical = np.array([label_at(offset, height)[2] for offset in offsets])
    assert np.abs(np.diff(vertical)).max() < 0.1, vertical.round(2)


def test_pick_descends_within_the_funnel_and_keeps_its_height_outside_it() -> None:
    """Aligned: down onto the block. 2 cm off at the hover height: down, while aligning. Beyond the funnel
    at the hover height: hold it and travel."""
    assert label_at(0.0, HOVER)[2] == -1.0
    inside = label_at(0.02, HOVER)
    assert inside[2] < -0.1 and inside[1] < 0.0
    outside = label_at(FUNNEL_XY + 0.01, HOVER)
    assert outside[2] == pytest.approx(0.0, abs=1e-9) and outside[1] < 0.0


def test_pick_grasps_only_once_aligned() -> None:
    """The fingers shut at the block's centre within ``ALIGN_XY`` and not 1 cm off, where the label
    aligns first."""
    assert label_at(ALIGN_XY / 2, 0.0)[3] == CLOSE
    assert label_at(0.01, 0.0)[3] != CLOSE
