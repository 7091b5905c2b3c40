"""Data a package installs under ``share/<package>/`` (parameters, shipped actors, recipes), found through the
ament index as ROS does, so a plain ``colcon build`` serves the nodes as well as a symlink install."""

from pathlib import Path


def share_path(package: str, *parts: str) -> Path:
    """``share/<package>/<parts...>`` in the install space that the ament index names for ``package``."""
    from ament_index_python.packages import PackageNotFoundError, get_package_share_directory

    try:
        return Path(get_package_share_directory(package), *parts)
    except PackageNotFoundError:
        raise FileNotFoundError(f"package {package} is not installed: build the workspace and source its setup "
                                "(make setup, or colcon build && source install/setup.bash)") from None
