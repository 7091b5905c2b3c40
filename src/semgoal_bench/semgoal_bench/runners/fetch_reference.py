"""gymnasium-robotics' FetchPickAndPlace-v4 stepped with the same random actions: the reference row of
bench/sim.py, run in a child `python -O` (its asserts fail on mujoco >= 3.12).

    python -O src/semgoal_bench/semgoal_bench/runners/fetch_reference.py STEPS REPEATS   -> the median steps/s
"""

import statistics
import sys
import time

import gymnasium as gym
import gymnasium_robotics
import numpy as np


def main(steps: int, repeats: int) -> None:
    gym.register_envs(gymnasium_robotics)
    env = gym.make("FetchPickAndPlace-v4", max_episode_steps=10**9)
    actions = np.random.default_rng(0).uniform(-1, 1, size=(steps, 4)).astype(np.float32)
    rates = []
    for _ in range(repeats):
        env.reset(seed=1)
        start = time.perf_counter()
        for action in actions:
            env.step(action)
        rates.append(steps / (time.perf_counter() - start))
    print(statistics.median(rates))


if __name__ == "__main__":
    main(int(sys.argv[1]), int(sys.argv[2]))
