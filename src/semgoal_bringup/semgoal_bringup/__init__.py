"""Operator CLI, parameters and bring-up of the semgoal node graph."""
