"""Stair climbing with circular soles (SPEC §6): sizing, hub kinematics, design check.

Millimetres and radians throughout. Symbols as in SPEC §6: ``b`` crank, ``a = 2 b``
hub-to-crank-axis distance, ``Y1`` strut radius vector, ``Y2`` sole radius, ``alpha`` the
hub angle at which a shoe lands on the next (higher) step.

What "one cycle" means (worked out from the formulas of SPEC §6): the hub turns by a
quarter turn, ``phi`` from the landing angle ``alpha`` to ``alpha + pi/2``, while one
shoe carries it; then the next crank (90 degrees behind) lands in the same pose one
step further. Over that quarter turn the hub moves by

    X01(alpha + pi/2) - X01(alpha) = (a+Y1)(cos a - sin a) - 2b sin 2a + Y2 pi/2   (advance)
    Y01(alpha + pi/2) - Y01(alpha) = 2b cos 2a - (a+Y1)(cos a + sin a)              (rise)

which are exactly the two left-hand sides of SPEC's cycle conditions; the sizing makes
them equal to the run ``l`` and the rise ``h``. Descending, the shoe lands at
``beta = -pi/2 - alpha`` and the cycle is ``phi`` from ``beta`` to ``beta + pi/2 = -alpha``:
since X01 is odd and Y01 even in ``phi``, this is the climb run backwards in ``phi`` and
mirrored, so the hub again advances ``l`` and now drops ``h``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from wheelstep_cli.errors import DesignError, require

KINEMATICS_COLUMNS = ("phi", "X01", "dX01", "d2X01", "Y01", "dY01", "d2Y01")


@dataclass(frozen=True)
class StairDesign:
    """A circular-sole mover: crank ``b``, ``a = 2 b``, strut ``y1``, sole radius ``y2`` (mm)."""

    a: float
    b: float
    y1: float
    y2: float


def _sizing_raw(run, rise, sole_radius, landing):
    """Crank ``b`` and strut ``Y1`` solving SPEC §6's cycle conditions with a = 2b (arrays ok).

    The two conditions are linear in ``u = a + Y1`` and ``b``; their determinant is
    ``-2 (sin 3 alpha - cos 3 alpha)``, zero at alpha = 15 deg + k 60 deg (including
    the -45 deg SPEC names). Returns ``(b, y1, det)``; at a zero determinant b and y1 are inf/nan.
    """
    al = np.asarray(landing, dtype=float)
    c, s = np.cos(al), np.sin(al)
    s2, c2 = np.sin(2 * al), np.cos(2 * al)
    lhs = run - sole_radius * np.pi / 2   # (a+Y1)(c - s) - 2b s2 = l - Y2 pi/2
    det = 2.0 * (s2 * (c + s) - c2 * (c - s))   # = 2 (sin 3 alpha - cos 3 alpha)
    with np.errstate(divide="ignore", invalid="ignore"):
        b = (-lhs * (c + s) - rise * (c - s)) / det          # SPEC §6's b, Cramer's rule
        u = -(2 * c2 * lhs + 2 * s2 * rise) / det            # a + Y1 (no extra 1/(c+s))
    return b, u - 2 * b, det


def singular_landing(landing) -> np.ndarray:
    """True where the sizing equations are singular (alpha = 15 deg + k 60 deg)."""
    al = np.asarray(landing, dtype=float)
    return np.abs(np.sin(3 * al) - np.cos(3 * al)) < 1e-9


def size_for_stair(run: float, rise: float, sole_radius: float, landing: float) -> StairDesign:
    """Crank, strut and ``a = 2b`` that climb a stair of ``run`` x ``rise`` (mm), landing at ``landing`` rad.

    Raises DesignError where the equations are singular or the sizes come out negative
    (no physical meaning).
    """
    require(run > 0, "run", run, "must be > 0 mm")
    require(rise > 0, "rise", rise, "must be > 0 mm")
    require(sole_radius > 0, "sole-radius", sole_radius, "must be > 0 mm")
    deg = round(float(np.degrees(landing)), 6)
    if singular_landing(landing):
        raise DesignError("landing-angle", deg,
                          "the sizing equations are singular here (alpha = 15 + k*60 deg)")
    b, y1, _ = _sizing_raw(run, rise, sole_radius, landing)
    b, y1 = float(b), float(y1)
    # the stair and the sole share the blame with the landing angle
    stair = {"run": run, "rise": rise, "sole_radius": sole_radius}
    if not b > 0:
        raise DesignError("landing-angle", deg, f"gives crank b = {b:.1f} mm <= 0 for this stair "
                          "and sole (no physical meaning)").tied_to(stair)
    if not y1 > 0:
        raise DesignError("landing-angle", deg, f"gives strut Y1 = {y1:.1f} mm <= 0 for this stair "
                          "and sole (no physical meaning)").tied_to(stair)
    return StairDesign(a=2 * b, b=b, y1=y1, y2=float(sole_radius))


def sizing_sweep(run: float, rise: float, landings, sole_radii) -> list[dict]:
    """Sizing over a grid of landing angles (rad) and sole radii (mm).

    Each row: ``landing`` (rad), ``sole_radius``, ``status`` ("ok", "singular",
    "negative b", "negative Y1") and ``b``, ``y1``, ``a`` (None unless ok).
    """
    al, y2 = np.meshgrid(np.asarray(landings, float), np.asarray(sole_radii, float), indexing="ij")
    b, y1, _ = _sizing_raw(run, rise, y2, al)
    sing = singular_landing(al)
    rows = []
    for i, j in np.ndindex(al.shape):
        if sing[i, j]:
            status = "singular"
        elif not b[i, j] > 0:
            status = "negative b"
        elif not y1[i, j] > 0:
            status = "negative Y1"
        else:
            status = "ok"
        ok = status == "ok"
        rows.append({"landing": float(al[i, j]), "sole_radius": float(y2[i, j]), "status": status,
                     "b": float(b[i, j]) if ok else None, "y1": float(y1[i, j]) if ok else None,
                     "a": float(2 * b[i, j]) if ok else None})
    return rows


def hub_kinematics(design: StairDesign, phi, landing: float) -> np.ndarray:
    """SPEC §6 hub kinematics at hub angles ``phi`` (rad); rows of KINEMATICS_COLUMNS.

    X01 is measured from the landing angle ``landing``; Y01 is SPEC's absolute
    expression. Derivatives are per radian of hub angle (mm/rad, mm/rad^2).
    """
    phi = np.asarray(phi, dtype=float)
    u, b, y2 = design.a + design.y1, design.b, design.y2

    def x(p):
        return u * np.sin(p) + b * np.sin(2 * p) + y2 * p

    cols = [
        phi,
        x(phi) - x(landing),
        u * np.cos(phi) + 2 * b * np.cos(2 * phi) + y2,
        -u * np.sin(phi) - 4 * b * np.sin(2 * phi),
        u * np.cos(phi) - b * np.cos(2 * phi) + y2,
        -u * np.sin(phi) + 2 * b * np.sin(2 * phi),
        -u * np.cos(phi) + 4 * b * np.cos(2 * phi),
    ]
    return np.stack(cols, axis=-1)


def descent_landing(landing: float) -> float:
    """Descending landing angle beta = -pi/2 - alpha (rad)."""
    return -np.pi / 2 - landing


def cycle_angles(landing: float, step: float) -> np.ndarray:
    """Hub angles of one cycle, ``landing`` to ``landing + pi/2`` inclusive, about ``step`` apart."""
    n = max(2, int(round((np.pi / 2) / step)) + 1)
    return landing + np.linspace(0.0, np.pi / 2, n)


def cycle_motion(design: StairDesign, landing) -> tuple[np.ndarray, np.ndarray]:
    """Hub advance and rise over one cycle (``landing`` to ``landing + pi/2``), mm, arrays ok."""
    al = np.asarray(landing, dtype=float)
    start = hub_kinematics(design, al, al)
    end = hub_kinematics(design, al + np.pi / 2, al)
    return end[..., 1] - start[..., 1], end[..., 4] - start[..., 4]


def hub_path(design: StairDesign, landing: float, run: float, rise: float,
             cycles: int, per_cycle: int = 91) -> np.ndarray:
    """Hub centre over ``cycles`` successive steps, (N, 2) mm: cycle k shifted by (k run, k rise).

    Cycle k is carried by a shoe standing on step k, so its hub height is
    ``k rise + Y01`` above the first tread (sign of rise < 0 for a descent).
    """
    phi = landing + np.linspace(0.0, np.pi / 2, per_cycle)
    kin = hub_kinematics(design, phi, landing)
    parts = [np.column_stack([kin[:, 1] + k * run, kin[:, 4] + k * rise]) for k in range(cycles)]
    return np.concatenate(parts)


@dataclass(frozen=True)
class ClimbCheck:
    """Whether ``design`` climbs a stair, and the numbers that say why (mm, rad)."""

    climbs: bool
    landing_for_rise: tuple       # landing angles whose cycle rises exactly ``rise``
    advance_at_rise: tuple        # the advance per cycle at each of those
    landing_for_run: tuple        # landing angles whose cycle advances exactly ``run``
    rise_at_run: tuple            # the rise per cycle at each of those
    best_landing: float           # landing angle closest to (run, rise)
    best_advance: float
    best_rise: float
    tolerance: float


def _roots(f, lo=-np.pi, hi=np.pi, n=7201):
    from scipy.optimize import brentq

    grid = np.linspace(lo, hi, n)
    vals = f(grid)
    idx = np.nonzero(np.sign(vals[:-1]) * np.sign(vals[1:]) < 0)[0]
    roots = [brentq(f, grid[i], grid[i + 1], xtol=1e-13) for i in idx]
    roots += [float(g) for g, v in zip(grid[:-1], vals[:-1]) if v == 0.0]
    return sorted(roots)


def check_climb(design: StairDesign, run: float, rise: float, tolerance: float = 1.0) -> ClimbCheck:
    """Search every landing angle for one whose cycle advances ``run`` and rises ``rise``.

    One cycle's advance and rise are fixed by the design and the landing angle alone
    (SPEC §6), so a stair is climbable only if a single landing angle gives both within
    ``tolerance`` mm.
    """
    from scipy.optimize import minimize_scalar

    require(design.b > 0, "b", design.b, "must be > 0 mm")
    require(design.y2 > 0, "y2", design.y2, "must be > 0 mm")

    def miss(al):
        adv, ris = cycle_motion(design, al)
        return np.hypot(adv - run, ris - rise)

    rise_roots = _roots(lambda al: cycle_motion(design, al)[1] - rise)
    run_roots = _roots(lambda al: cycle_motion(design, al)[0] - run)
    grid = np.linspace(-np.pi, np.pi, 7201)
    k = int(np.argmin(miss(grid)))
    step = grid[1] - grid[0]
    best = minimize_scalar(lambda al: float(miss(al)), bounds=(grid[k] - step, grid[k] + step),
                           method="bounded", options={"xatol": 1e-12})
    best_al = float(best.x) if best.fun <= miss(grid[k]) else float(grid[k])
    best_al = float(np.angle(np.exp(1j * best_al)))
    adv, ris = cycle_motion(design, best_al)
    return ClimbCheck(
        climbs=bool(np.hypot(adv - run, ris - rise) <= tolerance),
        landing_for_rise=tuple(rise_roots),
        advance_at_rise=tuple(float(cycle_motion(design, r)[0]) for r in rise_roots),
        landing_for_run=tuple(run_roots),
        rise_at_run=tuple(float(cycle_motion(design, r)[1]) for r in run_roots),
        best_landing=best_al, best_advance=float(adv), best_rise=float(ris), tolerance=tolerance,
    )
