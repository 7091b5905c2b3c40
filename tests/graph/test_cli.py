"""The operator CLI: `./semgoal run` starts real nodes, `./semgoal doctor` reports the environment."""

import re
import subprocess

from conftest import ROOT, GraphProbe, NodeProcesses


def test_semgoal_run_starts_a_node_seen_in_the_graph(nodes: NodeProcesses, probe: GraphProbe) -> None:
    process = nodes.start("semgoal_bringup", "echo_node", params={"feedback_count": 5})
    probe.spin_until(lambda: "semgoal_echo" in probe.node.get_node_names(), 20, "node semgoal_echo")
    # stop it only once fully up (its action server exists), or SIGINT lands mid-construction
    probe.spin_until(lambda: any("_action/send_goal" in name for name, _ in probe.node.get_service_names_and_types()),
                     20, "echo action server")
    assert process.poll() is None
    assert nodes.stop(process) in (0, -2)  # clean exit on SIGINT


def test_semgoal_run_rejects_unknown_executables() -> None:
    result = subprocess.run([str(ROOT / "semgoal"), "run", "semgoal_bringup", "no_such_node"],
                            capture_output=True, text=True)
    assert result.returncode == 2
    assert "no executable 'no_such_node'" in result.stderr and "echo_node" in result.stderr


def test_doctor_reports_versions_and_dds_settings() -> None:
    result = subprocess.run([str(ROOT / "semgoal"), "doctor"], capture_output=True, text=True)
    assert result.returncode == 0, result.stdout + result.stderr
    assert "rclpy                          7.1.6" in result.stdout
    assert "ROS_AUTOMATIC_DISCOVERY_RANGE  LOCALHOST" in result.stdout
    assert "built and current" in result.stdout


def test_demo_solves_a_task_through_the_graph() -> None:
    result = subprocess.run([str(ROOT / "semgoal"), "demo", "--task", "MC-2", "--seed", "4", "--gif", "/tmp/semgoal-test-demo.gif"],
                            capture_output=True, text=True, timeout=240)
    assert result.returncode == 0, result.stdout[-2000:] + result.stderr[-2000:]
    assert result.stdout.strip().splitlines()[-1] == "MC-2: success"
    assert "plan: 0. pick(" in result.stdout and "started 0. pick(" in result.stdout
    steps = int(re.search(r"\[demo\] (\d+) control steps", result.stdout).group(1))
    frames = int(re.search(r"episode GIF: \S+ \((\d+) frames\)", result.stdout).group(1))
    assert frames >= steps // 2, "the GIF should show every second step of the episode"


def test_demo_gives_its_goal_a_step_budget() -> None:
    result = subprocess.run([str(ROOT / "semgoal"), "demo", "--task", "MC-2", "--seed", "4", "--max-steps", "3", "--no-gif"],
                            capture_output=True, text=True, timeout=240)
    assert result.returncode == 1, result.stdout[-2000:] + result.stderr[-2000:]
    assert "budget of 3 control steps" in result.stdout and result.stdout.strip().splitlines()[-1] == "MC-2: failure"


def test_demo_rejects_unknown_tasks_and_budgets() -> None:
    result = subprocess.run([str(ROOT / "semgoal"), "demo", "--task", "XX-9"], capture_output=True, text=True)
    assert result.returncode == 2 and "unknown task 'XX-9'" in result.stderr
    result = subprocess.run([str(ROOT / "semgoal"), "demo", "--max-steps", "-1"], capture_output=True, text=True)
    assert result.returncode == 2 and "--max-steps must be 0" in result.stderr
