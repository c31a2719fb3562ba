"""What ``wheelstep stairs`` computes and reports (SPEC §6): a sized or given design against a
stair, with climb and descent kinematics and the climb check; or the sizing sweep.

Lengths mm, angles rad inside; the landing angle and table step are kept in degrees as the
user gave them, since the report echoes them back.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from wheelstep_cli.errors import DesignError, require
from wheelstep_cli.mechanism import stairs as st

UNITS = {"phi": "deg", "X01": "mm", "Y01": "mm", "dX01": "mm/rad", "dY01": "mm/rad",
         "d2X01": "mm/rad^2", "d2Y01": "mm/rad^2"}


@dataclass(frozen=True)
class StairRequest:
    """A stair (run x rise, mm), the landing angle and table step (deg, as given), and either
    the sole radius to size a design for (mm) or a ``design`` to check within ``tol`` mm."""

    run: float = 300.0
    rise: float = 150.0
    sole_radius: float = 70.0
    landing_angle_deg: float = -90.0
    step_deg: float = 5.0
    design: st.StairDesign | None = None
    tol: float = 1.0

    @property
    def checking(self) -> bool:
        return self.design is not None


def check_stair(run: float, rise: float, step_deg: float) -> None:
    """Raise DesignError unless run and rise (mm) are > 0 and the step is 0.01..45 deg and
    divides the cycle's 90 deg (the tables list the cycle's ends, so another step would be
    spread to one that does)."""
    require(run > 0, "run", run, "must be > 0 mm")
    require(rise > 0, "rise", rise, "must be > 0 mm")
    require(0.01 <= step_deg <= 45, "step", step_deg, "must be in [0.01, 45] deg")
    count = 90.0 / step_deg
    # within the digits the steps are printed with (10), so a printed one is taken
    if abs(count - round(count)) > 1e-8 * count:
        fine, coarse = 90.0 / int(np.ceil(count)), 90.0 / int(np.floor(count))
        raise DesignError("step", step_deg, f"must divide the cycle's 90 deg into whole steps: "
                                            f"{fine:.10g} or {coarse:.10g}")


def given_design(a, b, y1, y2, tol: float) -> st.StairDesign | None:
    """The design to check from its four sizes (mm), or None when none is given; all four
    must then be given and > 0, and ``tol`` > 0 mm."""
    given = {"a": a, "b": b, "y1": y1, "y2": y2}
    if all(v is None for v in given.values()):
        return None
    for name, value in given.items():
        require(value is not None, name, "missing", "a design check needs all of --a --b --y1 --y2")
        require(value > 0, name, value, "must be > 0 mm")
    require(tol > 0, "tol", tol, "must be > 0 mm")
    return st.StairDesign(a=a, b=b, y1=y1, y2=y2)


@dataclass(frozen=True)
class StairStudy:
    """The design, its climb and descent kinematics (rows of ``KINEMATICS_COLUMNS``), the
    motion per cycle (mm) and, for a given design, the climb check."""

    request: StairRequest
    design: st.StairDesign
    landing: float            # rad
    descent_landing: float    # rad
    climb: np.ndarray
    descent: np.ndarray
    advance: float
    rise: float
    check: st.ClimbCheck | None


def stair_study(request: StairRequest) -> StairStudy:
    """Size (or take) the design, and compute its kinematics and, when checking, the climb."""
    alpha = float(np.radians(request.landing_angle_deg))
    design = request.design
    if design is None:
        design = st.size_for_stair(request.run, request.rise, request.sole_radius, alpha)
    beta = st.descent_landing(alpha)
    step = np.radians(request.step_deg)
    climb = st.hub_kinematics(design, st.cycle_angles(alpha, step), alpha)
    descent = st.hub_kinematics(design, st.cycle_angles(beta, step), beta)
    adv, ris = st.cycle_motion(design, alpha)
    check = st.check_climb(design, request.run, request.rise, request.tol) if request.checking else None
    return StairStudy(request, design, alpha, beta, climb, descent, adv, ris, check)


def kinematics_rows(kin: np.ndarray) -> list[dict]:
    """Rows of the kinematics table as dicts; ``phi`` in degrees; no negative zeros (a
    derivative of 0 at phi = 0 came out as -0.0)."""
    out = []
    for row in kin:
        item = dict(zip(st.KINEMATICS_COLUMNS, (float(v) + 0.0 for v in row)))
        item["phi"] = float(np.degrees(row[0]))
        out.append(item)
    return out


def check_record(check: st.ClimbCheck, tol: float) -> dict:
    """The climb check as plain data, angles in degrees."""
    return {
        "climbs": check.climbs, "tolerance_mm": tol,
        "landing_for_rise_deg": [float(np.degrees(v)) for v in check.landing_for_rise],
        "advance_at_rise_mm": list(check.advance_at_rise),
        "landing_for_run_deg": [float(np.degrees(v)) for v in check.landing_for_run],
        "rise_at_run_mm": list(check.rise_at_run),
        "best_landing_deg": float(np.degrees(check.best_landing)),
        "best_advance_mm": check.best_advance, "best_rise_mm": check.best_rise,
    }


def stair_report(study: StairStudy) -> dict:
    """Sizes, stair, motion per cycle and both kinematics tables (and the check), plain data."""
    d, req = study.design, study.request
    report = {"b_mm": d.b, "y1_mm": d.y1, "a_mm": d.a, "y2_mm": d.y2,
              "run_mm": req.run, "rise_mm": req.rise, "landing_angle_deg": req.landing_angle_deg,
              "descent_landing_angle_deg": float(np.degrees(study.descent_landing)),
              "advance_per_cycle_mm": float(study.advance), "rise_per_cycle_mm": float(study.rise),
              "units": dict(UNITS),
              "climb": kinematics_rows(study.climb), "descent": kinematics_rows(study.descent)}
    if study.check is not None:
        report["check"] = check_record(study.check, req.tol)
    return report


def sweep_report(run: float, rise: float, rows: list[dict]) -> dict:
    """The sizing sweep (rows of :func:`~wheelstep_cli.mechanism.stairs.sizing_sweep`) as plain
    data, landing angles in degrees."""
    return {"run_mm": run, "rise_mm": rise, "sweep": [
        {"landing_angle_deg": round(float(np.degrees(r["landing"])), 9),
         "sole_radius_mm": r["sole_radius"], "status": r["status"], "b_mm": r["b"],
         "y1_mm": r["y1"], "a_mm": r["a"]} for r in rows]}
