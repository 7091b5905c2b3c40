"""`./semgoal doctor`: what a user needs to know before filing a bug."""

import importlib.metadata
import os
import subprocess
import sys
from pathlib import Path


def version(distribution: str) -> str:
    """Installed version of a distribution, or 'missing'."""
    try:
        return importlib.metadata.version(distribution)
    except importlib.metadata.PackageNotFoundError:
        return "missing"


def workspace_state(root: Path) -> str:
    """Ask the setup script whether the venv and the workspace match their inputs."""
    result = subprocess.run(["bash", str(root / "tools" / "setup.sh"), "--check"], capture_output=True, text=True)
    return result.stdout.strip() or f"unknown ({result.stderr.strip()})"


def main(argv: list[str]) -> int:
    """Print versions, workspace state and DDS settings."""
    root = Path(os.environ.get("SEMGOAL_ROOT", Path.cwd()))
    rows = [
        ("python", sys.version.split()[0]),
        ("rclpy", version("ros-jazzy-rclpy")),
        ("rmw", os.environ.get("RMW_IMPLEMENTATION", "default") + " " + version("ros-rmw-fastrtps-cpp")),
        ("mujoco", version("mujoco")),
        ("torch", version("torch")),
        ("stable-baselines3", version("stable-baselines3")),
        ("workspace", workspace_state(root)),
        ("ROS_DOMAIN_ID", os.environ.get("ROS_DOMAIN_ID", "unset (0)")),
        ("ROS_AUTOMATIC_DISCOVERY_RANGE", os.environ.get("ROS_AUTOMATIC_DISCOVERY_RANGE", "unset (SUBNET!)")),
        ("MUJOCO_GL", os.environ.get("MUJOCO_GL", "unset")),
    ]
    probe = subprocess.run([sys.executable, "-c", "import rclpy, semgoal_msgs.msg"], capture_output=True)
    rows.append(("rclpy + semgoal_msgs import", "ok" if probe.returncode == 0 else "FAILED"))
    width = max(len(name) for name, _ in rows)
    for name, value in rows:
        print(f"{name:<{width}}  {value}")
    return 0 if probe.returncode == 0 else 1
