"""`./semgoal up` keeps the graph alive: a node killed outright is started again while the others run on, and
the operator's next goal succeeds; SIGTERM stops every node and removes the planner's temporary journal."""

import os
import queue
import re
import signal
import subprocess
import threading
import time
from pathlib import Path

ROOT = Path(__file__).parents[2]


def test_a_killed_node_is_restarted_and_the_graph_works_on(ros_domain) -> None:
    up = subprocess.Popen([str(ROOT / "semgoal"), "up", "--task", "DC-2", "--seed", "5", "--mode", "lockstep",
                           "--log-level", "warn"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    lines: queue.Queue[str] = queue.Queue()
    threading.Thread(target=lambda: [lines.put(line) for line in up.stdout], daemon=True).start()

    def wait_for(pattern: str, timeout: float) -> re.Match:
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            try:
                line = lines.get(timeout=0.5)
            except queue.Empty:
                continue
            if match := re.search(pattern, line):
                return match
        raise AssertionError(f"up never printed {pattern!r}")

    try:
        journal = Path(wait_for(r"the planner's journal: (\S+) \(removed when the graph stops\)", 60)[1])
        pid = int(wait_for(r"started policy_node \(pid (\d+)\)", 60)[1])
        wait_for(r"running \(ROS_DOMAIN_ID", 60)
        os.kill(pid, signal.SIGKILL)
        wait_for(r"policy_node exited with -9; restarting it in 1 s", 10)
        restarted = int(wait_for(r"started policy_node \(pid (\d+)\)", 10)[1])
        assert restarted != pid
        ran = None
        for _ in range(3):  # the restarted policy may still be loading its actor
            ran = subprocess.run([str(ROOT / "semgoal"), "goal", "DC-2", "--wait", "--max-steps", "600"],
                                 capture_output=True, text=True, timeout=300)
            if ran.returncode == 0:
                break
            time.sleep(2)
        assert ran.returncode == 0 and "success" in ran.stdout, ran.stdout + ran.stderr
        assert up.poll() is None and journal.is_dir()  # the graph is still up
        up.send_signal(signal.SIGTERM)
        assert up.wait(timeout=30) == 0
        assert not journal.exists() and not Path(f"/proc/{restarted}").exists()  # no node left running
    finally:
        if up.poll() is None:
            up.send_signal(signal.SIGINT)
            up.wait(timeout=30)
