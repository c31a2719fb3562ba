"""Binary STL encoding and decoding (deterministic: fixed header, no timestamps)."""

from __future__ import annotations

import numpy as np

_RECORD = np.dtype([("normal", "<f4", 3), ("v", "<f4", (3, 3)), ("attr", "<u2")])


def stl_bytes(vertices: np.ndarray, faces: np.ndarray, name: str = "wheelstep part") -> bytes:
    """Binary STL of a triangle mesh (vertices in mm, faces as vertex indices, CCW outward)."""
    tri = np.asarray(vertices, dtype=np.float64)[np.asarray(faces)]
    normals = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    length = np.linalg.norm(normals, axis=1, keepdims=True)
    normals = np.divide(normals, length, out=np.zeros_like(normals), where=length > 0)
    records = np.zeros(len(tri), dtype=_RECORD)
    records["normal"] = normals
    records["v"] = tri
    header = name.encode("ascii", "replace")[:80].ljust(80, b" ")
    return header + np.uint32(len(tri)).tobytes() + records.tobytes()


def read_stl_triangles(data: bytes) -> np.ndarray:
    """Triangles (T, 3, 3) in mm from binary STL bytes."""
    count = int(np.frombuffer(data, dtype="<u4", count=1, offset=80)[0])
    records = np.frombuffer(data, dtype=_RECORD, count=count, offset=84)
    return records["v"].astype(np.float64)
