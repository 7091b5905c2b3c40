"""Metadata is declared in setup.cfg; only the C extensions need code: grounding's inner loop, and the
searches and heuristics, in C (parsing stays in Python)."""

from setuptools import Extension, setup

setup(ext_modules=[Extension(f"semgoal_planner.{name}", [f"semgoal_planner/{name}.c"],
                             depends=["semgoal_planner/_support.h"], extra_compile_args=["-O2", "-std=c11"])
                   for name in ("_core", "_ground")])
