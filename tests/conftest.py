"""Shared fixtures: a private ROS domain per test, real node processes, an in-test rclpy node."""

import contextlib
import os
import signal
import subprocess
import sys
import time
from collections.abc import Callable, Iterator
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def decoded_messages(path: Path) -> list[tuple[str, object]]:
    """(topic, message) of every message of an MCAP recording, decoded (the ``mcap`` reader, ``mcap-ros2-support``)."""
    from mcap.reader import make_reader
    from mcap_ros2.decoder import DecoderFactory

    with Path(path).open("rb") as stream:
        return [(channel.topic, message) for _, channel, _, message
                in make_reader(stream, decoder_factories=[DecoderFactory()]).iter_decoded_messages()]


def free_port() -> int:
    """A TCP port free on 127.0.0.1 now (for a server a test starts)."""
    import socket

    with socket.socket() as probe_socket:
        probe_socket.bind(("127.0.0.1", 0))
        return probe_socket.getsockname()[1]


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addoption("--pure", action="store_true",
                     help="fail a test that starts a process or a ROS context (make check: those carry `slow`)")


@pytest.fixture(autouse=True)
def _pure(request: pytest.FixtureRequest, monkeypatch: pytest.MonkeyPatch) -> None:
    """Under ``--pure`` a test that starts a process (subprocess, multiprocessing) or initialises rclpy fails
    with what to do, so the fast loop stays fast and ``slow`` stays true."""
    if not request.config.getoption("--pure"):
        return
    import multiprocessing.process

    def refuse(*_args, **_kwargs) -> None:
        raise RuntimeError("a test under --pure started a process or a ROS context: mark it @pytest.mark.slow")

    monkeypatch.setattr(subprocess.Popen, "__init__", refuse)
    monkeypatch.setattr(multiprocessing.process.BaseProcess, "start", refuse)
    if "rclpy" in sys.modules:
        monkeypatch.setattr(sys.modules["rclpy"], "init", refuse)


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """Tests under tests/graph/ start real nodes: mark them so they can be run apart (-m graph)."""
    for item in items:
        if "tests/graph/" in str(item.fspath).replace(os.sep, "/"):
            item.add_marker(pytest.mark.graph)


@pytest.fixture
def ros_domain(monkeypatch: pytest.MonkeyPatch) -> Iterator[int]:
    """A ROS_DOMAIN_ID held for this test only (:mod:`semgoal_ros.domains`: no graph on this host has it), DDS
    kept on localhost, set for child processes too."""
    from semgoal_ros.domains import lease

    current = os.environ.get("ROS_DOMAIN_ID", "")
    domain, handle = lease({int(current)} if current.isdigit() else set())
    monkeypatch.setenv("ROS_DOMAIN_ID", str(domain))
    monkeypatch.setenv("ROS_AUTOMATIC_DISCOVERY_RANGE", "LOCALHOST")
    yield domain
    handle.close()


class NodeProcesses:
    """Starts nodes as separate processes (`./semgoal run`) and stops them all at teardown."""

    def __init__(self, log_dir: Path) -> None:
        self.log_dir = log_dir
        self.processes: list[tuple[str, subprocess.Popen]] = []

    def start(self, package: str, executable: str, params: dict | None = None) -> subprocess.Popen:
        from semgoal_bringup.graph import node_command

        return self.run(executable, node_command(package, executable, params))

    def run(self, name: str, command: list[str]) -> subprocess.Popen:
        """Start ``command`` as one of the test's processes (its log named after ``name``)."""
        log = open(self.log_dir / f"{name}-{len(self.processes)}.log", "w")  # noqa: SIM115
        process = subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT, cwd=ROOT, start_new_session=True)
        self.processes.append((name, process))
        return process

    def logs(self) -> str:
        return "\n".join(f"--- {p.name}\n{p.read_text()[-3000:]}" for p in sorted(self.log_dir.glob("*.log")))

    def stop(self, process: subprocess.Popen, timeout: float = 5.0) -> int:
        """SIGINT, then after ``timeout`` SIGKILL to its whole process group: what it started (`study run`'s nodes)
        goes with it, even where it was itself killed before it could stop them."""
        if process.poll() is None:
            process.send_signal(signal.SIGINT)
            with contextlib.suppress(subprocess.TimeoutExpired):
                process.wait(timeout)
        with contextlib.suppress(ProcessLookupError, PermissionError):
            os.killpg(process.pid, signal.SIGKILL)
        process.wait()
        return process.returncode

    def stop_all(self) -> None:
        for _, process in self.processes:
            self.stop(process)


@pytest.fixture
def nodes(ros_domain: int, tmp_path: Path, request: pytest.FixtureRequest) -> Iterator[NodeProcesses]:
    """Start real node processes in this test's domain; their logs are printed when the test fails."""
    processes = NodeProcesses(tmp_path)
    yield processes
    processes.stop_all()
    report = getattr(request.node, "rep_call", None)
    if report is not None and report.failed:
        sys.stderr.write(processes.logs())


@pytest.hookimpl(wrapper=True, tryfirst=True)
def pytest_runtest_makereport(item: pytest.Item, call: pytest.CallInfo):
    report = yield
    setattr(item, f"rep_{report.when}", report)
    return report


@contextlib.contextmanager
def executor_nodes(executor, context) -> Iterator[Callable[[str], object]]:
    """A maker of rclpy nodes in ``context``, each spun by ``executor``; at the end the executor shuts down and the nodes
    go (the executor tests' fixtures)."""
    import rclpy

    made = []

    def node(name: str):
        made.append(rclpy.create_node(name, context=context))
        executor.add_node(made[-1])
        return made[-1]

    try:
        yield node
    finally:
        executor.shutdown()
        for each in made:
            each.destroy_node()


def spin_executor_until(executor, condition: Callable[[], bool], timeout: float = 10.0) -> None:
    """Spin ``executor`` until ``condition()`` holds; fail after ``timeout`` seconds."""
    end = time.monotonic() + timeout
    while not condition():
        assert time.monotonic() < end, "timed out"
        executor.spin_once(timeout_sec=0.1)


class GraphProbe:
    """An rclpy node inside the test process, in the test's domain, with helpers to wait on the graph."""

    def __init__(self, domain: int) -> None:
        import rclpy
        from rclpy.executors import SingleThreadedExecutor

        self.context = rclpy.Context()
        rclpy.init(context=self.context, domain_id=domain)
        self.node = rclpy.create_node("semgoal_test", context=self.context)
        self.executor = SingleThreadedExecutor(context=self.context)
        self.executor.add_node(self.node)

    def poll(self, condition: Callable[[], bool], timeout: float) -> bool:
        """Spin until ``condition()`` holds; False after ``timeout`` seconds."""
        deadline = time.monotonic() + timeout
        while not condition():
            if time.monotonic() > deadline:
                return False
            self.executor.spin_once(timeout_sec=0.05)
        return True

    def spin_until(self, condition: Callable[[], bool], timeout: float, what: str = "condition") -> None:
        """Spin until ``condition()`` holds; fail the test with ``what`` after ``timeout`` seconds."""
        if not self.poll(condition, timeout):
            pytest.fail(f"timed out after {timeout:.0f} s waiting for {what}")

    def send_goal(self, action, goal, feedback_callback=None):
        """The goal's handle once the server answers (sent again if no answer comes, as the product's
        clients do: :func:`semgoal_ros.interfaces.send_goal`); fails the test without one."""
        from semgoal_ros.interfaces import SEND_ATTEMPTS, send_goal

        handle = send_goal(action, goal, self.poll, feedback_callback)
        if handle is None:
            pytest.fail(f"no answer to a goal after {SEND_ATTEMPTS} tries")
        return handle

    def spin_for(self, seconds: float) -> None:
        """Process callbacks for ``seconds`` (to show that something does NOT happen)."""
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline:
            self.executor.spin_once(timeout_sec=0.05)

    def spin_future(self, future, timeout: float, what: str = "future"):
        self.spin_until(future.done, timeout, what)
        return future.result()

    def close(self) -> None:
        self.executor.shutdown()
        self.node.destroy_node()
        self.context.try_shutdown()


@pytest.fixture
def probe(ros_domain: int) -> Iterator[GraphProbe]:
    node = GraphProbe(ros_domain)
    yield node
    node.close()


def desk_with_a_fallen_block():
    """A DC-3 world whose green block was dropped past the desk's edge and has come to rest below it."""
    import numpy as np

    from semgoal_core.geometry import TABLE_TOP
    from semgoal_core.tasks import TASKS
    from semgoal_sim.world import FetchWorld

    world = FetchWorld("desk_cleanup", 3)
    world.reset(TASKS["DC-3"].initial_state(0)[0])
    world.set_block_pose("green", np.array([0.9, 0.3, TABLE_TOP + 0.1]))
    for _ in range(25):
        world.step(np.zeros(4))
    return world


BLOCKS = ("red", "green", "blue")


def semantic_state(true: set[str], step: int, fallen: tuple[str, ...] = ()):
    """A desk SemanticState with red, green and blue present and exactly the atoms in ``true`` holding, as the
    predicates node would publish it at ``step``."""
    from semgoal_core.vocabulary import LAYOUTS
    from semgoal_msgs.msg import Predicate, SemanticState

    layout = LAYOUTS["desk_cleanup"]
    msg = SemanticState(scene="desk_cleanup", step=step, objects=list(BLOCKS), fallen=list(fallen))
    for name, args in layout.atoms:
        if all(a in BLOCKS for a in args):
            msg.predicates.append(Predicate(name=name, args=list(args), value=f"{name}({','.join(args)})" in true))
    msg.vector = [p.value for p in msg.predicates]
    return msg
