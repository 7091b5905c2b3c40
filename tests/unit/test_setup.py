"""A second `make setup` with nothing changed rebuilds nothing."""

import subprocess

import pytest

from conftest import ROOT


@pytest.mark.slow
def test_second_setup_rebuilds_nothing() -> None:
    built = ROOT / "ros_ws" / "install" / "semgoal_msgs" / "share" / "semgoal_msgs" / "package.xml"
    before = built.stat().st_mtime_ns
    result = subprocess.run(["bash", str(ROOT / "tools" / "setup.sh")], capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    assert "venv up to date" in result.stdout and "workspace up to date" in result.stdout
    assert built.stat().st_mtime_ns == before
