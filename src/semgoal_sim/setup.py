from setuptools import find_packages, setup

PACKAGE = "semgoal_sim"

setup(
    name=PACKAGE,
    version="0.1.0",
    packages=find_packages(exclude=["test"]),
    data_files=[
        ("share/ament_index/resource_index/packages", [f"resource/{PACKAGE}"]),
        (f"share/{PACKAGE}", ["package.xml"]),
    ],
    install_requires=["setuptools"],
    zip_safe=True,
    maintainer="semgoal developers",
    maintainer_email="dev@semgoal.org",
    description="MuJoCo Fetch block world: scenes, task samplers, predicates, scripted expert, gymnasium env; sim and predicate nodes.",
    license="Apache-2.0",
    entry_points={
        "console_scripts": [
            "sim_node = semgoal_sim.sim_node:main",
            "predicate_node = semgoal_sim.predicate_node:main",
        ],
    },
)
