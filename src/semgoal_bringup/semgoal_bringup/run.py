"""`./semgoal run PKG EXE [args...]`: execute an installed node, as `ros2 run` does natively."""

import os
import sys
from pathlib import Path


def executable_path(package: str, executable: str) -> Path:
    """Return ``install/PKG/lib/PKG/EXE`` of the workspace overlay, or raise with a helpful message."""
    root = Path(os.environ.get("SEMGOAL_ROOT", Path.cwd()))
    lib_dir = root / "ros_ws" / "install" / package / "lib" / package
    if not lib_dir.is_dir():
        raise FileNotFoundError(f"package {package!r} not found in {root / 'ros_ws/install'}; run 'make setup'")
    path = lib_dir / executable
    if not path.is_file():
        available = ", ".join(sorted(p.name for p in lib_dir.iterdir())) or "none"
        raise FileNotFoundError(f"no executable {executable!r} in package {package!r} (available: {available})")
    return path


def main(argv: list[str]) -> int:
    """Replace this process with the node, passing every further argument (``--ros-args`` included)."""
    if len(argv) < 2:
        print("usage: ./semgoal run PACKAGE EXECUTABLE [args...] [--ros-args ...]", file=sys.stderr)
        return 2
    try:
        path = executable_path(argv[0], argv[1])
    except FileNotFoundError as error:
        print(f"semgoal run: {error}", file=sys.stderr)
        return 2
    os.execv(sys.executable, [sys.executable, str(path), *argv[2:]])
    return 0  # not reached
