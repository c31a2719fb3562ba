"""The shipped presets (YAML): design profiles and printer profiles, installed as package data
of ``wheelstep_cli.profiles`` (see setup.py) and read with importlib.resources."""
