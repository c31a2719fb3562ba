"""Independent checks of written files (trimesh, lib3mf) used by several test modules."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    import trimesh


def assert_printable_stl(path: Path) -> "trimesh.Trimesh":
    """Load an STL with trimesh and assert it is watertight, consistently wound, positive volume."""
    import trimesh

    mesh = trimesh.load(path, force="mesh")
    assert mesh.is_watertight, path
    assert mesh.is_winding_consistent, path
    assert mesh.volume > 0, path
    return mesh


def read_3mf_strict(path: Path) -> dict:
    """Read a 3MF with lib3mf in strict mode: returns warnings and mesh objects (name -> volume mm3)."""
    import lib3mf

    wrapper = lib3mf.get_wrapper()
    model = wrapper.CreateModel()
    reader = model.QueryReader("3mf")
    reader.SetStrictModeActive(True)
    reader.ReadFromFile(str(path))
    warnings = [reader.GetWarning(i) for i in range(reader.GetWarningCount())]
    objects = {}
    it = model.GetMeshObjects()
    while it.MoveNext():
        obj = it.GetCurrentMeshObject()
        vertices = np.array([v.Coordinates[0:3] for v in obj.GetVertices()])
        faces = np.array([t.Indices[0:3] for t in obj.GetTriangleIndices()])
        tri = vertices[faces]
        volume = np.einsum("ij,ij->i", tri[:, 0], np.cross(tri[:, 1], tri[:, 2])).sum() / 6.0
        objects[obj.GetName()] = volume
    items = model.GetBuildItems()
    count = 0
    while items.MoveNext():
        count += 1
    return {"warnings": warnings, "objects": objects, "build_items": count, "unit": model.GetUnit()}
