"""The walking legs ``wheelstep linkage`` knows (SPEC §7), lengths in mm, angles in rad."""

from __future__ import annotations

import numpy as np

from wheelstep_cli.mechanism.linkage.solver import Attached, Crank, Dyad, Fixed, Linkage


def four_bar_paper() -> Linkage:
    """SPEC §7's paper four-bar leg, metres converted to mm."""
    l1, l2, l3, l4, beta = 270.0, 638.0, 650.0, 654.0, np.radians(70.8)
    return Linkage(
        name="four-bar",
        description="source paper four-bar leg (SPEC §7): crank OK 270, rocker O1L 638, coupler KL 650, "
                    "bent arm LH 654 mm at 70.8 deg to the coupler, O1 = (567, 615) mm (the paper runs it at 27 rpm)",
        steps=(Fixed("O", 0.0, 0.0), Fixed("O1", 567.0, 615.0), Crank("K", "O", l1),
               Dyad("L", "K", l3, "O1", l2, branch=-1),
               # H = L - l4 (cos(g3 + beta), sin(g3 + beta)), g3 the direction K -> L
               Attached("H", "L", "K", l4, beta)),
        foot="H", ground=-1, rpm=27.0,
        links=(("O", "K"), ("K", "L"), ("O1", "L"), ("L", "H")),
    )


def six_bar_source() -> Linkage:
    """SPEC §7's six-bar topology with numbers chosen here (SPEC gives none): see description."""
    beta1, beta2, gamma = np.radians(48.0), np.radians(26.8), np.radians(153.6)
    return Linkage(
        name="six-bar",
        description="six-bar leg with SPEC §7's topology (crank B-O-N, links BM and NA, bent rocker "
                    "O1-M-D, bent support arm D-A-H). SPEC gives no numbers for it: these were chosen "
                    "here by a small search for a closed full-turn loop with a flat low stretch, at the "
                    "four-bar's scale (illustrative, not the source machine): OB = ON = 150 with N "
                    "lagging B by 48 deg, BM 641, O1 = (-627, 488), O1M 340, MD 135 at 26.8 deg from "
                    "M->O1, NA 511, DA 467, AH 420 at 153.6 deg from A->D (mm)",
        steps=(Fixed("O", 0.0, 0.0), Fixed("O1", -627.0, 488.0),
               Crank("B", "O", 150.0), Crank("N", "O", 150.0, phase=-beta1),
               Dyad("M", "B", 641.0, "O1", 340.0, branch=1),
               Attached("D", "M", "O1", 135.0, beta2),
               Dyad("A", "N", 511.0, "D", 467.0, branch=1),
               Attached("H", "A", "D", 420.0, gamma)),
        foot="H", ground=-1, rpm=27.0,
        links=(("O", "B"), ("O", "N"), ("B", "M"), ("O1", "M"), ("M", "D"), ("N", "A"), ("D", "A"), ("A", "H")),
    )


def chebyshev_lambda(unit: float = 1.0) -> Linkage:
    """Chebyshev's lambda linkage: crank 1, ground 2, rocker 2.5, coupler 2.5, foot at 5 (x unit).

    Frame: crank pivot A = (0, 0), rocker pivot D = (2, 0) (x unit); the coupler B-C runs
    from the crank tip B through the rocker joint C (|BC| = 2.5) to the foot F, |BF| = 5.
    The foot traces its nearly straight segment along y = 4 unit for crank angles
    90..270 deg and bulges to y = 4.9 unit on the return: the straight segment is the
    lowest level of the path, so the ground side is -y (as in Chebyshev's plantigrade
    machine, where the path is carried down to the foot by a parallel linkage).
    """
    u = float(unit)
    return Linkage(
        name="chebyshev",
        description=f"Chebyshev lambda linkage, unit {u:g} mm: crank AB 1, ground AD 2, rocker DC 2.5, "
                    "coupler BC 2.5 extended to foot F at BF 5; A = (0,0), D = (2,0); the straight "
                    "segment is y = 4 (the path's lowest level)",
        steps=(Fixed("A", 0.0, 0.0), Fixed("D", 2 * u, 0.0), Crank("B", "A", 1 * u),
               Dyad("C", "B", 2.5 * u, "D", 2.5 * u, branch=1),
               Attached("F", "B", "C", 5 * u, 0.0)),
        foot="F", ground=-1, rpm=60.0,
        links=(("A", "B"), ("D", "C"), ("B", "F")),
    )


def jansen_leg() -> Linkage:
    """Theo Jansen's leg with his published "holy numbers" (a..m), lengths as mm.

    Frame: crank axle at (0, 0), crank m = 15; the fixed pivot is at (-a, -l) =
    (-38, -7.8). The leg hangs toward -y.
    """
    a, b, c, d, e, f, g, h, i, j, k, l, m = (38.0, 41.5, 39.3, 40.1, 55.8, 39.4, 36.7, 65.7,
                                             49.0, 50.0, 61.9, 7.8, 15.0)
    return Linkage(
        name="jansen",
        description="Theo Jansen's leg, holy numbers a=38 b=41.5 c=39.3 d=40.1 e=55.8 f=39.4 g=36.7 "
                    "h=65.7 i=49 j=50 k=61.9 l=7.8 m=15 (mm); crank at (0,0), pivot at (-a, -l)",
        steps=(Fixed("O", 0.0, 0.0), Fixed("P", -a, -l), Crank("M", "O", m),
               Dyad("U", "M", j, "P", b, branch=-1),       # upper joint, above the pivot
               Dyad("W", "P", d, "U", e, branch=1),        # outer corner of triangle b-d-e
               Dyad("R", "M", k, "P", c, branch=1),        # lower joint, below the pivot
               Dyad("K", "W", f, "R", g, branch=-1),       # knee
               Dyad("F", "K", h, "R", i, branch=-1)),      # foot, corner of triangle g-h-i
        foot="F", ground=-1, rpm=60.0,
        links=(("O", "M"), ("M", "U"), ("P", "U"), ("P", "W"), ("U", "W"), ("M", "R"), ("P", "R"),
               ("W", "K"), ("K", "R"), ("K", "F"), ("R", "F")),
    )


PRESETS = {"four-bar": four_bar_paper, "six-bar": six_bar_source,
           "chebyshev": lambda: chebyshev_lambda(50.0), "jansen": jansen_leg}


def four_bar(l1=None, l2=None, l3=None, l4=None, beta_deg=None, o1=None) -> Linkage:
    """The paper four-bar with any of its numbers replaced: crank ``l1``, rocker ``l2``,
    coupler ``l3``, arm ``l4`` (mm), arm angle ``beta_deg`` (deg, as given), rocker pivot
    ``o1`` = (x, y) mm; None keeps the paper's."""
    from wheelstep_cli.errors import require

    base = four_bar_paper()
    steps = {s.name: s for s in base.steps}
    paper = (steps["K"].length, steps["L"].rq, steps["L"].rp, steps["H"].length,
             float(np.degrees(steps["H"].angle)), steps["O1"].x, steps["O1"].y)
    given = (l1, l2, l3, l4, beta_deg, *((None, None) if o1 is None else o1))
    numbers = tuple(own if value is None else value for value, own in zip(given, paper))
    if numbers == paper:
        return base         # the paper's own numbers, typed: the paper's leg
    l1, l2, l3, l4, beta, ox, oy = numbers
    for name, value in (("l1", l1), ("l2", l2), ("l3", l3), ("l4", l4)):
        require(value > 0, name, value, "link length must be > 0 mm")
    # an angle past a full turn names the same arm as its remainder: taken as typed, 400 would
    # silently be 40
    require(-360 < beta < 360, "beta", beta, "must be in (-360, 360) deg")
    return Linkage(
        name="four-bar",
        description=f"four-bar leg (SPEC §7): crank OK {l1:g}, rocker O1L {l2:g}, coupler KL {l3:g}, "
                    f"bent arm LH {l4:g} mm at {beta:g} deg, O1 = ({ox:g}, {oy:g}) mm",
        steps=(Fixed("O", 0.0, 0.0), Fixed("O1", ox, oy), Crank("K", "O", l1),
               Dyad("L", "K", l3, "O1", l2, branch=steps["L"].branch),
               Attached("H", "L", "K", l4, float(np.radians(beta)))),
        foot="H", ground=-1, rpm=base.rpm, links=base.links)
