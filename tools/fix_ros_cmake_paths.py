"""Point the ROS wheels' exported CMake targets at this interpreter instead of the wheel build machine.

The PyPI ROS 2 wheels were built under ``/opt/python/cp311-cp311``; their ``*Export*.cmake`` files name
that prefix for the Python headers and numpy's headers, and CMake refuses non-existent include paths.
Idempotent: files already rewritten are left alone.
"""

import sys
import sysconfig
from pathlib import Path

BUILD_PREFIX = "/opt/python/cp311-cp311"


def rewrite(venv: Path) -> int:
    """Rewrite every exported CMake file under ``venv/share``; return how many files changed."""
    include_dir = sysconfig.get_paths()["include"]
    site_packages = sysconfig.get_paths()["purelib"]
    replacements = [
        (f"{BUILD_PREFIX}/include/python3.11", include_dir),
        (f"{BUILD_PREFIX}/lib/python3.11/site-packages", site_packages),
    ]
    changed = 0
    for path in venv.glob("share/*/cmake/*Export*.cmake"):
        text = path.read_text()
        new = text
        for old, repl in replacements:
            new = new.replace(old, repl)
        if new != text:
            path.write_text(new)
            changed += 1
    return changed


if __name__ == "__main__":
    print(f"rewrote {rewrite(Path(sys.prefix))} exported CMake files")
