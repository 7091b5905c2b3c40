from setuptools import find_packages, setup

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
