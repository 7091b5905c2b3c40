"""A node process whose DDS participant hangs on the way out is ended by the kernel, not left spinning a core."""

import signal
import subprocess
import sys
import time

import pytest

pytestmark = pytest.mark.slow  # each starts a Python process

HUNG_EXIT = """
import types
from semgoal_ros import interfaces
interfaces.EXIT_GRACE_S = 1


class HungNode:
    def destroy_node(self):
        while True:  # as Fast DDS busy-waits on a listener callback that never ends
            pass


interfaces._destroy(types.SimpleNamespace(try_shutdown=lambda: None), [HungNode()])
"""

CLEAN_EXIT = """
import time
import types
from semgoal_ros import interfaces
interfaces.EXIT_GRACE_S = 1


class Node:
    def destroy_node(self):
        pass


interfaces._destroy(types.SimpleNamespace(try_shutdown=lambda: None), [Node()])
time.sleep(2)  # past the grace: the guard was disarmed once the nodes were gone
print("exited cleanly")
"""


def test_a_node_hung_in_its_destruction_is_ended_after_the_grace() -> None:
    start = time.monotonic()
    done = subprocess.run([sys.executable, "-c", HUNG_EXIT], timeout=30)
    assert done.returncode == -signal.SIGALRM and time.monotonic() - start < 15


def test_a_clean_exit_disarms_the_guard() -> None:
    done = subprocess.run([sys.executable, "-c", CLEAN_EXIT], capture_output=True, text=True, timeout=30)
    assert done.returncode == 0 and "exited cleanly" in done.stdout
