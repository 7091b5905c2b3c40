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
    # the searches and heuristics in C (parsing and grounding stay in Python)
    ext_modules=[Extension(f"{PACKAGE}._core", [f"{PACKAGE}/_core.c"], extra_compile_args=["-O2", "-std=c11"])],
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
