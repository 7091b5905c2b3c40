"""A lockstep DC-2 episode through the graph, recorded by `./semgoal eval --via-ros --record`, read back with the
mcap reader and mcap-ros2-support's decoder (not the writer's code): every step present and contiguous, every
topic of the graph present, the final state the in-process episode's, and `./semgoal replay --verify` passing."""

import subprocess
from pathlib import Path

import av
import pytest
from mcap.reader import make_reader

from conftest import decoded_messages
from semgoal_bringup.experiments.episodes import make_agent
from semgoal_ros import interfaces as topics

ROOT = Path(__file__).parents[2]
TASK, SEED = "DC-2", 3_000_000


def semgoal(*args: str, timeout: float = 600) -> subprocess.CompletedProcess:
    return subprocess.run([str(ROOT / "semgoal"), *args], capture_output=True, text=True, timeout=timeout)


@pytest.mark.parametrize("layout", [(), ("--composed",)], ids=["four processes", "one process"])
def test_a_recorded_episode_reads_back_whole_and_replays_step_for_step(ros_domain, tmp_path, layout) -> None:
    """In one process too: the recorder, a listener outside, gets every message the nodes hand each other."""
    evaluated = semgoal("eval", "--tasks", TASK, "--episodes", "1", "--seed", str(SEED), "--seeds", "1", "--jobs", "1",
                        "--via-ros", "--record", str(tmp_path), "--json", *layout)
    assert evaluated.returncode == 0, evaluated.stderr[-3000:]
    record = tmp_path / f"{TASK}-{SEED}.mcap"
    decoded = decoded_messages(record)
    with record.open("rb") as stream:
        metadata = {m.name: m.metadata for m in make_reader(stream).iter_metadata()}
    assert len(metadata["provenance"]["commit"]) == 40 and "--via-ros" in metadata["provenance"]["command"], metadata
    seen = {topic for topic, _ in decoded}
    assert {topics.WORLD_STATE, topics.JOINT_STATES, topics.SEMANTIC_STATE, topics.PLAN, topics.SUBGOAL,
            topics.ARM_COMMAND, topics.MARKERS, topics.PLAN_MARKERS, topics.CLOCK} <= seen, seen

    episode = max(m.episode for t, m in decoded if t == topics.WORLD_STATE)
    steps = sorted({m.step for t, m in decoded if t == topics.WORLD_STATE and m.episode == episode})
    assert steps == list(range(steps[-1] + 1))  # every step, none missing
    commands = sorted({m.step for t, m in decoded if t == topics.ARM_COMMAND})
    assert set(range(steps[-1])) <= set(commands)

    in_process = make_agent("hierarchical", "desk_cleanup").run(TASK, SEED)
    assert in_process.success and steps[-1] >= in_process.steps
    final = [m for t, m in decoded if t == topics.SEMANTIC_STATE and m.episode == episode and m.step == in_process.steps][-1]
    true = {f"{p.name}({','.join(p.args)})" for p in final.predicates if p.value}
    assert {"in_bin(red)", "in_bin(green)"} <= true and not any(lit.startswith("holding") for lit in true)
    plans = [m for t, m in decoded if t == topics.PLAN]
    assert plans[-1].status == "succeeded"

    verified = semgoal("replay", str(record), "--verify", "--summary")
    assert verified.returncode == 0 and "verified: all" in verified.stdout, verified.stdout + verified.stderr
    assert f"{TASK} in desk_cleanup, seed {SEED}" in verified.stdout

    video = tmp_path / "episode.mp4"  # the episode as a video, from the record alone
    rendered = semgoal("replay", str(record), "--mp4", str(video))
    assert rendered.returncode == 0, rendered.stdout + rendered.stderr
    with av.open(str(video)) as container:
        stream = container.streams.video[0]
        decoded_frames = sum(1 for _ in container.decode(stream))
    assert stream.codec_context.name == "h264" and decoded_frames == int(rendered.stdout.split("(")[1].split()[0])


def test_up_and_goal_record_what_the_operator_ran(ros_domain, tmp_path) -> None:
    import signal
    import time

    session, goal_record = tmp_path / "up.mcap", tmp_path / "goal.mcap"
    up = subprocess.Popen([str(ROOT / "semgoal"), "up", "--task", TASK, "--seed", "7", "--mode", "lockstep",
                           "--record", str(session), "--log-level", "warn"], stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True)
    try:
        from semgoal_ros.client import GraphClient

        watcher = GraphClient("semgoal_test_watcher", watch=False)
        try:  # the session recorder records a topic once its reader has matched the publisher: under load it once
            # matched the sim's world states only at the episode's end, and the session held no start of it
            def recorder_hears_the_sim() -> bool:
                readers = watcher.node.get_subscriptions_info_by_topic(topics.WORLD_STATE)
                return (any(info.node_name == "recorder" for info in readers)
                        and watcher.node.count_publishers(topics.WORLD_STATE) > 0)

            assert watcher.spin_until(recorder_hears_the_sim, 60.0), "the session recorder never met the sim"
            watcher.spin_until(lambda: False, 1.0)  # a moment for the two to match, as a third process saw them
        finally:
            watcher.close()
        ran = None
        for _ in range(3):  # the first try may come before the planner is up
            ran = semgoal("goal", TASK, "--wait", "--max-steps", "600", "--record", str(goal_record), timeout=300)
            if ran.returncode == 0 or "success" in ran.stdout:
                break
            time.sleep(3)
        assert ran.returncode == 0 and "recorded" in ran.stdout, ran.stdout + ran.stderr
        refused = semgoal("plan", "remove", "99")  # an edit the planner refuses: on record with its reason
        assert refused.returncode != 0, refused.stdout
        from semgoal_msgs.msg import OperatorEvent

        hand = GraphClient("semgoal_test_hand", watch=False)  # a person's move (MoveBlock), as the console makes
        moves: list = []
        hand.node.create_subscription(OperatorEvent, topics.OPERATOR_EVENTS,
                                      lambda e: moves.append(e) if e.kind == OperatorEvent.KIND_MOVE else None,
                                      topics.EVENTS)
        try:
            assert hand.move_block("red", 1.2, 0.6, 0.425)[0]
            # the move's event is out before the graph stops (a SIGINT right after the answer could stop the session
            # recorder before the event reached it); a second more for the recorder, a reader like this one
            assert hand.spin_until(lambda: bool(moves), 10.0), "the move's operator event never came"
            hand.spin_until(lambda: False, 1.0)
        finally:
            hand.close()
    finally:
        up.send_signal(signal.SIGINT)
        output = up.communicate(timeout=30)[0]
    for record in (goal_record, session):
        summary = semgoal("replay", str(record), "--summary")
        assert summary.returncode == 0 and "outcome: succeeded" in summary.stdout, (record, summary.stdout, output[-2000:])
        assert f"operator goal '{TASK}': accepted" in summary.stdout, summary.stdout
    edit = [line for line in summary.stdout.splitlines() if line.startswith("operator edit 'remove index=99'")]
    assert edit and "refused, no plan to edit" in edit[0], summary.stdout
    assert "operator move 'red to (1.200, 0.600, 0.425)': accepted" in summary.stdout, summary.stdout


def test_a_session_recorder_started_late_still_has_the_first_operator_event(nodes, probe, tmp_path) -> None:
    """Discovery may match the session recorder to the planner after the operator's first request: the events
    the planner keeps (QoS ``EVENTS``) reach it all the same."""
    nodes.start("semgoal_planner", "planner_node", params={"scene": "desk_cleanup"})
    refused = semgoal("plan", "remove", "3", timeout=120)  # an event: a refused edit, before any recorder runs
    assert refused.returncode == 1, refused.stdout + refused.stderr
    record = tmp_path / "session.mcap"
    recorder = nodes.start("semgoal_bringup", "record_node", params={"path": str(record)})
    assert probe.poll(lambda: "recording to" in nodes.logs(), timeout=60), nodes.logs()
    # the recorder says when its reader has matched the planner's writer, which then hands it the kept events
    assert probe.poll(lambda: f"recording {topics.OPERATOR_EVENTS}\n" in nodes.logs(), timeout=60), nodes.logs()
    probe.poll(lambda: False, 1)
    assert nodes.stop(recorder) == 0, nodes.logs()
    events = [message for topic, message in decoded_messages(record) if topic == topics.OPERATOR_EVENTS]
    assert [(e.kind, e.request, e.accepted) for e in events] == [("edit", "remove index=3", False)], events
