"""A plain `colcon build` (no --symlink-install) of a copy of src/ into a temporary install space serves the
whole graph: the copy is deleted, the nodes start from that install alone (no src/ and no dev workspace on
any path), find their parameters, launch file and actors through the ament index, and solve DC-3."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import NodeProcesses
from semgoal_core.tasks import TASK_STEP_BUDGET

ROOT = Path(__file__).parents[2]
VENV = Path(os.environ["VIRTUAL_ENV"])
TASK, SEED = "DC-3", 6
pytestmark = pytest.mark.timeout(1200)
"""A whole plain build (the messages' C and C++ type support included) takes minutes on two busy cores: the
suite's 300 s per test was not enough beside two training runs."""
PATH_VARIABLES = ("PATH", "PYTHONPATH", "AMENT_PREFIX_PATH", "CMAKE_PREFIX_PATH", "COLCON_PREFIX_PATH", "LD_LIBRARY_PATH")


def _without_checkout(env: dict[str, str]) -> dict[str, str]:
    """``env`` with every path entry into the checkout's src/ and dev workspace removed (the venv stays)."""
    dev = (str(ROOT / "src"), str(ROOT / "ros_ws"))
    clean = dict(env)
    for name in PATH_VARIABLES:
        entries = [e for e in env.get(name, "").split(os.pathsep) if e and not e.startswith(dev)]
        clean[name] = os.pathsep.join(entries)
    return clean


def _sourced(install: Path, env: dict[str, str]) -> dict[str, str]:
    out = subprocess.run(["bash", "-c", f"source {install}/local_setup.bash && env -0"], env=env,
                         capture_output=True, check=True).stdout
    return dict(item.split("=", 1) for item in out.decode().split("\0") if "=" in item)


@pytest.fixture(scope="module")
def plain_install(tmp_path_factory) -> tuple[Path, dict[str, str]]:
    base = tmp_path_factory.mktemp("plain")
    shutil.copytree(ROOT / "src", base / "src", ignore=shutil.ignore_patterns("__pycache__", "*.so", "*.egg-info"))
    env = _without_checkout(os.environ) | {"CMAKE_PREFIX_PATH": str(VENV), "AMENT_PREFIX_PATH": str(VENV)}
    build = subprocess.run(
        [str(VENV / "bin" / "colcon"), "--log-base", str(base / "log"), "build", "--base-paths", str(base / "src"),
         "--build-base", str(base / "build"), "--install-base", str(base / "install"),
         "--event-handlers", "console_cohesion-", "status-", "summary+",
         "--cmake-args", f"-DPython3_EXECUTABLE={sys.executable}", "-DBUILD_TESTING=OFF"],
        cwd=base, env=env, capture_output=True, text=True, timeout=1200)
    assert build.returncode == 0, build.stdout[-3000:] + build.stderr[-3000:]
    shutil.rmtree(base / "src")
    shutil.rmtree(base / "build")  # nothing may point into the build tree either
    return base / "install", _sourced(base / "install", env)


def test_a_plain_install_serves_the_graph_from_the_install_space_alone(plain_install, ros_domain, tmp_path) -> None:
    from semgoal_ros.client import GraphClient

    install, env = plain_install
    env |= {"ROS_DOMAIN_ID": str(ros_domain), "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST"}
    for name in PATH_VARIABLES:
        assert not any(str(ROOT / d) in env.get(name, "") for d in ("src", "ros_ws")), name
    where = subprocess.run([sys.executable, "-c", "import semgoal_policy, semgoal_bringup.graph as g; "
                            "print(semgoal_policy.__file__); print(g.params_file())"],
                           env=env, cwd=tmp_path, capture_output=True, text=True, check=True).stdout.split()
    assert all(path.startswith(str(install)) for path in where), where
    assert (install / "semgoal_bringup/share/semgoal_bringup/launch/semgoal.launch.py").is_file()

    nodes = NodeProcesses(tmp_path)
    params = f"{install}/semgoal_bringup/share/semgoal_bringup/config/semgoal.yaml"
    task = {"scene": "desk_cleanup", "task": TASK, "seed": SEED, "mode": "lockstep"}
    started = [("semgoal_sim", "sim_node", task), ("semgoal_sim", "predicate_node", {}),
               ("semgoal_planner", "planner_node", {"scene": "desk_cleanup"}),
               ("semgoal_policy", "policy_node", {"scene": "desk_cleanup", "mode": "lockstep"})]
    try:
        for package, executable, overrides in started:
            command = [sys.executable, "-m", "semgoal_bringup.cli", "run", package, executable,
                       "--ros-args", "--params-file", params, *[a for k, v in overrides.items() for a in ("-p", f"{k}:={v}")]]
            log = open(tmp_path / f"{executable}.log", "w")  # noqa: SIM115
            nodes.processes.append((executable, subprocess.Popen(command, env=env, cwd=tmp_path, stdout=log,
                                                                 stderr=subprocess.STDOUT)))
        client = GraphClient("semgoal_plain_install_test", watch=False)
        try:
            assert client.wait_ready(), nodes.logs()
            ok, message = client.reset(TASK, SEED)
            assert ok, message
            result = client.execute(TASK, max_steps=TASK_STEP_BUDGET, timeout=240)
        finally:
            client.close()
        assert result.success, result.message + nodes.logs()
        assert f"from {install}/semgoal_policy/share/semgoal_policy/models/desk_cleanup" in nodes.logs()
    finally:
        nodes.stop_all()
