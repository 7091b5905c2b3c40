"""Measurements outside the product: each a `./semgoal bench ...` command (README.md)."""
