"""Each node killed outright in the middle of a task under `./semgoal up`: the operator's `goal --wait`
ends in success (the node is back in time and the task goes on) or in a failure that says why, within 5 s of
the kill; `up` starts the node again and the next goal succeeds."""

import os
import queue
import re
import signal
import subprocess
import threading
import time
from pathlib import Path

import pytest

from semgoal_ros.client import GraphClient

ROOT = Path(__file__).parents[2]
TASK = "DC-2"
ANSWER_S = 5.0
VICTIMS = ("policy_node", "predicate_node", "sim_node", "planner_node")


class Lines:
    """A process's output, line by line as it comes, with the time each line came."""

    def __init__(self, process: subprocess.Popen) -> None:
        self.queue: queue.Queue[tuple[float, str]] = queue.Queue()
        self.seen: list[tuple[float, str]] = []
        threading.Thread(target=lambda: [self.queue.put((time.monotonic(), line)) for line in process.stdout],
                         daemon=True).start()

    def wait_for(self, pattern: str, timeout: float) -> re.Match:
        for _, line in self.seen:
            if match := re.search(pattern, line):
                return match
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            try:
                stamp, line = self.queue.get(timeout=0.2)
            except queue.Empty:
                continue
            self.seen.append((stamp, line))
            if match := re.search(pattern, line):
                return match
        raise AssertionError(f"never printed {pattern!r}; printed:\n{''.join(line for _, line in self.seen)[-3000:]}")

    def last_pid(self, executable: str) -> int:
        self.drain()
        return int([m for _, line in self.seen if (m := re.search(rf"started {executable} \(pid (\d+)\)", line))][-1][1])

    def drain(self) -> None:
        while not self.queue.empty():
            self.seen.append(self.queue.get())


def semgoal(*args: str) -> subprocess.Popen:
    return subprocess.Popen([str(ROOT / "semgoal"), *args], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)


@pytest.mark.timeout(900)
def test_a_node_killed_mid_task_ends_the_goal_in_success_or_a_reason_within_5_s(ros_domain) -> None:
    up = semgoal("up", "--task", TASK, "--seed", "5", "--mode", "lockstep", "--log-level", "warn")
    up_lines = Lines(up)
    outcomes = {}
    try:
        up_lines.wait_for(r"running \(ROS_DOMAIN_ID", 90)
        for round_, victim in enumerate(VICTIMS):
            client = GraphClient("semgoal_test_reset", watch=False)  # a fresh start, as `ros2 service call` makes
            try:
                reset = client.reset(TASK, 10 + round_)
            finally:
                client.close()
            assert reset[0], reset[1]
            goal = semgoal("goal", TASK, "--wait", "--max-steps", "900")
            goal_lines = Lines(goal)
            goal_lines.wait_for(r">\s+1\. ", 120)  # the first step done: mid-task
            pid = up_lines.last_pid(victim)
            os.kill(pid, signal.SIGKILL)
            killed = time.monotonic()
            ended = goal_lines.wait_for(r"^(success|failure): .*", 300)
            answered = [stamp for stamp, line in goal_lines.seen if line.startswith(ended[0])][-1] - killed
            outcomes[victim] = (ended[1], round(answered, 1), ended[0].strip())
            assert ended[1] == "success" or answered <= ANSWER_S, (victim, outcomes[victim])
            assert goal.wait(timeout=30) == (0 if ended[1] == "success" else 1)
            up_lines.wait_for(rf"started {victim} \(pid (?!{pid}\))\d+\)", 30)  # up started it again
        print(f"\n{outcomes}")
        ran = None
        for _ in range(3):  # the last node restarted may still be starting
            ran = subprocess.run([str(ROOT / "semgoal"), "goal", TASK, "--wait", "--max-steps", "900"],
                                 capture_output=True, text=True, timeout=300)
            if ran.returncode == 0:
                break
            time.sleep(2)
        assert ran.returncode == 0, ran.stdout + ran.stderr
        assert up.poll() is None
    finally:
        up.send_signal(signal.SIGINT)
        up.wait(timeout=30)
