"""Metadata is declared in setup.cfg; the shipped voter and its recipe are installed under
share/semgoal_perception/ (found at run time through the ament index)."""

from pathlib import Path

from setuptools import setup

PACKAGE = "semgoal_perception"
DATA = [path for root in ("models", "recipes") for path in sorted(Path(root).rglob("*")) if path.is_file()]
FOLDERS = sorted({path.parent for path in DATA})

setup(data_files=[
    ("share/ament_index/resource_index/packages", [f"resource/{PACKAGE}"]),
    (f"share/{PACKAGE}", ["package.xml", "README.md"]),
    *((f"share/{PACKAGE}/{folder}", [str(p) for p in DATA if p.parent == folder]) for folder in FOLDERS),
])
