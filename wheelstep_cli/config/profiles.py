"""YAML presets in ``profiles/``: designs (mechanism, gears, shoe) and printers.

A profile is looked up as a path, then as ``NAME.yaml`` in ``./profiles`` and among
the presets shipped with the package (``wheelstep_cli.profiles``, read with
importlib.resources, so they are there after a normal install too). Keys are checked against what the
command knows; an unknown key is an error naming the file and the allowed keys.
"""

from __future__ import annotations

import importlib.resources
from pathlib import Path
from typing import Any, Iterable

from wheelstep_cli.errors import DesignError

def shipped_profiles() -> Path:
    """Folder of the presets installed with the package."""
    return Path(str(importlib.resources.files("wheelstep_cli.profiles")))


def profile_dirs() -> list[Path]:
    """Folders searched for profiles by name, in order."""
    return [Path.cwd() / "profiles", shipped_profiles()]


def find_profile(name_or_path: str) -> Path:
    """Path of a profile given as a file path or a bare name."""
    path = Path(name_or_path)
    if path.suffix in (".yaml", ".yml") and path.is_file():
        return path
    for folder in profile_dirs():
        for suffix in (".yaml", ".yml"):
            candidate = folder / f"{name_or_path}{suffix}"
            if candidate.is_file():
                return candidate
    known = sorted({p.stem for d in profile_dirs() if d.is_dir() for p in d.glob("*.yaml")})
    raise DesignError("profile", name_or_path, f"not found; known profiles: {', '.join(known) or 'none'}")


def load_profile(name_or_path: str) -> tuple[Path, dict[str, Any]]:
    """Read a profile file; returns its path and its top-level mapping."""
    import yaml

    path = find_profile(name_or_path)
    try:
        data = yaml.safe_load(path.read_text(encoding="utf-8"))
    except yaml.YAMLError as err:
        raise DesignError("profile", str(path), f"is not valid YAML ({err})") from None
    if not isinstance(data, dict):
        raise DesignError("profile", str(path), "must be a mapping of sections")
    return path, data


def profile_section(path: Path, data: dict[str, Any], section: str,
                    allowed: Iterable[str]) -> dict[str, Any]:
    """One section of a profile, keys checked against ``allowed`` (dashes read as underscores)."""
    raw = data.get(section) or {}
    if not isinstance(raw, dict):
        raise DesignError("profile", f"{path}:{section}", "must be a mapping")
    allowed = list(allowed)
    values = {}
    for key, value in raw.items():
        name = str(key).replace("-", "_")
        if name not in allowed:
            raise DesignError("profile", f"{path}:{section}.{key}",
                              f"unknown key; allowed: {', '.join(allowed)}")
        values[name] = value
    return values


def merge_options(cli: dict[str, Any], *layers: dict[str, Any]) -> dict[str, Any]:
    """Command-line values that were given (not None) override profile layers, first layer wins."""
    merged: dict[str, Any] = {}
    for layer in reversed(layers):
        merged.update({k: v for k, v in layer.items() if v is not None})
    merged.update({k: v for k, v in cli.items() if v is not None})
    return merged
