"""What ``wheelstep linkage`` computes and reports: a leg (a preset, or the paper four-bar
with replaced numbers), re-branched and scaled, solved over one crank turn, and its gait.

Lengths mm, speeds mm/s, angles rad inside; the report gives crank angles in degrees.
"""

from __future__ import annotations

import math

from dataclasses import dataclass, field

import numpy as np

from wheelstep_cli.errors import DesignError, require, rounded_down
from wheelstep_cli.mechanism.linkage.gait import Gait, gait
from wheelstep_cli.mechanism.linkage.presets import PRESETS, four_bar
from wheelstep_cli.mechanism.linkage.solver import Dyad, Linkage, Solution, cycle_angles, solve

#: The numbers of the paper four-bar a request may replace (see :func:`four_bar`).
FOUR_BAR_KEYS = ("l1", "l2", "l3", "l4", "beta_deg", "o1")
#: The option a four-bar number is given by, where its name differs (a refusal names the option).
OPTION_OF = {"beta_deg": "beta"}


@dataclass(frozen=True)
class LinkageRequest:
    """Which leg and how to run it: ``preset`` name, crank speed (rpm; None: the preset's),
    samples per turn, length ``scale``, dyad ``branches`` (name -> +1/-1), support tolerance
    (mm; None: 2 % of the lift), replaced four-bar numbers (:data:`FOUR_BAR_KEYS`) and the
    crank-angle step of the printed path (deg, as given)."""

    preset: str = "four-bar"
    rpm: float | None = None
    samples: int = 720
    scale: float = 1.0
    branches: dict = field(default_factory=dict)
    ground_tol: float | None = None
    four_bar: dict = field(default_factory=dict)
    step_deg: float = 15.0


#: Range of --scale, the factor on every length of a leg.
MIN_SCALE, MAX_SCALE = 1e-3, 1e3


def check_sampling(samples: int, scale: float, gif_frames: int, step_deg: float) -> None:
    """Raise DesignError for a sample count, scale, GIF frame count or table step out of range."""
    require(36 <= samples <= 100000, "samples", samples, "must be in [36, 100000]")
    # a thousandth to a thousand times the presets' lengths (about 2 mm to 600 m of crank):
    # beyond, the printed mm and m/s figures show nothing but zeros or nonsense speeds
    require(MIN_SCALE <= scale <= MAX_SCALE, "scale", scale, f"must be in [{MIN_SCALE:g}, {MAX_SCALE:g}]")
    require(2 <= gif_frames <= 720, "gif-frames", gif_frames, "must be in [2, 720]")
    require(0 < step_deg <= 180, "step", step_deg, "must be in (0, 180] deg")


#: Crank-angle step (deg) of the printed table when none is given.
DEFAULT_STEP = 15.0


def default_step(samples: int) -> float:
    """The table's step (deg) when none is given: the whole multiple of the ``samples`` crank
    angles' spacing (360 / samples) nearest :data:`DEFAULT_STEP` (the larger of two as near),
    at least one spacing."""
    spacing = 360.0 / samples
    return max(1, math.floor(DEFAULT_STEP / spacing + 0.5)) * spacing


def require_step_on_samples(step_deg: float, samples: int) -> None:
    """Refuse (DesignError) a table step (deg) that is not a whole number of the ``samples``
    crank angles' spacing: the table lists sampled angles, so such a step would be rounded."""
    spacing = 360.0 / samples
    count = step_deg / spacing
    # within the digits the multiples are printed with (10), so a printed one is taken
    if abs(count - round(count)) <= 1e-8 * max(1.0, count) and round(count) >= 1:
        return
    below, above = max(1, int(np.floor(count))) * spacing, int(np.ceil(count)) * spacing
    choices = f"{below:.10g} or {above:.10g}" if above != below else f"{above:.10g}"
    raise DesignError("step", step_deg, f"must be a whole multiple of the crank angles' spacing "
                                        f"{spacing:.10g} deg (360 / --samples {samples}): {choices}")


def build_leg(request: LinkageRequest) -> Linkage:
    """The leg of ``request``: preset or custom four-bar, its branches set, scaled."""
    custom = {k: v for k, v in request.four_bar.items() if v is not None}
    if custom and request.preset != "four-bar":
        # named as the option that would do nothing: the preset has links of its own
        name = next(iter(custom))
        value = custom[name]
        shown = ",".join(f"{v:g}" for v in value) if isinstance(value, tuple) else value   # as typed: X,Y
        raise DesignError(OPTION_OF.get(name, name), shown, f"shapes the four-bar only (--l1..--l4, --beta, --o1), "
                                              f"not the {request.preset} preset: drop it or use --preset four-bar")
    if custom:
        leg = four_bar(**custom)
    else:
        leg = PRESETS[request.preset]()
    dyads = {s.name for s in leg.steps if isinstance(s, Dyad)}
    for name in request.branches:
        require(name in dyads, "branch", name,
                f"not a dyad joint of {leg.name} (those are {', '.join(sorted(dyads))})")
    leg = leg.with_branches(request.branches)
    return leg.scaled(request.scale) if request.scale != 1.0 else leg


@dataclass(frozen=True)
class LinkageStudy:
    """A solved leg at ``rpm``: its solution over one turn and its gait."""

    request: LinkageRequest
    leg: Linkage
    rpm: float
    solution: Solution
    gait: Gait


def linkage_study(request: LinkageRequest) -> LinkageStudy:
    """Build, solve and analyse the leg of ``request``; DesignError names what is impossible."""
    leg = build_leg(request)
    rpm = leg.rpm if request.rpm is None else request.rpm
    require(rpm > 0, "rpm", rpm, "must be > 0")
    if request.ground_tol is not None:
        require(request.ground_tol > 0, "ground-tol", request.ground_tol, "must be > 0 mm")
    theta = cycle_angles(request.samples)
    try:
        sol = solve(leg, theta)
    except DesignError as err:
        raise _for_the_inputs(err, request) from None
    probe = gait(leg, sol, rpm)
    # a band as deep as the lift holds the whole path: every crank angle would be support
    require(request.ground_tol is None or request.ground_tol < probe.lift, "ground-tol", request.ground_tol,
            f"must be < the foot's lift {rounded_down(probe.lift, 1)} mm (within the lift the whole path is "
            "support)")
    tol = 0.02 * probe.lift if request.ground_tol is None else request.ground_tol
    return LinkageStudy(request, leg, rpm, sol, gait(leg, sol, rpm, tol))


def _for_the_inputs(err: DesignError, request: LinkageRequest) -> DesignError:
    """A solver error (it names a crank angle, which nobody types) restated for each input
    that shapes the leg, so the command line names the one the user gave: a replaced
    four-bar number first, then the branches, the scale, the preset."""
    if err.param != "crank-angle":
        return err
    why = f"the leg cannot turn its crank fully with it: at crank angle {err.shown_value} deg, {err.limit}"
    alternatives = {OPTION_OF.get(k, k): (_shown(v), why) for k, v in request.four_bar.items()
                    if v is not None}
    if request.branches:
        alternatives["branch"] = (",".join(f"{k}={v:+d}" for k, v in request.branches.items()), why)
    alternatives["scale"] = (request.scale, why)
    alternatives["preset"] = (request.preset, why)
    return DesignError(err.param, err.value, err.limit, alternatives)


def _shown(value) -> object:
    """A four-bar number as the user gave it (a pivot 'x,y' as typed)."""
    return ",".join(f"{c:g}" for c in value) if isinstance(value, tuple) else value


def _stats(values: np.ndarray) -> dict:
    return {"min": values.min(), "mean": values.mean(), "max": values.max()}


def path_rows(study: LinkageStudy) -> list[dict]:
    """The foot path every ``step_deg`` of crank angle: position, velocity, speed, phase."""
    g, theta = study.gait, study.solution.theta
    every = max(1, int(round(np.radians(study.request.step_deg) / (theta[1] - theta[0]))))
    return [{"crank_deg": float(np.degrees(theta[k])), "x_mm": g.foot[k, 0], "y_mm": g.foot[k, 1],
             "vx_mm_s": g.velocity[k, 0], "vy_mm_s": g.velocity[k, 1], "speed_mm_s": g.speed[k],
             "support": bool(g.support[k])} for k in range(0, study.request.samples, every)]


def linkage_report(study: LinkageStudy) -> dict:
    """Leg, branches, loop residual, stride, lift, duty factor, speeds and the sampled path."""
    g, sol = study.gait, study.solution
    return {
        "preset": study.leg.name, "description": study.leg.description, "scale": study.request.scale,
        "rpm": study.rpm,
        "samples": study.request.samples, "table_step_deg": study.request.step_deg,
        "branches": sol.branches, "loop_residual_mm": sol.residual,
        "stride_mm": g.stride, "lift_mm": g.lift, "duty_factor": g.duty_factor,
        "ground_level_mm": g.ground_level, "ground_tol_mm": g.ground_tol,
        "foot_speed_mm_s": _stats(g.speed),
        "body_speed_mm_s": _stats(g.body_speed[g.support]),
        "path": path_rows(study),
    }


def path_table(study: LinkageStudy) -> tuple[list[str], np.ndarray, list[str]]:
    """Header, rows and column formats of the foot path at every sample (deg, mm, mm/s to six
    decimals; support as 0 or 1)."""
    g = study.gait
    header = ["crank_deg", "x_mm", "y_mm", "vx_mm_s", "vy_mm_s", "speed_mm_s", "support"]
    return header, np.column_stack([np.degrees(study.solution.theta), g.foot, g.velocity, g.speed,
                                    g.support]), ["%.6f"] * (len(header) - 1) + ["%d"]
