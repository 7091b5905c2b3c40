"""The block voter's training frames with a second Fetch in view: both arms at work on the desk, each frame labelled
with the blocks' true centres, and spread through the one-arm frames so that training's held-out frames have both."""

import numpy as np

from semgoal_bringup.experiments.perception_training import TWO_ARM_TASKS, interleaved, two_arm_frames
from semgoal_core.tasks import TABLETOP_TASKS, TASKS
from semgoal_core.vocabulary import BLOCK_COLOURS, BLOCK_HALF_SIZE
from semgoal_perception.geometry import PinholeCamera
from semgoal_sim.perception_data import LabelledFrames, labelled_frames


def frames_of(count: int, task: int) -> LabelledFrames:
    """``count`` blank frames, each's grip holding its index (to follow it through a reordering)."""
    rows = {name: np.zeros((count, 2)) for name in LabelledFrames.__dataclass_fields__}
    rows["grip"] = np.arange(count, dtype=float)[:, None].repeat(4, axis=1)
    rows["task"] = np.full(count, task)
    return LabelledFrames(**rows)


def test_the_second_kind_is_spread_through_the_first_in_order():
    merged = interleaved(frames_of(10, 0), frames_of(2, 1))
    assert list(merged.task) == [0, 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0]
    assert list(merged.grip[merged.task == 0, 0]) == list(range(10))
    assert list(merged.grip[merged.task == 1, 0]) == [0, 1]


def test_tabletop_frames_come_from_its_tasks_with_every_block_labelled():
    frames = labelled_frames(12, 8_700_000, (80, 60), tasks=tuple(TABLETOP_TASKS))
    assert [task.name for task in frames.tasks()] == ["Tower-3"] * 6 + ["Tower-4"] * 6
    colours = list(BLOCK_COLOURS)
    for labels, centres, task in zip(frames.labels, frames.centres, frames.tasks(), strict=True):
        present = {c for c in range(len(colours)) if np.isfinite(centres[c]).all()}
        assert present == {colours.index(block) for block in task.blocks}
        assert set(np.unique(labels)) - {0} <= {c + 1 for c in present}
    first = frames.where(frames.task == frames.task[0])
    assert len(first.rgb) == 6 and {task.name for task in first.tasks()} == {"Tower-3"}


def test_two_arm_frames_show_both_robots_at_the_desk_with_the_blocks_labelled():
    frames = two_arm_frames(8, 8_500_000, (80, 60), strength=1.0)
    assert frames.rgb.shape == (8, 60, 80, 3) and frames.depth.shape == (8, 60, 80)
    assert {list(TASKS)[t] for t in frames.task} <= set(TWO_ARM_TASKS) and len(set(frames.task)) == 2
    colours = list(BLOCK_COLOURS)
    for labels, centres, task in zip(frames.labels, frames.centres, frames.task, strict=True):
        present = [c for c in range(len(colours)) if np.isfinite(centres[c]).all()]
        assert len(present) == int(list(TASKS)[task][-1])  # DC-N: N blocks, each with its true centre
        assert set(np.unique(labels)) - {0} <= {c + 1 for c in present}


def test_repainted_frames_label_each_block_by_its_paint_with_the_centre_of_the_block_that_wears_it():
    frames = labelled_frames(12, 8_700_000, (80, 60), tasks=("Tower-3",), repaint=True)
    colours = list(BLOCK_COLOURS)
    worn = set()
    for i in range(len(frames.rgb)):
        present = {c for c in range(len(colours)) if np.isfinite(frames.centres[i, c]).all()}
        assert len(present) == 3
        worn |= present
        fx, fy, cx, cy = frames.camera[i]
        points, valid = PinholeCamera(fx, fy, cx, cy, frames.world_from_camera[i]).world_points(frames.depth[i])
        for c in present:
            mask = (frames.labels[i] == c + 1) & valid
            if mask.sum() > 10:
                assert np.linalg.norm(np.median(points[mask], axis=0) - frames.centres[i, c]) < 2 * BLOCK_HALF_SIZE
    assert worn != {0, 1, 2}  # colours beyond the task's own red, green and blue
