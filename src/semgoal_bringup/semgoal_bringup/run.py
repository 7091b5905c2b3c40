"""`./semgoal run PKG EXE [args...]`: execute an installed node, as `ros2 run` does natively."""

import os
import sys
from pathlib import Path


def executable_path(package: str, executable: str) -> Path:
    """``<prefix>/lib/PKG/EXE`` of the install space the ament index names for ``package``, as ``ros2 run``
    finds it; FileNotFoundError with a helpful message."""
    from ament_index_python.packages import PackageNotFoundError, get_package_prefix

    try:
        lib_dir = Path(get_package_prefix(package)) / "lib" / package
    except PackageNotFoundError:
        raise FileNotFoundError(f"package {package!r} is not installed: run 'make setup' (or source an install)") from None
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
