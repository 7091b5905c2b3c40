from setuptools import find_packages, setup

PACKAGE = "semgoal_core"

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
    description="The semantic core: vocabulary, tasks, layouts and features, geometry, the at-rest and lockstep rules.",
    license="Apache-2.0",
)
