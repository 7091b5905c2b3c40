"""Block speeds behind ``semgoal_core.settling.REST_SPEED``: resting blocks, and a block let go 2, 5 and 12 cm
over the table (the last control step at which it still moves at REST_SPEED or faster), at four spots.

    source tools/env.sh && python -m semgoal_bench.rest_speeds
"""

import numpy as np

from semgoal_core.settling import REST_SPEED
from semgoal_core.tasks import TABLE_TOP
from semgoal_core.vocabulary import BLOCK_HALF_SIZE
from semgoal_sim.world import FetchWorld

REST_Z = TABLE_TOP + BLOCK_HALF_SIZE


def resting_speed(world: FetchWorld, steps: int = 50) -> float:
    """The fastest block (m/s) over ``steps`` control steps of three blocks resting on the table."""
    world.reset(np.array([[1.45, 0.95, REST_Z], [1.25, 0.95, REST_Z], [1.25, 0.70, REST_Z]]))
    fastest = 0.0
    for _ in range(steps):
        world.step(np.zeros(4))
        fastest = max(fastest, float(np.linalg.norm(world.snapshot().block_velocities[:, :3], axis=1).max()))
    return fastest


def last_moving_step(world: FetchWorld, x: float, height: float, steps: int = 40) -> int:
    """The last control step at which blue, let go ``height`` (m) over the table at (x, 0.65), is not still."""
    world.reset(np.array([[1.45, 0.95, REST_Z], [1.25, 0.95, REST_Z], [x, 0.65, REST_Z]]))
    world.set_block_pose("blue", np.array([x, 0.65, REST_Z + height]))
    last = 0
    for step in range(1, steps + 1):
        world.step(np.zeros(4))
        if np.linalg.norm(world.snapshot().block_velocities[2, :3]) >= REST_SPEED:
            last = step
    return last


def main() -> None:
    world = FetchWorld("three_blocks")
    print(f"resting blocks, 50 steps after reset: fastest {resting_speed(world):.2e} m/s")
    for height in (0.02, 0.05, 0.12):
        steps = [last_moving_step(world, x, height) for x in (1.15, 1.25, 1.40, 1.50)]
        print(f"let go {100 * height:.0f} cm up: last step at or above {REST_SPEED} m/s: {steps}")


if __name__ == "__main__":
    main()
