"""``mesh-check`` of two written gear meshes: inputs checked, outlines read, the check run
and summarised, the optional plot rendered (SPEC §10)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

import numpy as np

from wheelstep_cli.errors import DesignError, require
from wheelstep_cli.gears.meshing import MeshingReport
from wheelstep_cli.parts.bound_figures import bounds_verdict
from wheelstep_cli.parts.gear_pair import (GearPairSpec, design_law, generation_law, installed_distance,
                                          law_record)


MAX_SAMPLES = 20000     # poses over one period: 13 x the default 1536
#: How far (a fraction of the centre distance) the two outlines' pitch radii may add up away
#: from it: a pinion and its wheel roll on pitch curves whose radii add to the distance.
SIZE_SLACK = 0.2

@dataclass(frozen=True)
class WrittenPairCheck:
    """What to check: two mesh specs (``FILE.stl``, ``FILE.3mf[:NAME]``), the design whose
    law they follow, the pose count, the mesh window (mm, None: automatic), the plot path."""

    pinion: str
    wheel: str
    spec: GearPairSpec
    samples: int | None
    window: float | None = None
    plot: Path | None = None

    def validate(self) -> None:
        """Raise DesignError for a distance, pose count, window or plot name that cannot work."""
        dist = installed_distance(self.spec)
        require(dist > 0, "distance", dist, "must be > 0 mm")
        require_sampling(self.samples, self.window, self.plot)


def require_sampling(samples: int | None, window: float | None, plot: Path | None) -> None:
    """Raise DesignError for a pose count (per law period), window (mm) or plot name that
    cannot work, before anything is read."""
    # each pose sections and intersects both outlines: the count bounds the run time
    require(samples is None or 16 <= samples <= MAX_SAMPLES, "samples", samples,
            f"must be in [16, {MAX_SAMPLES}]")
    require(window is None or window > 0, "window", window, "must be > 0 mm")
    if plot is not None:
        require(plot.suffix.lower() == ".png", "plot", str(plot), "must be a .png file")


def read_written_pair(check: WrittenPairCheck) -> tuple[np.ndarray, np.ndarray]:
    """Check the inputs and read both meshes' sections half-way up their teeth (mm, own frames)."""
    from wheelstep_cli.formats.mesh_read import read_outline

    law = design_law(check.spec)
    check.validate()
    outlines = (read_outline(check.pinion, "pinion", default_name="pinion"),
                read_outline(check.wheel, "wheel", default_name="wheel"))
    require_written_pair(check, outlines, law)
    return outlines


def require_written_pair(check: WrittenPairCheck, outlines: tuple[np.ndarray, np.ndarray], law) -> None:
    """Refuse (DesignError naming the file or option to change) two mesh sections (mm, own
    frames, half-way up the tooth zone) that are not the pinion and the wheel of ``check``'s
    design under ``law``: sizes that do not add to the distance, the two swapped, teeth the
    law does not pair, too few poses per tooth. Checked before any pose is run."""
    from wheelstep_cli.gears.meshing.check import radius_by_area

    for outline, name, file in zip(outlines, ("pinion", "wheel"), (check.pinion, check.wheel)):
        require_about_its_axis(outline, name, file)
    radii = tuple(radius_by_area(o) for o in outlines)
    require_a_pair(radii, installed_distance(check.spec), (check.pinion, check.wheel), law)
    require_pinion_first(radii, law, check.pinion)
    teeth = _teeth_under_the_law(outlines, law, check)
    require_poses_per_tooth(check.samples, teeth, law)


def _teeth_under_the_law(outlines: tuple[np.ndarray, np.ndarray], law, check: WrittenPairCheck) -> int:
    """:func:`require_gear_teeth`; when the teeth do not count right under the design's law but
    do under the crank law of the other pinion turns (2 or 4), the refusal says to give those."""
    names = (check.pinion, check.wheel)
    try:
        return require_gear_teeth(outlines, law, names)
    except DesignError as err:
        spec = check.spec
        if spec.law_csv is not None:
            raise
        turns = 6 - int(spec.turns)
        try:
            require_gear_teeth(outlines, design_law(spec.model_copy(update={"turns": turns})), names)
        except DesignError:
            raise err from None
        from wheelstep_cli.gears.meshing.check import pair_teeth

        counted = pair_teeth(*outlines, law)[0 if err.param == "pinion" else 1]
        raise DesignError(err.param, err.value, f"has {_teeth(counted)} along its pitch curve at "
                          f"{spec.turns} pinion turns per carrier turn, but the two count as one pair's "
                          f"at {turns}: give -n {turns}") from None


def require_about_its_axis(outline: np.ndarray, name: str, file: str) -> None:
    """Refuse (naming ``name`` = ``file``) a gear section (mm) that does not surround (0, 0):
    the check turns each gear about its frame's origin, and a gear surrounds its axis, so the
    mesh was moved off it (exported where it lay on a bed, say)."""
    from wheelstep_cli.geometry.planar import points_inside, prepared_polygon

    inside = bool(points_inside(prepared_polygon(outline), np.zeros((1, 2)))[0])
    centre = 0.5 * (outline.min(axis=0) + outline.max(axis=0))
    require(inside, name, file,
            f"does not surround (0, 0), where the check takes its axis (its section is centred "
            f"near ({centre[0]:.1f}, {centre[1]:.1f}) mm): give the mesh in the gear's own frame, "
            "axis at the origin, as wheelstep writes it (not moved to where it lay on a bed)")


def require_a_pair(radii: tuple[float, float], distance: float, names: tuple[str, str], law) -> None:
    """Refuse two outlines that cannot be a pinion and its wheel at ``distance`` mm, e.g. two
    wheels or two pinions: their ``radii`` by area (mm; the teeth above and below the pitch
    curve cancel) must add to the distance within SIZE_SLACK. Checked before the poses: two
    wheels overlap everywhere and their check ran for minutes. Two gears whose sizes are in
    ``law``'s mean ratio are a pair at another distance: the distance is named. When one gear
    has about the radius that ratio gives it at the distance, the other (of ``names``, the
    files as given) is named; else the wheel, for both."""
    total = sum(radii)
    if abs(total - distance) <= SIZE_SLACK * distance:
        return
    ratio = _mean_ratio(law)
    # sizes in the law's ratio: a pinion and its wheel, checked at a distance not theirs
    require(abs(radii[1] * ratio / radii[0] - 1.0) > 0.5 * SIZE_SLACK, "distance", distance,
            f"the pinion and the wheel given are a pair for about {total:.1f} mm (radii by area "
            f"{radii[0]:.1f} + {radii[1]:.1f} mm), more than {100 * SIZE_SLACK:.0f} % off: give "
            "the distance they were designed for, or their design's --profile")
    expected = (distance * ratio / (1.0 + ratio), distance / (1.0 + ratio))
    off = [abs(r - e) / e for r, e in zip(radii, expected)]
    bad = 0 if off[0] > off[1] else 1
    fits = off[1 - bad] <= 0.5 * SIZE_SLACK
    part, other = ("pinion", "wheel") if bad == 0 else ("wheel", "pinion")
    why = (f"its radius by area {radii[bad]:.1f} mm is not the {part}'s of a pair at the centre "
           f"distance {distance:g} mm (about {expected[bad]:.1f} mm; the {other}'s "
           f"{radii[1 - bad]:.1f} mm fits it)" if fits else
           f"its radius by area {radii[1]:.1f} mm and the pinion's {radii[0]:.1f} mm add to "
           f"{total:.1f} mm, not the centre distance {distance:g} mm +-{100 * SIZE_SLACK:.0f} %")
    param = part if fits else "wheel"
    raise DesignError(param, names[0 if param == "pinion" else 1],
                      f"{why}: give the pinion and the wheel of one pair (two wheels or two pinions "
                      "cannot mesh), at the distance they were designed for (--distance, or their "
                      "design's --profile)")


def _mean_ratio(law) -> float:
    """The law's mean wheel turn per pinion turn (its rise over one period)."""
    period = float(law.theta_period)
    ends = np.asarray(law.carrier_angle(np.array([0.0, period])), dtype=float)
    return abs(float(ends[1] - ends[0])) / period


def require_pinion_first(radii: tuple[float, float], law, pinion: str,
                         remedy: str = "give the pinion first, then the wheel") -> None:
    """Refuse (naming the pinion) outlines given wheel first (``radii`` by area, mm, in the
    order given): where the law turns the wheel slower than the pinion on average (by more
    than SIZE_SLACK), the wheel is the larger gear. Checked up front: swapped, every pose
    interferes. ``remedy``: how the user puts them in order."""
    ratio = _mean_ratio(law)
    first, second = radii
    require(not (ratio < 1.0 - SIZE_SLACK and first > second), "pinion", pinion,
            f"is the larger gear (radius by area {first:.1f} mm, the wheel given {second:.1f} mm) "
            f"while the law turns the wheel {1.0 / ratio:.3g} times slower than the pinion: the two "
            f"look swapped; {remedy}")


#: How far (a fraction) the wheel's teeth counted may lie from those the pinion's need.
TEETH_SLACK = 0.05


def require_gear_teeth(outlines: tuple[np.ndarray, np.ndarray], law, names: tuple[str, str]) -> int:
    """Refuse (naming the mesh) a pinion outline with fewer teeth than a gear has (a shoe, a
    plain disc), or a wheel whose teeth, counted along its pitch curve, are not the ones the
    pinion's need under ``law`` (another pair's wheel): sizes alone can add up by chance,
    and such a check reports interference at every pose. Returns the pinion's teeth."""
    from wheelstep_cli.config.specs import MIN_TEETH
    from wheelstep_cli.gears.meshing.check import pair_teeth

    z_p, z_w, needed = pair_teeth(*outlines, law)
    require(z_p >= MIN_TEETH, "pinion", names[0],
            f"has {_teeth(z_p)} along the pitch curve of the law; a pinion has "
            f"at least {MIN_TEETH}: give the pinion mesh of a gear pair in its own frame (axis at the "
            "origin), and its design (--profile, --a/--b/--c, --law-csv)")
    require(abs(z_w - needed) <= max(1.0, TEETH_SLACK * needed), "wheel", names[1],
            f"has {_teeth(z_w)} along its pitch curve, not the {needed:.0f} that the pinion's {z_p} "
            "need under the law: give the wheel of this pinion's pair, both as written (a gear turned "
            "about its axis is counted against the wrong stretch of its pitch curve), and its design "
            "(--profile, --a/--b/--c, --law-csv)")
    return z_p


def require_poses_per_tooth(samples: int | None, teeth: int, law) -> None:
    """Refuse (naming --samples) fewer poses over the law's period than the figures of SPEC §10
    need for a pinion of ``teeth`` teeth: the band-limited ripple keeps BAND_HARMONICS tooth
    harmonics, which the period's samples hold only above twice their count per tooth pitch
    (f'i came out 0 um at 16 poses). None (the default, 16 in the shortest tooth pitch) passes."""
    from wheelstep_cli.gears.meshing.figures import BAND_HARMONICS

    if samples is None:
        return
    per_tooth = 2 * BAND_HARMONICS
    least = math.floor(per_tooth * teeth * float(law.theta_period) / (2.0 * math.pi) + 1e-9) + 1
    require(samples >= least, "samples", samples,
            f"must be >= {least} for a pinion of {teeth} teeth (more than {per_tooth} poses per tooth "
            f"pitch: fewer cannot hold the {BAND_HARMONICS} tooth harmonics of the figures)")


def _teeth(count: int) -> str:
    return f"{count} tooth" if count == 1 else f"{count} teeth"


def run_written_pair_check(check: WrittenPairCheck, outlines: tuple[np.ndarray, np.ndarray],
                           progress: Callable[[int, int], None] | None = None, inset: float = 0.0
                           ) -> tuple[MeshingReport, dict]:
    """Check both outlines over one period of the law (blended by the spec's ``blend``, as
    the teeth were cut); returns the report and its summary (files, law, figures, what it says
    of the bounds: ``inset`` mm, the fit's inset a plate's meshes carry, leaves them unjudged)."""
    from wheelstep_cli.parts.mesh_check import check_outlines

    law, blended = generation_law(check.spec)
    report = check_outlines(*outlines, blended, installed_distance(check.spec, blended), check.samples,
                            check.window, progress=progress)
    record = {**law_record(check.spec, law), "blend_deg": check.spec.blend}
    summary = {"pinion": str(check.pinion), "wheel": str(check.wheel), "law": record,
               **report.to_dict()}
    summary["bounds"] = bounds_verdict(summary, inset=inset)
    if inset:
        summary["outline_inset_mm"] = inset
    return report, summary


def written_pair_files(check: WrittenPairCheck, report: MeshingReport) -> dict[Path, bytes]:
    """The plot asked for (``--plot``), if any: path -> PNG bytes."""
    from wheelstep_cli.parts.mesh_check import speed_words
    from wheelstep_cli.render.meshing_plot import meshing_plot_png

    if check.plot is None:
        return {}
    title = f"{Path(check.pinion).name} + {Path(check.wheel).name} at {installed_distance(check.spec):g} mm"
    return {check.plot: meshing_plot_png(report, title, speed_words(check.spec.law_csv is not None))}


def plate_pair_outlines(pair) -> tuple[np.ndarray, np.ndarray]:
    """Mid-thickness sections (mm) of a plate pair's gears, each in its own object frame
    (the build-item transform only placed it on the plate)."""
    from wheelstep_cli.geometry.solids import section_outline

    return (section_outline(pair.pinion.vertices, pair.pinion.faces, "pinion"),
            section_outline(pair.wheel.vertices, pair.wheel.faces, "wheel"))


def run_plate_pair_check(pair, samples: int | None, window: float | None,
                         progress: Callable[[int, int], None] | None = None
                         ) -> tuple[MeshingReport, dict]:
    """Check a pair found on plates (parts.plate_pairs.PlatePair) with the law and installed
    distance of the design in its metadata; returns the report and its summary."""
    check = WrittenPairCheck(f"{pair.files[0]}:{pair.pinion.name}", f"{pair.files[1]}:{pair.wheel.name}",
                             pair.spec, samples, window)
    from wheelstep_cli.gears.meshing.check import radius_by_area

    check.validate()
    outlines = plate_pair_outlines(pair)
    law = design_law(pair.spec)
    # the labels are the plate's word for which gear is which: checked as two meshes given are
    radii = tuple(radius_by_area(o) for o in outlines)
    require_pinion_first(radii, law, check.pinion, "swap the two objects' wheelstep:part metadata "
                                                   "(pinion, wheel) or write the pair again")
    require_poses_per_tooth(samples, int(pair.spec.z), law)
    report, summary = run_written_pair_check(check, outlines, progress, pair.inset)
    return report, {"pair": pair.pair, "distance_mm": installed_distance(pair.spec), **summary}
