from setuptools import Extension, find_packages, setup

PACKAGE = "semgoal_planner"

setup(
    name=PACKAGE,
    version="0.1.0",
    packages=find_packages(exclude=["test"]),
    data_files=[
        ("share/ament_index/resource_index/packages", [f"resource/{PACKAGE}"]),
        (f"share/{PACKAGE}", ["package.xml"]),
    ],
    package_data={PACKAGE: ["domains/*.pddl"]},
    # grounding's inner loop, and the searches and heuristics, in C (parsing stays in Python)
    ext_modules=[Extension(f"{PACKAGE}.{name}", [f"{PACKAGE}/{name}.c"], depends=[f"{PACKAGE}/_support.h"],
                           extra_compile_args=["-O2", "-std=c11"]) for name in ("_core", "_ground")],
    install_requires=["setuptools"],
    zip_safe=False,
    maintainer="semgoal developers",
    maintainer_email="dev@semgoal.org",
    description="Vendored STRIPS planner, PDDL domains of the scenes, Plan2Goals, plan editing and execution monitoring; planner node.",
    license="Apache-2.0",
    entry_points={
        "console_scripts": [
            f"planner_node = {PACKAGE}.planner_node:main",
        ],
    },
)
