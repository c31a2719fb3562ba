"""3MF (3D Manufacturing Format) writer: named objects, build plate layout, metadata.

Each object keeps its own frame (vertices as the part was built); its place on the plate
is the build item's transform (3MF core: rotation about z, then translation, mm). Object
metadata go in a 3MF 1.2 ``<metadatagroup>``, names prefixed ``wheelstep:``. A slicer
configuration (PrusaSlicer's ``Metadata/Slic3r_PE.config``) may ride along.
Deterministic: fixed zip timestamps, sequential object ids, fixed number formatting.
"""

from __future__ import annotations

import io
import zipfile
from dataclasses import dataclass, field
from xml.sax.saxutils import escape, quoteattr

import numpy as np

_CONTENT_TYPES = (
    '<?xml version="1.0" encoding="UTF-8"?>\n'
    '<Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">'
    '<Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/>'
    '<Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/>'
    '<Default Extension="png" ContentType="image/png"/>'
    "</Types>"
)
_RELS = (
    '<?xml version="1.0" encoding="UTF-8"?>\n'
    '<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">'
    '<Relationship Target="/3D/3dmodel.model" Id="rel0" '
    'Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/>'
    "</Relationships>"
)
_ZIP_DATE = (1980, 1, 1, 0, 0, 0)
WHEELSTEP_NS = "urn:wheelstep:3mf:metadata"
#: Where PrusaSlicer reads (and writes) its configuration inside a 3MF.
SLICER_CONFIG = "Metadata/Slic3r_PE.config"


@dataclass(frozen=True)
class PlateObject:
    """One mesh placed on the plate: vertices in mm (part frame); the build item turns it by
    ``rotation`` (radians about z, through the frame's origin), then moves it by
    ``translation`` (mm)."""

    name: str
    vertices: np.ndarray
    faces: np.ndarray
    translation: tuple[float, float, float] = (0.0, 0.0, 0.0)
    metadata: dict[str, str] = field(default_factory=dict)
    rotation: float = 0.0


def item_transform(rotation: float, translation: tuple[float, float, float]) -> str:
    """The 3MF ``transform`` attribute (row vectors: p' = p M) of a turn about z, then a shift."""
    c, s = round(float(np.cos(rotation)), 12) + 0.0, round(float(np.sin(rotation)), 12) + 0.0
    tx, ty, tz = (float(t) + 0.0 for t in translation)
    return (f"{c:.9g} {s:.9g} 0 {-s + 0.0:.9g} {c:.9g} 0 0 0 1 "
            f"{tx:.5f} {ty:.5f} {tz:.5f}")


def placed_vertices(obj: PlateObject) -> np.ndarray:
    """The object's vertices where its build item puts them on the plate (mm)."""
    c, s = np.cos(obj.rotation), np.sin(obj.rotation)
    v = np.asarray(obj.vertices, dtype=float)
    return np.column_stack([c * v[:, 0] - s * v[:, 1], s * v[:, 0] + c * v[:, 1], v[:, 2]]) \
        + np.asarray(obj.translation, dtype=float)


def placed_object(name: str, vertices: np.ndarray, faces: np.ndarray, corner: tuple[float, float],
                  rotated: bool, metadata: dict[str, str]) -> PlateObject:
    """The part in its own frame, placed by its build item: turned by 90 degrees about z when
    ``rotated``, its bounding box's lower-left corner at ``corner`` (mm), its bottom on z = 0."""
    obj = PlateObject(name, vertices, faces, (0.0, 0.0, 0.0), metadata, np.pi / 2 if rotated else 0.0)
    lo = placed_vertices(obj).min(axis=0)
    return PlateObject(name, vertices, faces, (corner[0] - lo[0], corner[1] - lo[1], -lo[2]),
                       metadata, obj.rotation)


#: Deflate level of the package's entries: level 1 writes a pair's plates in a fifth of the
#: time of zlib's default 6 for about a fifth more bytes (measured in benchmarks/results.md).
ZIP_LEVEL = 1


def threemf_bytes(objects: list[PlateObject], metadata: dict[str, str] | None = None,
                  slicer_config: bytes | None = None) -> bytes:
    """A 3MF package (millimetres) holding ``objects`` as named build items, with
    ``slicer_config`` as ``Metadata/Slic3r_PE.config`` when given."""
    parts = [
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        '<model unit="millimeter" xml:lang="en-US" '
        'xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02" '
        f'xmlns:wheelstep="{WHEELSTEP_NS}">'
    ]
    for key, value in sorted((metadata or {}).items()):
        parts.append(f"<metadata name={quoteattr(_meta_name(key))}>{escape(str(value))}</metadata>")
    parts.append("<resources>")
    for oid, obj in enumerate(objects, start=1):
        parts.append(f'<object id="{oid}" name={quoteattr(obj.name)} type="model">')
        if obj.metadata:
            parts.append("<metadatagroup>")
            for key, value in sorted(obj.metadata.items()):
                parts.append(
                    f"<metadata name={quoteattr(_meta_name(key))}>{escape(str(value))}</metadata>"
                )
            parts.append("</metadatagroup>")
        parts.append("<mesh><vertices>")
        parts.append(_rows('<vertex x="%.5f" y="%.5f" z="%.5f"/>', obj.vertices))
        parts.append("</vertices><triangles>")
        parts.append(_rows('<triangle v1="%d" v2="%d" v3="%d"/>', obj.faces))
        parts.append("</triangles></mesh></object>")
    parts.append("</resources><build>")
    for oid, obj in enumerate(objects, start=1):
        parts.append(f'<item objectid="{oid}" '
                     f'transform="{item_transform(obj.rotation, obj.translation)}"/>')
    parts.append("</build></model>")
    model = "".join(parts).encode("utf-8")

    entries = [("[Content_Types].xml", _CONTENT_TYPES.encode()), ("_rels/.rels", _RELS.encode()),
               ("3D/3dmodel.model", model)]
    if slicer_config is not None:
        entries.append((SLICER_CONFIG, slicer_config))
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w") as zf:
        for name, data in entries:
            info = zipfile.ZipInfo(name, date_time=_ZIP_DATE)
            info.compress_type = zipfile.ZIP_DEFLATED
            info.external_attr = 0o644 << 16
            zf.writestr(info, data, compresslevel=ZIP_LEVEL)
    return buf.getvalue()


def _meta_name(key: str) -> str:
    """Non-standard 3MF metadata names need a namespace prefix; ours is ``wheelstep``."""
    standard = {"Title", "Designer", "Description", "Copyright", "LicenseTerms", "Rating",
                "CreationDate", "ModificationDate", "Application"}
    return key if key in standard or ":" in key else f"wheelstep:{key}"


def _rows(fmt: str, array: np.ndarray) -> str:
    """Every row of ``array`` through the %-format ``fmt``, concatenated (one C-level format call)."""
    array = np.asarray(array)
    if array.size == 0:
        return ""
    return (fmt * len(array)) % tuple(array.ravel().tolist())
