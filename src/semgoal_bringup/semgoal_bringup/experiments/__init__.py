"""Experiments on the agent: evaluations (tasks, goal families, sub-goal types, perception), training, sweeps, ablations."""
