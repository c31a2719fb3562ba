"""Reading back what `--step` writes (needs the cad extra)."""

from __future__ import annotations


def step_volume(solid) -> float:
    """Volume (mm3) of a build123d solid by adaptive Gauss-Kronrod integration.

    OpenCASCADE's default rule (``BRepGProp.VolumeProperties``, build123d's ``.volume``) is
    0.1-12 % off on extruded B-spline side faces with hundreds of knots (benchmarks/results.md,
    "STEP of a generated pair as fitted B-splines"); this one agrees with the polygon's area
    times the thickness to 1e-6."""
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps

    props = GProp_GProps()
    BRepGProp.VolumePropertiesGK_s(solid.wrapped, props, 1e-6)
    return props.Mass()
