"""Everything about this package is declared in setup.cfg."""

from setuptools import setup

setup()
