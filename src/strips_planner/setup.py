"""Metadata is declared in setup.cfg; only the C extensions need code: the PDDL reader's fast pass, grounding's
exploration and inner loop, and the searches and heuristics, in C (the reader's checks stay in Python)."""

from setuptools import Extension, setup

HEADERS = ["strips_planner/_support.h", "strips_planner/_atoms.h", "strips_planner/_landmarks.h"]

setup(ext_modules=[Extension(f"strips_planner.{name}", [f"strips_planner/{name}.c"], depends=HEADERS,
                             extra_compile_args=["-O2", "-std=c11"])
                   for name in ("_core", "_explore", "_ground", "_reader")])
