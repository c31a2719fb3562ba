"""The sole table ``wheelstep shoe`` prints (SPEC §2)."""

from __future__ import annotations

import numpy as np

from wheelstep_cli.mechanism.shoe import (ShoeDesign, contact_angles, sole_curvature_radius,
                                          sole_polar, sole_profile)


def sole_table(design: ShoeDesign, count: int = 7) -> np.ndarray:
    """Rows (phi deg, X, Y, rho, alpha deg, R) at ``count`` hub angles over the contact, mm."""
    phi = contact_angles(count)
    xy = sole_profile(design, phi)
    rho, alpha = sole_polar(design, phi)
    return np.column_stack([np.degrees(phi), xy, rho, np.degrees(alpha),
                            sole_curvature_radius(design, phi)])
