"""The Docker image installs what the nodes need at the versions the venv pins, and runs a plain build.
(No Docker daemon is at hand in CI: the file is checked, not built.)"""

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).parents[2]
DOCKERFILE = (ROOT / "docker" / "Dockerfile").read_text()


def _pins(text: str) -> dict[str, str]:
    return {name.lower().replace("_", "-"): version for name, version in re.findall(r"([A-Za-z0-9_.-]+)==([^\s\\]+)", text)}


def test_the_image_pins_every_runtime_package_as_the_lock_file_does() -> None:
    lock = _pins((ROOT / "requirements" / "lock.txt").read_text())
    pip_lines = " ".join(line for line in DOCKERFILE.splitlines() if "==" in line)
    image = _pins(pip_lines)
    for needed in ("torch", "mujoco", "gymnasium", "gymnasium-robotics", "lark-parser", "matplotlib", "imageio", "tqdm",
                   "mcap", "mcap-ros2-support", "foxglove-sdk"):
        assert needed in image, f"the image does not install {needed}"
    for name, version in image.items():
        assert lock.get(name) == version or (name == "torch" and lock.get(name, "").startswith(version)), \
            f"{name}=={version} in the image, {lock.get(name)} in requirements/lock.txt"


def test_the_image_builds_plainly_and_sources_with_a_double_dash() -> None:
    builds = [line for line in DOCKERFILE.splitlines() if "colcon build" in line and not line.lstrip().startswith("#")]
    assert builds and not any("--symlink-install" in line for line in builds)
    for package in ("ros-jazzy-rviz2", "ros-jazzy-launch-ros", "ros-jazzy-diagnostic-msgs", "ros-jazzy-rosgraph-msgs"):
        assert package in DOCKERFILE
    entrypoint = (ROOT / "docker" / "entrypoint.sh").read_text()
    assert all(line.rstrip().endswith("--") for line in entrypoint.splitlines() if line.startswith("source "))


@pytest.mark.slow
def test_the_dockerfile_is_hadolint_clean() -> None:
    import subprocess

    result = subprocess.run(["hadolint", str(ROOT / "docker" / "Dockerfile")], capture_output=True, text=True)
    assert result.returncode == 0, result.stdout + result.stderr
