"""`./semgoal eval perception --recordings FILE...`: the perceiver (the voter and the tracker as the code has them now)
run again over episodes recorded through the graph (``eval --via-ros --record DIR``, ``demo``, ``up --record``),
beside the simulator's poses recorded in the same world states.

Each recorded RGB-D frame goes through :class:`~semgoal_perception.perceiver.Perceiver` with the arm's state of its
world state, as the perception node runs it, and every tracked block is compared with where the simulator had it:
how many block-frames are more than :data:`FAR` off, and how many of the scene's literals the camera reads otherwise
than the simulator (its semantic vector against the one of the recorded poses). Per block colour and place (on the
table, in the bin), the voter's own share: of the frames in which the block shows at least :data:`SHOWN_PIXELS`
pixels within :data:`SHOWN_RADIUS` of its true centre, those on which most of them are labelled its colour.

A recording keeps the camera's frames at 5 Hz of sim time (``semgoal_ros.recording.CAMERA_RECORD_PERIOD_S``), a fifth
of what the node saw live, so the tracker bridges five control steps a frame here: the figures are a change's offline
measure on fixed frames (the same frames before and after), not the live run's. Blocks that fell off the table are
left out (the camera does not look there).
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field, fields
from pathlib import Path

import numpy as np

from semgoal_ros import interfaces as topics

FAR = 0.03
"""A tracked block this far (m) from the simulator's pose counts as off."""
SHOWN_RADIUS = 0.035
"""Pixels whose 3-D point lies this near (m) a block's true centre show that block (its top face and sides)."""
SHOWN_PIXELS = 8
"""A block showing fewer pixels than this in a frame is not counted in the voter's share (hidden, or a sliver)."""
FRAME_PARTS = {topics.WORLD_STATE: "world", topics.RGBD_COLOUR: "colour", topics.RGBD_DEPTH: "depth",
               topics.RGBD_INFO: "info"}
"""The topics whose messages of one stamp make one frame: the sim's world state and the camera's colour, depth, info."""


@dataclass
class TrackingScore:
    """What the camera got wrong over a set of frames (module doc)."""

    frames: int = 0
    block_frames: int = 0
    far: int = 0
    literals: int = 0
    wrong: int = 0
    labelled: dict[str, list[int]] = field(default_factory=dict)
    """``"colour place"`` -> [frames it showed in, frames most of its pixels were labelled its colour]."""

    def __iadd__(self, other: TrackingScore) -> TrackingScore:
        for name in (f.name for f in fields(self) if f.name != "labelled"):
            setattr(self, name, getattr(self, name) + getattr(other, name))
        for key, (shown, right) in other.labelled.items():
            counts = self.labelled.setdefault(key, [0, 0])
            counts[0], counts[1] = counts[0] + shown, counts[1] + right
        return self

    def as_dict(self) -> dict:
        return {**{f.name: getattr(self, f.name) for f in fields(self) if f.name != "labelled"},
                "far_share": round(self.far / self.block_frames, 5) if self.block_frames else None,
                "wrong_share": round(self.wrong / self.literals, 5) if self.literals else None,
                "labelled": {key: {"shown": shown, "labelled_right": right, "share": round(right / shown, 3)}
                             for key, (shown, right) in sorted(self.labelled.items())}}


def summed(scores: Iterable[TrackingScore]) -> TrackingScore:
    """All of ``scores`` as one."""
    total = TrackingScore()
    for score in scores:
        total += score
    return total


class _KeepingLabels:
    """The estimator as the perceiver calls it, keeping the last frame's pixel labels: the voter's share is read from
    the same network run that gave the detections."""

    def __init__(self, estimator) -> None:
        self.estimator, self.pixels = estimator, None

    def detect(self, rgb: np.ndarray, depth: np.ndarray, camera) -> list:
        self.pixels = self.estimator.label(rgb, depth, camera)
        return self.pixels.detections()


@dataclass(frozen=True)
class RecordedFrame:
    world: object
    """The sim's ``WorldState`` of the frame's instant: the arm's state and the true block poses."""
    rgb: np.ndarray
    depth: np.ndarray
    camera: object
    """:class:`~semgoal_perception.geometry.PinholeCamera` of the frame."""


def recorded_frames(path: Path) -> Iterator[RecordedFrame]:
    """Every instant of ``path`` whose world state, colour, depth and camera info were all recorded, in order."""
    from mcap.reader import make_reader
    from mcap_ros2.decoder import DecoderFactory

    from semgoal_perception.geometry import PinholeCamera
    from semgoal_perception.perception_node import CAMERA_FRAME, image_array, pose_matrix, stamp_key

    pending: dict[int, dict] = {}
    pose = None
    with path.open("rb") as stream:
        reader = make_reader(stream, decoder_factories=[DecoderFactory()])
        for _, channel, _, msg in reader.iter_decoded_messages(topics=[*FRAME_PARTS, topics.TF_STATIC]):
            if channel.topic == topics.TF_STATIC:
                pose = next((pose_matrix(t.transform) for t in msg.transforms if t.child_frame_id == CAMERA_FRAME), pose)
                continue
            parts = pending.setdefault(stamp_key(msg.header), {})
            parts[FRAME_PARTS[channel.topic]] = msg
            if len(parts) < len(FRAME_PARTS) or pose is None:
                continue
            del pending[stamp_key(msg.header)]
            info = parts["info"]
            yield RecordedFrame(parts["world"], image_array(parts["colour"], "rgb8", 3, np.uint8),
                                image_array(parts["depth"], "32FC1", 1, np.float32),
                                PinholeCamera(info.k[0], info.k[4], info.k[2], info.k[5], pose))


def score_recording(path: Path, estimator) -> TrackingScore:
    """The perceiver's :class:`TrackingScore` over the frames of one recording (a new episode starts its tracks
    afresh, as in the node)."""
    from semgoal_core.geometry import TABLE_TOP
    from semgoal_core.tasks import get_task
    from semgoal_core.vocabulary import fallen_blocks
    from semgoal_perception.perceiver import Perceiver
    from semgoal_perception.perception_node import PerceptionNode
    from semgoal_ros.messages import block_centres, hands, semantic_vector

    keeping = _KeepingLabels(estimator)
    perceiver, score = Perceiver(keeping), TrackingScore()
    for frame in recorded_frames(path):
        world = frame.world
        seen = perceiver.perceive(frame.rgb, frame.depth, frame.camera, PerceptionNode.arm_state(world), world.scene,
                                  get_task(world.task).blocks, (world.episode, world.seed), world.step,
                                  hands(world)[1:])
        truth = block_centres(world)
        names = list(truth)
        on_the_table = set(names) - set(fallen_blocks(names, np.array([truth[n] for n in names]), TABLE_TOP))
        for name, track in zip(seen.blocks, seen.tracks, strict=True):
            if name in on_the_table:
                score.block_frames += 1
                score.far += bool(np.linalg.norm(track.position - truth[name]) > FAR)  # never seen: NaN, not off
        _count_labelled(score, keeping.pixels, frame.world.scene, {name: truth[name] for name in on_the_table})
        true_vector, seen_vector = semantic_vector(world) > 0.5, np.asarray(seen.vector) > 0.5
        score.frames += 1
        score.literals += true_vector.size
        score.wrong += int((true_vector != seen_vector).sum())
    return score


def _count_labelled(score: TrackingScore, pixels, scene: str, centres: dict[str, np.ndarray]) -> None:
    """Fold one frame's voter labels (:class:`~semgoal_perception.estimator.LabelledPixels`) into ``score.labelled``
    (module doc): each block at ``centres`` (its true one)."""
    from semgoal_core.vocabulary import BLOCK_COLOURS, SCENES

    bin_ = SCENES[scene].bin
    for name, centre in centres.items():
        shown = pixels.valid & (np.linalg.norm(pixels.points - centre, axis=-1) < SHOWN_RADIUS)
        if shown.sum() < SHOWN_PIXELS:
            continue
        place = "bin" if bin_ is not None and bin_.inside(centre[:2]) else "table"
        counts = score.labelled.setdefault(f"{name} {place}", [0, 0])
        counts[0] += 1
        counts[1] += bool((pixels.labels[shown] == list(BLOCK_COLOURS).index(name) + 1).mean() > 0.5)


def replay_table(scores: dict[str, TrackingScore]) -> str:
    """One row per recording and one for all of them."""
    total = summed(scores.values())
    width = max(len("recording"), *map(len, scores))
    lines = [f"{'recording':{width}s} {'frames':>6s} {'block-frames':>12s} {'> 3 cm off':>14s} {'literals':>9s} "
             f"{'read wrong':>14s}"]
    for name, score in [*scores.items(), ("all", total)]:
        row = score.as_dict()
        lines.append(f"{name:{width}s} {score.frames:6d} {score.block_frames:12d} {score.far:6d} "
                     f"({100 * (row['far_share'] or 0):5.2f} %) {score.literals:9d} {score.wrong:6d} "
                     f"({100 * (row['wrong_share'] or 0):5.2f} %)")
    lines.append("the voter's labels, all recordings: of the frames a block showed in, those mostly labelled its colour")
    lines += [f"  {key:16s} {counts['labelled_right']:6d} of {counts['shown']:6d} ({100 * counts['share']:5.1f} %)"
              for key, counts in total.as_dict()["labelled"].items()]
    return "\n".join(lines)
