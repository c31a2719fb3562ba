"""Read gear meshes back (STL, or an object of a 3MF) and section them into 2D outlines.

The part's own frame is kept: its rotation axis is the mesh's z axis through
x = y = 0, as ``wheelstep gears`` writes them (3MF build-item transforms, which only
place parts on the plate, are read but not applied). Lengths in mm.
"""

from __future__ import annotations

import io
import zipfile
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from wheelstep_cli.errors import DesignError, file_problem
from wheelstep_cli.geometry.solids import section_outline

_CORE_NS = "http://schemas.microsoft.com/3dmanufacturing/core/2015/02"
_UNITS_MM = {"micron": 1e-3, "millimeter": 1.0, "centimeter": 10.0, "inch": 25.4,
             "foot": 304.8, "meter": 1000.0}


@dataclass(frozen=True)
class MeshObject:
    """One build item of a 3MF: the object's mesh in its own frame (mm), the item's transform
    (4 x 3, row vectors: placed = [x y z 1] @ transform) and the object's metadata (names
    without the ``wheelstep:`` prefix; ``printer`` and ``compensated``: the plate's, unless the
    object names them)."""

    name: str
    vertices: np.ndarray
    faces: np.ndarray
    transform: np.ndarray
    metadata: dict[str, str] = field(default_factory=dict)


def split_mesh_spec(spec: str) -> tuple[Path, str | None]:
    """``FILE.3mf:NAME`` -> (path, name); anything else -> (path, None)."""
    head, sep, tail = str(spec).rpartition(":")
    if sep and head.lower().endswith(".3mf") and tail and "/" not in tail:
        return Path(head), tail
    return Path(spec), None


def read_mesh(spec: str, param: str, default_name: str | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Vertices (V, 3) in mm and triangles (F, 3) of an STL file or a 3MF object.

    ``spec``: ``FILE.stl``, ``FILE.3mf`` (its only object, else the object called
    ``default_name``) or ``FILE.3mf:NAME``. ``param`` names the argument in errors.
    """
    path, name = split_mesh_spec(spec)
    if not path.is_file():
        raise DesignError(param, str(spec), file_problem(path))
    suffix = path.suffix.lower()
    if suffix == ".3mf":
        return _read_3mf_object(path, name, default_name, param)
    if suffix == ".stl":
        if name is not None:
            raise DesignError(param, str(spec), "an STL file holds one mesh; drop ':NAME'")
        return _readable(param, str(spec), "STL", lambda: _read_stl(path))
    raise DesignError(param, str(spec), "must be an .stl or .3mf file")


def _readable(param: str, where: str, kind: str, read):
    """``read()``, any failure but a DesignError turned into one naming ``param``."""
    try:
        return read()
    except DesignError:
        raise
    except Exception as err:  # malformed files of every kind end here
        raise DesignError(param, where, f"cannot be read as {kind} "
                          f"({type(err).__name__}: {str(err)[:80]})") from None


def _binary_stl_shortfall(path: Path) -> str | None:
    """Why an STL that read as no mesh may be a binary one cut short (its header declares
    more triangles than it holds), else None. Asked only after the reader failed, so a text
    STL is never judged by its first bytes."""
    with open(path, "rb") as stream:
        head = stream.read(84)
    declared = int.from_bytes(head[80:84], "little") if len(head) == 84 else 0
    held = (path.stat().st_size - 84) // 50
    return f"truncated: declares {declared} triangles, holds {held}" if 0 <= held < declared else None


def _read_stl(path: Path) -> tuple[np.ndarray, np.ndarray]:
    import trimesh

    try:
        mesh = trimesh.load(path, file_type="stl", force="mesh", process=True)
    except Exception:
        short = _binary_stl_shortfall(path)    # the reader's own error, unless the file is cut short
        if short is None:
            raise
        raise ValueError(short) from None
    if len(mesh.faces) == 0:
        raise ValueError(_binary_stl_shortfall(path) or "no triangles")
    return np.asarray(mesh.vertices, dtype=float), np.asarray(mesh.faces, dtype=np.int64)


def read_3mf_objects(path: Path, param: str) -> list[MeshObject]:
    """Every build item of a 3MF package (each object once if it has no build), own frames."""
    def read() -> list[MeshObject]:
        with zipfile.ZipFile(path) as zf:
            root = ET.parse(io.BytesIO(zf.read(_model_part(zf)))).getroot()
        return _objects_of(root)

    return _readable(param, str(path), "3MF", read)


def _objects_of(root) -> list[MeshObject]:
    scale = _UNITS_MM.get(root.get("unit", "millimeter"))
    if scale is None:
        raise ValueError(f"unknown unit {root.get('unit')!r}")
    ns = {"m": _CORE_NS}
    # the printer a plate was laid out for is the model's, and whether its parts were drawn
    # for it (compensated): each object carries them too
    model = {m.get("name", ""): (m.text or "") for m in root.iterfind("m:metadata", ns)}
    plate = {key: model[f"wheelstep:{key}"] for key in ("printer", "compensated") if model.get(f"wheelstep:{key}")}
    meshes = {}
    for obj in root.iterfind("m:resources/m:object", ns):
        mesh = obj.find("m:mesh", ns)
        if mesh is not None:
            meta = {**plate, **{m.get("name", "").removeprefix("wheelstep:"): (m.text or "")
                                for m in obj.iterfind("m:metadatagroup/m:metadata", ns)}}
            meshes[obj.get("id")] = (obj.get("name") or f"object {obj.get('id')}", mesh, meta)
    items = [(i.get("objectid"), i.get("transform")) for i in root.iterfind("m:build/m:item", ns)]
    items = [i for i in items if i[0] in meshes] or [(oid, None) for oid in meshes]
    objects = []
    for oid, transform in items:
        name, mesh, meta = meshes[oid]
        vertices, faces = _mesh_arrays(mesh, ns, name)
        matrix = np.vstack([np.eye(3), np.zeros(3)]) if not transform else \
            np.array([float(t) for t in transform.split()]).reshape(4, 3)
        objects.append(MeshObject(name, vertices * scale, faces, matrix, meta))
    return objects


def _mesh_arrays(mesh, ns, name: str) -> tuple[np.ndarray, np.ndarray]:
    vertices = np.array([[float(v.get(k)) for k in "xyz"]
                         for v in mesh.iterfind("m:vertices/m:vertex", ns)], dtype=float)
    faces = np.array([[int(t.get(k)) for k in ("v1", "v2", "v3")]
                      for t in mesh.iterfind("m:triangles/m:triangle", ns)], dtype=np.int64)
    if len(faces) == 0 or faces.min() < 0 or faces.max() >= len(vertices):
        raise ValueError(f"object {name!r} has no valid triangles")
    return vertices, faces


def _read_3mf_object(path: Path, name: str | None, default_name: str | None,
                     param: str) -> tuple[np.ndarray, np.ndarray]:
    """Mesh of one named object of a 3MF package, in its own frame (mm)."""
    objects = {o.name: o for o in read_3mf_objects(path, param)}
    if not objects:
        raise DesignError(param, str(path), "holds no mesh object")
    wanted = name
    if wanted is None:
        wanted = next(iter(objects)) if len(objects) == 1 else default_name
    if wanted not in objects:
        names = ", ".join(sorted(objects))
        raise DesignError(param, f"{path}:{wanted}" if wanted else str(path),
                          f"name one of its objects as FILE.3mf:NAME ({names})")
    return objects[wanted].vertices, objects[wanted].faces


def _model_part(zf: zipfile.ZipFile) -> str:
    """The 3D model part named by the package relationships (default 3D/3dmodel.model)."""
    try:
        rels = ET.fromstring(zf.read("_rels/.rels"))
        for rel in rels:
            if rel.get("Type", "").endswith("/3dmodel"):
                return rel.get("Target", "").lstrip("/")
    except KeyError:
        pass
    return "3D/3dmodel.model"


def read_outline(spec: str, param: str, default_name: str | None = None) -> np.ndarray:
    """Read a gear mesh and return its outline (N, 2), mm, counter-clockwise, at the middle of
    its tooth zone (geometry.mesh_checks.tooth_zone_middle: a hub above the teeth is not cut)."""
    vertices, faces = read_mesh(spec, param, default_name)
    try:
        return section_outline(vertices, faces, param)
    except DesignError as err:          # named by the file the user gave, not "mesh"
        raise DesignError(param, spec, err.limit) from None
