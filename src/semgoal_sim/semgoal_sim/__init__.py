"""The simulated Fetch: worlds, envs, the sim and predicates nodes. Importing it registers the gymnasium ids
(:mod:`semgoal_sim.registration`)."""

from semgoal_sim.registration import register_envs

register_envs()
