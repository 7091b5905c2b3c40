from glob import glob

from setuptools import find_packages, setup

PACKAGE = "semgoal_bringup"

setup(
    name=PACKAGE,
    version="0.1.0",
    packages=find_packages(exclude=["test"]),
    data_files=[
        ("share/ament_index/resource_index/packages", [f"resource/{PACKAGE}"]),
        (f"share/{PACKAGE}", ["package.xml"]),
        (f"share/{PACKAGE}/config", glob("config/*.yaml")),
    ],
    install_requires=["setuptools"],
    zip_safe=True,
    maintainer="semgoal developers",
    maintainer_email="dev@semgoal.org",
    description="Parameters, launch file and the operator CLI of semgoal.",
    license="Apache-2.0",
    entry_points={
        "console_scripts": [
            "echo_node = semgoal_bringup.echo_node:main",
        ],
    },
)
