from setuptools import find_packages, setup

PACKAGE = "semgoal_ros"

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
    description="The ROS side every semgoal node shares: topic names, QoS, message <-> core conversions, run_node.",
    license="Apache-2.0",
)
