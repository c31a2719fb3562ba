"""Solids with manifold3d (the only module that imports it): extrusion of checked outlines,
sockets, elephant-foot insets, footprints and sections."""

from __future__ import annotations

import numpy as np

from wheelstep_cli.errors import DesignError, rounded_down
from wheelstep_cli.geometry.hole_walls import (MIN_HOLE_WALL, corner_clear_of, hole_reach, require_hub_fits,
                                               require_screw_fits, require_wall)
from wheelstep_cli.geometry.mesh_checks import Part, tooth_zone_middle
from wheelstep_cli.geometry.staircase import staircase_mesh
from wheelstep_cli.geometry.planar import (check_outline, drop_collinear, group_rings_by_shell,
                                          inset_area_lost, min_radius, signed_area)


def circle(radius: float, segments: int) -> np.ndarray:
    """Counter-clockwise circle of ``segments`` points, radius in mm."""
    t = np.linspace(0.0, 2.0 * np.pi, segments, endpoint=False)
    return radius * np.column_stack([np.cos(t), np.sin(t)])


def bore_segments(diameter: float) -> int:
    """Polygon count for a bore: chord error below 0.01 mm, at least 32."""
    r = diameter / 2.0
    return max(32, int(np.ceil(np.pi / np.arccos(max(1e-9, 1.0 - 0.01 / max(r, 0.01))))))


def extrude_plate(name: str, outline: np.ndarray, thickness: float, bore: float = 0.0,
                  bore_param: str = "bore") -> Part:
    """Extrude a closed outline (mm, any orientation) by ``thickness`` mm along +Z.

    A centred round ``bore`` of that diameter (mm, 0 for none) is cut through.
    The outline is checked first; the bore must leave wall to the outline.
    """
    if not thickness > 0:
        raise DesignError("thickness", thickness, "must be > 0 mm")
    outline = check_outline(outline, name)
    polygons = [outline]
    area = signed_area(outline)
    if bore > 0:
        wall = min_radius(outline) - bore / 2.0
        if wall < 1.0:
            raise DesignError(bore_param, bore,
                              f"must be < {rounded_down(2 * (min_radius(outline) - 1.0))} mm "
                              f"(leave 1 mm of wall inside the {name}'s root)")
        segments = bore_segments(bore)
        # circumscribed polygon: its flats touch the nominal circle, so the shaft fits
        hole = circle(bore / 2.0 / np.cos(np.pi / segments), segments)
        polygons.append(hole[::-1])
        area -= signed_area(hole)
    elif bore < 0:
        raise DesignError(bore_param, bore, "must be >= 0 mm")
    return solid_from_polygons(name, polygons, thickness, area * thickness)




def extrude_gear(name: str, outline: np.ndarray, thickness: float, hole: np.ndarray | None,
                 marks: list[np.ndarray], mark_depth: float, hole_param: str = "bore",
                 hole_value: object = None, pockets: list[np.ndarray] = (),
                 chamfer: float = 0.0, hub: tuple[float, float] = (0.0, 0.0),
                 set_screw: tuple | None = None, keyed_bore: tuple[float, float] | None = None) -> Part:
    """A gear plate (mm): ``outline`` extruded by ``thickness`` along +z with the shaft
    ``hole`` ring (CCW, None for none) cut through and the ``marks`` (CCW rings) engraved
    ``mark_depth`` mm into the top face (an open groove: prints without support) and the
    ``pockets`` (CCW rings inside the web, checked by their maker) cut through; every edge
    of the top and bottom faces chamfered 45 deg by ``chamfer`` mm (see :func:`_chamfered`);
    ``hub`` = (diameter, length) mm: a boss round the hole on the top face (none for 0), which
    must leave MIN_HOLE_WALL mm to the root and round the hole (DesignError naming hub_d); it
    fills the chamfer of the hole's top edge (see :func:`_with_hub`).
    ``set_screw`` = (name, direction rad, teardrop ring, nut across flats, nut height) mm: a
    radial screw hole through the hub along ``direction`` and a nut slot open to the hub's
    top (see :func:`_set_screw`).

    The hole must leave MIN_HOLE_WALL mm to the root (DesignError naming ``hole_param``, or for
    a keyway the bore when ``keyed_bore`` = (bore, key width) mm says no key depth helps)."""
    import manifold3d as m3d

    if not thickness > 0:
        raise DesignError("thickness", thickness, "must be > 0 mm")
    outline = check_outline(outline, name)
    if signed_area(outline) < 0:
        outline = outline[::-1]
    polygons, area = [outline], signed_area(outline)
    if hole is not None:
        require_wall(name, outline, hole, hole_param, hole_value, keyed_bore)
        polygons.append(np.asarray(hole, dtype=float)[::-1])
        area -= signed_area(hole)
    for pocket in pockets:
        polygons.append(np.asarray(pocket, dtype=float)[::-1])
        area -= signed_area(pocket)
    section = m3d.CrossSection([np.ascontiguousarray(p, dtype=np.float64) for p in polygons],
                               m3d.FillRule.Positive)
    if chamfer > 0:
        # a hub's bore meets the staircase's bore walls face to face, and its boolean with the
        # direct mesh leaves edges of four faces once written in float32: hubbed plates unite
        body, volume, layers = _chamfered(section, thickness, chamfer, direct=hub[0] <= 0)
    else:
        body, volume, layers = m3d.Manifold.extrude(section, thickness), area * thickness, \
            [(section, 0.0)]
    if hub[0] > 0:
        # a set screw's hole runs along its direction
        phase = 0.0 if set_screw is None else corner_clear_of(set_screw[1], bore_segments(hub[0]))
        body, volume = _with_hub(body, volume, layers, outline, hole, hub, thickness, chamfer, phase)
    if set_screw is not None:
        body, volume = _set_screw(body, volume, hole, hub, thickness, set_screw)
    if marks and mark_depth > 0:
        # the cutter pokes 1 mm above the top so no face of it is coplanar with the top
        cutter = m3d.Manifold.extrude(m3d.CrossSection(
            [np.ascontiguousarray(m, dtype=np.float64) for m in marks], m3d.FillRule.Positive),
            mark_depth + 1.0).translate((0.0, 0.0, thickness - mark_depth))
        body = body - cutter
        volume -= mark_depth * sum(signed_area(m) for m in marks)
    return _part_of(name, body, volume)


def _set_screw(body, volume: float, hole, hub: tuple[float, float], thickness: float,
               screw: tuple):
    """Cut a radial set-screw hole (teardrop section, axis half-way up the hub) and a captive
    nut slot (open upwards, so both print without support) into ``body``; the volume (mm3)
    is taken from the boolean result since the cuts cross curved walls (refused when the nut
    leaves under MIN_HOLE_WALL mm of wall)."""
    import manifold3d as m3d

    name, direction, drop, flats, height = screw
    reach = hole_reach(hole)
    require_screw_fits(name, reach, hub, thickness, flats, height, drop)
    r_hub, axis_z = hub[0] / 2.0, thickness + hub[1] / 2.0
    nut_in = reach + MIN_HOLE_WALL
    # the hole: the teardrop in the (y, z) plane extruded along +x, then turned to direction
    rod = m3d.Manifold.extrude(m3d.CrossSection([np.ascontiguousarray(drop)]), r_hub + 1.0)
    rod = rod.rotate((0.0, 90.0, 0.0)).rotate((90.0, 0.0, 0.0))
    # the nut slides in from the top, flats against the slot's sides: corners up and down
    corner = flats / np.sqrt(3.0)
    slot = m3d.Manifold.cube((height, flats, hub[1] / 2.0 + corner + 1.0)).translate(
        (nut_in, -flats / 2.0, axis_z - corner))
    cutter = (rod.translate((0.0, 0.0, axis_z)) + slot).rotate((0.0, 0.0, float(np.degrees(direction))))
    result = body - cutter
    return result, float(result.volume())


def _with_hub(body, volume: float, layers: list, outline: np.ndarray, hole: np.ndarray | None,
              hub: tuple[float, float], thickness: float, chamfer: float, phase: float = 0.0):
    """``body`` (the plate, of ``volume`` mm3, made of the nested ``layers`` = [(section, z)]:
    each section extruded from z to thickness - z) with the hub = (diameter, length) mm
    standing on its top face round the hole, and the volume of the union (mm3). ``phase``
    (rad): where the hub polygon's first corner lies.

    The boss reaches down into the plate, below the top chamfer: solids that only touch at
    a plane stay two shells, and it fills the chamfer round the hole's top edge, so the hole
    runs straight on into the hub (the teeth, pockets and the hole's bottom edge keep their
    chamfer). The material of both is counted once: the plate's share inside the boss's
    ring is summed layer by layer from the same nested sections."""
    import manifold3d as m3d

    ring, hub_area = _hub_ring(outline, hole, hub[0], phase)
    # without a chamfer 1 mm; with one, between the bottom chamfer and the top one
    base = thickness - chamfer - min(1.0, 0.5 * (thickness - 2.0 * chamfer)) if chamfer > 0 \
        else thickness - 1.0
    boss = m3d.Manifold.extrude(ring, thickness + hub[1] - base).translate((0.0, 0.0, base))
    shared, previous = 0.0, 0.0
    for layer, z in layers:
        inside = (layer ^ ring).area()
        shared += (inside - previous) * (thickness - z - base)
        previous = inside
    return body + boss, volume + hub_area * (thickness + hub[1] - base) - shared


def _hub_ring(outline: np.ndarray, hole: np.ndarray | None, diameter: float, phase: float = 0.0):
    """The hub's cross-section (manifold3d) and area (mm2), its diameter checked; its
    polygon's first corner at polar angle ``phase`` (rad)."""
    import manifold3d as m3d

    require_hub_fits(outline, hole, diameter)
    c, s = np.cos(phase), np.sin(phase)
    rings = [circle(diameter / 2.0, bore_segments(diameter)) @ np.array([[c, s], [-s, c]])]
    if hole is not None:
        rings.append(np.asarray(hole, dtype=float)[::-1])
    area = sum(signed_area(r) for r in rings)
    return m3d.CrossSection([np.ascontiguousarray(r) for r in rings], m3d.FillRule.Positive), area


#: Height (mm) of one step of a chamfer: half a fine layer, so a slicer prints it as a slope.
CHAMFER_STEP = 0.1


def _chamfered(section, thickness: float, chamfer: float, direct: bool = True):
    """The section extruded by ``thickness`` mm with its top and bottom edges chamfered 45 deg
    by ``chamfer`` mm, its volume (mm3) and its layers [(section, z)]. The chamfer is a
    staircase of steps no taller than CHAMFER_STEP (finer than any printed layer, so the print
    is the slope); the steps are nested prisms (each layer's section extruded from z to
    thickness - z) that overlap in volume, so their union is one closed body. ``direct``:
    built as one mesh by :func:`_staircase` (else, and where that fails, as the union)."""
    import manifold3d as m3d

    if not 2.0 * chamfer < thickness:      # the spec refuses it first (config.shaft_rules): before manifold3d
        raise DesignError("chamfer", chamfer, f"must be < half the thickness {thickness / 2:g} mm")
    steps = max(2, int(np.ceil(chamfer / CHAMFER_STEP)))
    body, volume, previous, layers = None, 0.0, 0.0, []
    for k in range(steps + 1):
        inset = chamfer * (1.0 - k / steps)
        # offsets leave vertex pairs nanometres apart; 0.1 micron simplification drops them
        layer = section.offset(-inset, m3d.JoinType.Miter, 2.0).simplify(1e-4) if inset else section
        if layer.is_empty():
            raise DesignError("chamfer", chamfer, "removes a whole tooth or web")
        z = chamfer * k / steps
        volume += (layer.area() - previous) * (thickness - 2.0 * z)
        previous = layer.area()
        layers.append((layer, z))
    body = _staircase(layers, thickness) if direct else None
    if body is None:
        # layers whose rings the direct build cannot stitch: the union of the nested prisms
        for layer, z in layers:
            prism = m3d.Manifold.extrude(layer, thickness - 2.0 * z).translate((0.0, 0.0, z))
            body = prism if body is None else body + prism
    return body, volume, layers


def _staircase(layers, thickness: float):
    """:func:`_chamfered`'s nested prisms as one solid (geometry.staircase); None when it
    cannot be built closed (then the caller unites them)."""
    import manifold3d as m3d
    rings = [[np.asarray(r, dtype=np.float64) for r in layer.to_polygons()] for layer, _ in layers]
    if any(not rs or any(len(r) < 3 for r in rs) for rs in rings):
        return None
    points, triangles = staircase_mesh(rings, [z for _, z in layers], thickness, m3d.triangulate)
    body = m3d.Manifold(m3d.Mesh(np.ascontiguousarray(points, dtype=np.float32),
                                 np.ascontiguousarray(triangles, dtype=np.uint32)))
    return body if body.status() == m3d.Error.NoError and not body.is_empty() else None


def section_rings(part: Part, z: float) -> list[np.ndarray]:
    """Every ring (N, 2) mm of the part's section at height ``z`` (outer CCW, holes CW)."""
    rings = _manifold_of(part).slice(float(z)).to_polygons()
    return [np.asarray(r, dtype=float) for r in rings if len(r) >= 3]


def manifold_of(part: Part):
    """The part as a manifold3d solid (for boolean checks in tests and reports)."""
    return _manifold_of(part)


def solid_from_polygons(name: str, polygons: list[np.ndarray], height: float,
                        expected_volume: float) -> Part:
    """Extrude checked polygons (outer CCW, holes CW) with manifold3d into a Part."""
    import manifold3d as m3d

    section = m3d.CrossSection([np.ascontiguousarray(p, dtype=np.float64) for p in polygons],
                               m3d.FillRule.Positive)
    return _part_of(name, m3d.Manifold.extrude(section, height), expected_volume)


def _part_of(name: str, solid, expected_volume: float, double: bool = False) -> Part:
    """The manifold3d solid as a Part (mm), refused when manifold3d reports an error or it is
    empty. ``double``: vertices in double precision (a boolean's result may hold vertices
    closer than float32 resolves, which would collapse triangles)."""
    import manifold3d as m3d

    if solid.status() != m3d.Error.NoError:
        raise DesignError(name, "solid", f"manifold3d reports {solid.status().name}")
    mesh = solid.to_mesh64() if double else solid.to_mesh()
    vertices = np.asarray(mesh.vert_properties, dtype=np.float64)[:, :3]
    faces = np.asarray(mesh.tri_verts, dtype=np.int64)
    if len(faces) == 0:
        raise DesignError(name, "solid", "came out empty")
    return Part(name, vertices, faces, float(expected_volume))


def extrude_with_socket(name: str, outline: np.ndarray, width: float, socket_ring: np.ndarray,
                        socket_base: float, socket_length: float, expected_volume: float) -> Part:
    """Extrude a checked outline (x, y in mm, CCW) by ``width`` mm along +z and cut a socket.

    The socket is a prism of cross-section ``socket_ring`` (CCW, mm) along +y, from
    y = ``socket_base`` for ``socket_length`` mm, centred at z = width / 2.
    """
    import manifold3d as m3d

    body = m3d.Manifold.extrude(m3d.CrossSection([np.ascontiguousarray(outline)], m3d.FillRule.Positive),
                                width)
    prism = m3d.Manifold.extrude(m3d.CrossSection([np.ascontiguousarray(socket_ring)], m3d.FillRule.Positive),
                                 socket_length)
    # rotate -90 deg about x: the prism's +z axis becomes +y
    cutter = prism.rotate([-90.0, 0.0, 0.0]).translate([0.0, socket_base, width / 2.0])
    return _part_of(name, body - cutter, expected_volume)


def inset_bottom(part: Part, height: float, inset: float) -> Part:
    """Elephant-foot compensation: the part's lowest ``height`` mm shrunk inwards by ``inset`` mm,
    as one closed body (a step inset of the bed-side edges).

    The first layers of a print squash outwards on the bed; drawing them smaller by
    about the squash keeps bed-side edges (and bores) true. The part must be a prism
    over its lowest ``height`` (as every extruded plate is); this is checked. The
    expected volume drops by ``height`` times the area lost in the offset, computed
    independently in 2D (geometry.planar), so the later volume check stays exact.
    """
    import manifold3d as m3d

    if not (np.isfinite(height) and height >= 0):
        raise DesignError("elephant_foot_height", height, "must be >= 0 mm")
    if not (np.isfinite(inset) and inset >= 0):
        raise DesignError("elephant_foot_inset", inset, "must be >= 0 mm")
    if height == 0 or inset == 0:
        return part
    z0, z1 = float(part.bounds[0, 2]), float(part.bounds[1, 2])
    if not 2.0 * height < z1 - z0:
        raise DesignError("elephant_foot_height", height,
                          f"must be < half the {part.name}'s height {z1 - z0:g} mm")
    solid = _manifold_of(part)
    section = solid.slice(z0 + height / 2.0)
    # the foot reaches one more foot height up into the body, so the union overlaps in volume
    # (solids that only touch at a plane stay two shells) and no two faces are coplanar
    below = solid.trim_by_plane((0.0, 0.0, -1.0), -(z0 + 2.0 * height))
    prism_error = abs(below.volume() - section.area() * 2.0 * height)
    if prism_error > 1e-6 * max(1.0, below.volume()):
        raise DesignError(part.name, "elephant foot",
                          f"needs a part that is a prism over its lowest {2 * height:g} mm")
    # the offset leaves vertex pairs a few nanometres apart (slivers once written); 0.1 micron
    # of simplification removes them without changing the area measurably
    foot_section = section.offset(-inset, m3d.JoinType.Miter, 2.0).simplify(1e-4)
    if foot_section.is_empty():
        raise DesignError("elephant_foot_inset", inset, f"removes the whole bottom of the {part.name}")
    foot = m3d.Manifold.extrude(foot_section, 2.0 * height).translate((0.0, 0.0, z0))
    above = solid.trim_by_plane((0.0, 0.0, 1.0), z0 + height)
    result = above + foot
    if len(result.decompose()) != 1:
        raise DesignError(part.name, "elephant foot", "does not come out as one body")
    lost = inset_area_lost(group_rings_by_shell(section.to_polygons()), inset, mitre_limit=2.0)
    return _part_of(part.name, result, part.expected_volume - height * lost, double=True)


def footprint(part: Part) -> list[list[np.ndarray]]:
    """The part seen from above: a list of polygons, each [outer ring CCW, hole rings CW...] (mm).

    Slivers below 0.001 mm^2 (left by the projection where faces were split) are dropped.
    """
    rings = _manifold_of(part).project().to_polygons()
    return group_rings_by_shell([r for r in rings if abs(signed_area(np.asarray(r))) >= 1e-3])


def _manifold_of(part: Part):
    import manifold3d as m3d

    # double precision: float32 would merge vertices a few microns apart into degenerate triangles
    mesh = m3d.Mesh64(vert_properties=np.ascontiguousarray(part.vertices, dtype=np.float64),
                      tri_verts=np.ascontiguousarray(part.faces, dtype=np.uint64))
    solid = m3d.Manifold(mesh)
    if solid.status() != m3d.Error.NoError:
        raise DesignError(part.name, "mesh", f"is not a closed manifold ({solid.status().name})")
    return solid


def section_outline(vertices: np.ndarray, faces: np.ndarray, param: str,
                    z: float | None = None) -> np.ndarray:
    """Outer boundary (N, 2), counter-clockwise, of the mesh's section at height ``z`` (mm).

    ``z`` defaults to the middle of the tooth zone (:func:`tooth_zone_middle`), not of the
    mesh: a hub stands above the teeth. Holes (the bore) are dropped: the outer boundary is
    the ring of largest area.
    """
    import manifold3d as m3d

    vertices = np.asarray(vertices, dtype=np.float64)
    if z is None:
        z = tooth_zone_middle(vertices)
    mesh = m3d.Mesh(vert_properties=np.ascontiguousarray(vertices, dtype=np.float32),
                    tri_verts=np.ascontiguousarray(faces, dtype=np.uint32))
    solid = m3d.Manifold(mesh)
    if solid.status() != m3d.Error.NoError:
        raise DesignError(param, "mesh", f"is not a closed manifold solid "
                          f"(manifold3d: {solid.status().name}); cannot section it")
    rings = [np.asarray(r, dtype=float) for r in solid.slice(float(z)).to_polygons()]
    rings = [r for r in rings if len(r) >= 3]
    if not rings:
        raise DesignError(param, "mesh", f"has no material at z = {z:g} mm (the middle of its tooth zone)")
    areas = [signed_area(r) for r in rings]
    outer = drop_collinear(rings[int(np.argmax(np.abs(areas)))])
    return outer if signed_area(outer) > 0 else outer[::-1]
