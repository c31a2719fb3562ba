"""Package layout that pyproject.toml cannot say: the top-level ``profiles/`` folder is shipped
inside the package as ``wheelstep_cli.profiles`` (the presets, as package data)."""

from setuptools import find_packages, setup

setup(
    packages=find_packages(include=["wheelstep_cli", "wheelstep_cli.*"]) + ["wheelstep_cli.profiles"],
    package_dir={"wheelstep_cli.profiles": "profiles"},
    package_data={"wheelstep_cli.profiles": ["*.yaml"], "wheelstep_cli.config": ["*.json"]},
)
