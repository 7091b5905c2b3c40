"""`./semgoal replay FILE [--summary] [--verify] [--gif OUT] [--mp4 OUT]`: an episode recorded as MCAP (``make demo``,
``eval --via-ros --record``), read back with the ``mcap`` reader and ``mcap-ros2-support``'s decoder.

``--summary`` prints the episode: task and seed, each plan (a re-plan starts a new one), the sub-goal
timeline and the outcome; where the camera saw the blocks (``--perception camera``), each span of steps in which a
block's estimate was more than :data:`~semgoal_bringup.experiments.perception_replay.FAR` off the simulator's pose,
beside the sub-goals: where to look first when a run from the camera fails. ``--verify`` runs the recorded start and
the recorded arm commands through the simulator again and checks that every recorded world state is reproduced, step
for step (lockstep episodes: one command per step). ``--gif`` / ``--mp4`` render the episode from the recorded states.
"""

from __future__ import annotations

import argparse
import sys
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from mcap.exceptions import McapError

from semgoal_core.layout import CONTROL_DT
from semgoal_ros.interfaces import BLOCK_ESTIMATES

POSITION_TOLERANCE = 1e-9
"""Metres: the simulator is deterministic, so a replayed state matches the recorded one to float precision."""


@dataclass
class Episode:
    """The last episode of a recording: its world states and joint states by step, commands, plans, sub-goals."""

    worlds: dict[int, object] = field(default_factory=dict)
    joints: dict[tuple[int, int], object] = field(default_factory=dict)
    commands: dict[int, object] = field(default_factory=dict)
    plans: list = field(default_factory=list)
    subgoals: dict[tuple[int, int], object] = field(default_factory=dict)
    """The planner's decisions by (episode, step)."""
    operator: list = field(default_factory=list)
    """Every goal and plan edit the planner answered during the recording, with its answer, in order."""
    estimates: dict[int, object] = field(default_factory=dict)
    """The camera's block estimates by step (none when the graph saw by the simulator's poses)."""
    topics: dict[str, int] = field(default_factory=dict)

    @property
    def first(self):
        return self.worlds[min(self.worlds)]


def read(path: Path) -> Episode:
    """Decode every message of ``path``; keep what belongs to its last episode."""
    from mcap.reader import make_reader
    from mcap_ros2.decoder import DecoderFactory

    with path.open("rb") as stream:
        messages = [(channel.topic, message.log_time, decoded) for _, channel, message, decoded
                    in make_reader(stream, decoder_factories=[DecoderFactory()]).iter_decoded_messages()]
    worlds = [(t, m) for topic, t, m in messages if topic.endswith("/world_state")]
    if not worlds:
        raise ValueError(f"{path} holds no world state")
    last = max(m.episode for _, m in worlds)
    since = min(t for t, m in worlds if m.episode == last)  # commands and plans carry no episode: keep those sent
    # after its start (the episode before's plan, latched, reaches the recorder first)
    episode = Episode()
    for topic, log_time, msg in messages:
        episode.topics[topic] = episode.topics.get(topic, 0) + 1
        if topic.endswith("/world_state") and msg.episode == last:
            episode.worlds.setdefault(int(msg.step), msg)  # a heartbeat repeats a step
        elif topic == "/joint_states":
            episode.joints[(msg.header.stamp.sec, msg.header.stamp.nanosec)] = dict(zip(msg.name, msg.position, strict=True))
        elif topic.endswith("/arm_command") and log_time >= since:
            episode.commands.setdefault(int(msg.step), msg)
        elif topic.endswith("/plan") and log_time >= since:
            episode.plans.append(msg)
        elif topic.endswith("/subgoal") and msg.episode == last:
            episode.subgoals[(msg.episode, int(msg.step))] = msg
        elif topic.endswith("/operator_events"):
            episode.operator.append(msg)
        elif topic == BLOCK_ESTIMATES and msg.episode == last:
            episode.estimates.setdefault(int(msg.step), msg)
    return episode


@dataclass(frozen=True)
class OffSpan:
    """Steps ``first`` to ``last`` over which the camera's estimate of ``block`` was off the simulator's pose by more
    than FAR, at most ``worst`` (m); ``unseen``: it was not in view at the worst of them (occluded, held, lost)."""

    block: str
    first: int
    last: int
    worst: float
    unseen: bool


def off_spans(episode: Episode) -> list[OffSpan]:
    """Every span of steps in which a block's estimate was far off where the simulator had it, in order of start.
    A block not seen yet (no estimate) is not counted; one that fell off the table is, until its estimate follows."""
    from semgoal_bringup.experiments.perception_replay import FAR
    from semgoal_perception.tracker import TrackStatus
    from semgoal_ros.messages import block_centres, estimated_blocks

    spans, open_spans = [], {}
    for step in sorted(set(episode.estimates) & set(episode.worlds)):
        truth = block_centres(episode.worlds[step])
        for name, centre, status in estimated_blocks(episode.estimates[step]):
            error = float(np.linalg.norm(centre - truth[name])) if np.isfinite(centre).all() else 0.0
            span = open_spans.get(name)
            if error <= FAR:
                if span is not None:
                    spans.append(OffSpan(name, *open_spans.pop(name)))
            elif span is None:
                open_spans[name] = [step, step, error, status != TrackStatus.VISIBLE]
            else:
                span[1] = step
                if error > span[2]:
                    span[2:] = error, status != TrackStatus.VISIBLE
    spans += [OffSpan(block, *span) for block, span in open_spans.items()]
    return sorted(spans, key=lambda span: (span.first, span.block))


def _camera_lines(episode: Episode) -> list[str]:
    from semgoal_bringup.experiments.perception_replay import FAR

    if not episode.estimates:
        return []
    spans = off_spans(episode)
    lines = [f"camera: {len(episode.estimates)} estimates, "
             + (f"{len(spans)} span(s) of a block more than {FAR * 100:.0f} cm off the sim's pose" if spans
                else f"every block within {FAR * 100:.0f} cm of the sim's pose")]
    lines += [f"  steps {span.first:4d}-{span.last:4d}: {span.block} off by up to {span.worst * 100:.1f} cm"
              f"{' (unseen)' if span.unseen else ''}" for span in spans]
    return lines


def episode_frames(episode: Episode) -> list:
    """The GIF frames of a recorded episode, every second step, captioned with the sub-goal followed."""
    from semgoal_bringup.tools.episode_video import frames_from

    return frames_from([episode.worlds[s] for s in sorted(episode.worlds)], episode.joints, episode.subgoals)


def summary(episode: Episode) -> str:
    """The episode as text: start, plans, the sub-goal timeline, outcome."""
    first, last = episode.first, episode.worlds[max(episode.worlds)]
    lines = [f"{first.task} in {first.scene}, seed {first.seed}, episode {first.episode}: "
             f"{len(episode.worlds)} world states, steps {min(episode.worlds)}-{max(episode.worlds)}"]
    for event in episode.operator:
        lines.append(f"operator {event.kind} {event.request!r}: {'accepted' if event.accepted else 'refused'}, "
                     f"{event.answer.splitlines()[0] if event.answer else ''} (plan revision {event.revision})")
    shown = set()
    for plan in episode.plans:
        key = (plan.goal, tuple(s.action for s in plan.steps), plan.replans)
        if plan.steps and key not in shown:
            shown.add(key)
            what = "plan" if not plan.replans else f"re-plan {plan.replans}"
            lines.append(f"{what} for {plan.goal}: " + ", ".join(f"{s.index}. {s.action} ({s.assignee})" for s in plan.steps))
    current = None
    for decision in episode.subgoals.values():
        label = decision.action or f"({decision.status})"
        if label != current:
            lines.append(f"  step {decision.step:4d}: {label}")
            current = label
    final = episode.plans[-1] if episode.plans else None
    lines.append(f"outcome: {final.status if final else 'no plan'} at step {last.step} "
                 f"({last.step * CONTROL_DT:.1f} s sim time), {final.replans if final else 0} re-plans")
    lines += _camera_lines(episode)
    lines.append("topics: " + ", ".join(f"{t} {n}" for t, n in sorted(episode.topics.items())))
    return "\n".join(lines)


def verify(episode: Episode) -> tuple[bool, str]:
    """Re-run the recorded start and commands in the simulator; whether every recorded state comes back."""
    from semgoal_ros.messages import block_poses
    from semgoal_sim.sim_core import SimCore

    first = episode.first
    core = SimCore(first.scene, first.task, int(first.seed))
    steps = sorted(episode.worlds)
    for step in steps[1:]:
        command = episode.commands.get(step - 1)
        if command is None:
            return False, f"no recorded command for step {step - 1}: not a lockstep recording"
        values = [command.displacement.x, command.displacement.y, command.displacement.z, command.gripper]
        core.step(values)
        recorded = episode.worlds[step]
        snapshot = core.snapshot()
        expected = block_poses(recorded)[:, :3]
        error = float(np.abs(snapshot.block_positions - expected).max())
        grip = np.array([recorded.gripper_position.x, recorded.gripper_position.y, recorded.gripper_position.z])
        error = max(error, float(np.abs(snapshot.grip_position - grip).max()))
        if snapshot.step != step or error > POSITION_TOLERANCE:
            return False, f"step {step}: the replayed world differs from the recorded one by {error:.3g} m"
    return True, f"all {len(steps)} recorded world states reproduced (steps {steps[0]}-{steps[-1]})"


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="semgoal replay", description=__doc__.split("\n\n")[0])
    parser.add_argument("file", type=Path)
    parser.add_argument("--summary", action="store_true", help="print the plans, the sub-goal timeline and the outcome")
    parser.add_argument("--verify", action="store_true", help="re-run the recorded commands and compare the states")
    parser.add_argument("--gif", type=Path, help="render the episode from the recorded states as an animated GIF")
    parser.add_argument("--mp4", type=Path, help="render the episode from the recorded states as MP4 (H.264)")
    args = parser.parse_args(argv)
    if not args.file.is_file():
        parser.error(f"no such file: {args.file}")
    try:
        episode = read(args.file)
    except (ValueError, McapError) as error:  # not an MCAP file, or not one of ours
        print(f"semgoal replay: {args.file}: {error}", file=sys.stderr)
        return 2
    if args.summary or not (args.verify or args.gif or args.mp4):
        print(summary(episode))
    for video in (args.gif, args.mp4.with_suffix(".mp4") if args.mp4 else None):
        if video:
            from semgoal_bringup.tools.episode_video import write_video
            from semgoal_core.tasks import get_task

            frames = episode_frames(episode)
            task = get_task(episode.first.task)
            write_video(task.scene, task.n_blocks, frames, video)
            print(f"episode video: {video} ({len(frames)} frames)")
    if args.verify:
        ok, message = verify(episode)
        print(("verified: " if ok else "NOT reproduced: ") + message)
        return 0 if ok else 1
    return 0
