from setuptools import find_packages, setup

PACKAGE = "semgoal_policy"

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
    description="Goal-conditioned SAC+HER low-level policy: training, baselines, evaluation, exported actors; policy node.",
    license="Apache-2.0",
    entry_points={
        "console_scripts": [
            f"policy_node = {PACKAGE}.policy_node:main",
        ],
    },
)
