"""The bounds a written pair must mesh within, and the play's ripple model behind the remedies."""

from __future__ import annotations

import numpy as np
import pytest

from wheelstep_cli.gears.generation.play import largest_play, play_angle, play_ripple
from wheelstep_cli.gears.pitch_curves import pitch_curves
from wheelstep_cli.parts.gear_pair import GearPairSpec, design_backlash, generation_law, installed_distance
from wheelstep_cli.parts.mesh_bounds import MeshBounds, bound_violations, ripple_teeth_remedy, teeth_remedy


def flank(total=5.0, tooth=4.0, ripple=0.5):
    return {"F_i_total_um": total, "f_i_tooth_um": tooth, "hub_speed_ripple_pct": ripple,
            "te_min_arcmin": -10.0, "te_max_arcmin": -9.0}


def record(drive=None, coast=None, **extra):
    return {"interference": False, "interfering_poses": 0, "samples": 1536, "contact_lost": False,
            "law_hub_speed_ripple_pct": 0.0, "drive": drive or flank(), "coast": coast or flank(), **extra}


def test_within_bounds_on_both_flanks_has_no_violation():
    assert bound_violations(record()) == []


@pytest.mark.parametrize("side", ["drive", "coast"])
def test_each_flank_and_figure_is_held_to_its_bound(side):
    broken = bound_violations(record(**{side: flank(total=15.5, tooth=10.2, ripple=1.3)}))
    assert len(broken) == 3 and all(text.startswith(f"{side} flank") for text in broken)
    assert bound_violations(record(**{side: flank(total=None)})) == [f"{side} flank F'i not measured (bound 15 um)"]


def test_a_figure_just_over_its_bound_is_shown_over_it():
    """1.0042 % was shown "1.00 % > 1 %": the decimals that show it over the bound are kept."""
    assert bound_violations(record(drive=flank(ripple=1.0042))) == ["drive flank band-limited ripple 1.004 % > 1 %"]
    assert bound_violations(record(coast=flank(total=16.134))) == ["coast flank F'i 16.13 um > 15 um"]


@pytest.mark.parametrize("found, passes_from, failed, expect", [
    (96, 60, [], 60),           # 48 fails, 96 passes: halves to 72 (pass), 60 (pass), 54 (fail)
    (96, 91, [], 96),           # 72, 84, 90 fail: only the count found passes
    (96, 50, [{"z": 52}], 56),  # a failed try at 52 is the lower end (figures not monotone in z)
    (68, 60, [], 60),           # 58 is refused (no count), 62 and 60 pass
])
def test_fewest_teeth_halves_the_gap_and_returns_only_a_count_built_within(found, passes_from, failed, expect):
    """A remedy that adds teeth is followed down to fewer teeth, each count built; a count is
    returned only if its build was within the bounds (the stub passes from ``passes_from``,
    except a count a failed try had, and refuses 58)."""
    from wheelstep_cli.errors import DesignError
    from wheelstep_cli.parts.fewest_teeth import fewest_teeth

    built = []

    def verify(trial):
        built.append(trial.z)
        if trial.z == 58:
            raise DesignError("z", 58, "teeth too thin")      # a refused build is no count
        within = trial.z >= passes_from and trial.z not in [c["z"] for c in failed]
        return None, record() if within else record(drive=flank(total=20.0))

    design = GearPairSpec(z=48)
    assert fewest_teeth(design, {"z": found, "backlash": 0.1}, failed, 2, verify, MeshBounds()) == \
        {"z": expect, "backlash": 0.1}
    assert len(built) <= 3 and all(z % 2 == 0 for z in built)
    # nothing to halve: fewer teeth, or a module that sizes the pair with the count
    assert fewest_teeth(design, {"z": 40}, [], 2, verify, MeshBounds()) == {"z": 40}
    assert fewest_teeth(GearPairSpec(z=48, module=2.0), {"z": 96}, [], 2, verify, MeshBounds()) == {"z": 96}


def test_ripple_bound_is_on_what_the_teeth_add_to_the_laws_own():
    assert bound_violations(record(drive=flank(ripple=9.8), coast=flank(ripple=9.9),
                                   law_hub_speed_ripple_pct=9.2)) == []
    assert len(bound_violations(record(drive=flank(ripple=10.4), law_hub_speed_ripple_pct=9.2))) == 1


def test_teeth_remedy_scales_z_by_the_worst_ratio_in_whole_periods():
    assert teeth_remedy(record(drive=flank(total=30.0, tooth=12.0)), 24, 2) == 48
    assert teeth_remedy(record(), 48, 2) == 48


def test_ripple_of_the_tooth_form_is_remedied_with_fewer_teeth_in_whole_periods():
    """The form's ripple grows about as z: a pair at z 200 rippling 1.8 % (the law's own 0.1 %
    taken off) is offered 200 / (1.7 / 0.9) rounded down to whole periods; one within the
    bound but not its 0.9 margin loses a period at least; never below 6 teeth; unmeasured:
    two periods more."""
    over = record(drive=flank(ripple=1.8), coast=flank(ripple=1.2), law_hub_speed_ripple_pct=0.1)
    assert ripple_teeth_remedy(over, 200, 2) == 104
    assert ripple_teeth_remedy(record(drive=flank(ripple=0.95)), 48, 2) == 44   # 0.9 x the bound
    assert ripple_teeth_remedy(record(drive=flank(ripple=50.0)), 48, 4) == 8
    assert ripple_teeth_remedy(record(drive=flank(ripple=None)), 48, 2) == 52


def test_a_constant_play_costs_hub_speed_ripple_at_the_handover_corners():
    spec = GearPairSpec()
    _, law = generation_law(spec)
    assert play_ripple(law, 0.0) < 0.002                  # the law alone is (nearly) flat
    curves = pitch_curves(law, installed_distance(spec))
    quarter, half = (play_ripple(law, play_angle(j, curves.wheel, np.radians(20.0))) for j in (0.25, 0.5))
    assert 0.004 < quarter < half < 0.012                 # grows with the play, about linearly
    limit = largest_play(law, 0.005)
    assert play_ripple(law, limit) == pytest.approx(0.005, abs=1e-4)


def test_default_backlash_of_generated_teeth_keeps_half_the_ripple_bound_for_the_teeth():
    assert 0.2 < design_backlash(GearPairSpec()) < 0.3
    assert design_backlash(GearPairSpec(backlash=0.4)) == 0.4
    assert design_backlash(GearPairSpec(teeth="paper")) == 0.5


def _refusal(verify, **given):
    """The bounds refusal of a pair whose F'i is over its bound (the remedy: more teeth),
    with ``verify`` standing for the build and check of a remedy; ``given``: more spec values."""
    from types import SimpleNamespace

    from wheelstep_cli.errors import DesignError
    from wheelstep_cli.parts.mesh_bounds import require_within_bounds

    spec = GearPairSpec(z=32, **given)
    pair = SimpleNamespace(generated=SimpleNamespace(law=generation_law(spec)[1]), printing=None,
                           spec=spec, as_asked=spec, opening=0.0)
    with pytest.raises(DesignError) as err:
        require_within_bounds(pair, record(drive=flank(total=18.0, tooth=6.0)), verify=verify)
    return err.value, pair


def test_a_remedy_is_offered_once_its_build_is_within_the_bounds():
    builds = []

    def verify(design):
        builds.append(design.z)
        return None, record()

    error, _ = _refusal(verify)
    # F'i 18 um against 15: z 32 x sqrt(1.2) (the deviations fall about as 1/z^2), whole periods;
    # within, the gap down to the design's count is halved: 34 is built and within too
    assert builds == [36, 34] and error.remedy == {"z": 34} and error.limit.endswith("; use --z 34")


def test_a_remedy_whose_build_is_still_out_is_not_offered_and_the_line_says_what_was_tried():
    from types import SimpleNamespace

    builds = []

    def verify(design):
        builds.append(design.z)
        pair = SimpleNamespace(generated=SimpleNamespace(law=generation_law(design)[1]), printing=None,
                               spec=design, as_asked=design, opening=0.0)
        return pair, record(drive=flank(total=18.0, tooth=6.0))

    error, _ = _refusal(verify)
    assert builds == [36, 40, 44, 50, 56]    # each try from the last one's figures (x sqrt 1.2)
    assert error.remedy == {} and "; use --" not in error.limit
    assert ("no remedy found (--z 36 still gives drive flank F'i 18.00 um > 15 um; --z 40 still "
            "gives drive flank F'i 18.00 um > 15 um; --z 44 still gives drive flank F'i 18.00 um "
            "> 15 um; --z 50 still gives drive flank F'i 18.00 um > 15 um; --z 56 still gives drive "
            "flank F'i 18.00 um > 15 um): change the mechanism") in error.limit
    from wheelstep_cli.config.names import remedy_in_yaml

    # a batch file states the tries as its override keys
    assert "no remedy found (overrides {z: 36} still gives" in remedy_in_yaml(error)
    assert "; overrides {z: 40} still gives" in remedy_in_yaml(error)


def test_when_more_teeth_do_not_do_the_settings_the_design_changed_are_set_back():
    """A pair cut with a small pressure angle and a short addendum whose deviations more teeth
    do not cure: after the tries of more teeth, those settings at their defaults (the count
    kept) are built and offered; a design at the defaults gets no such try."""
    from types import SimpleNamespace

    builds = []

    def verify(design):
        builds.append((design.z, design.pressure_angle, design.addendum))
        pair = SimpleNamespace(generated=SimpleNamespace(law=generation_law(design)[1]), printing=None,
                               spec=design, as_asked=design, opening=0.0)
        return pair, record() if design.pressure_angle == 20 else record(drive=flank(total=18.0))

    error, _ = _refusal(verify, pressure_angle=15.0, addendum=0.9, dedendum=1.2)
    defaults = GearPairSpec.model_fields
    assert builds == [(36, 15.0, 0.9), (40, 15.0, 0.9), (44, 15.0, 0.9), (50, 15.0, 0.9), (56, 15.0, 0.9),
                      (32, 20.0, 1.0)]
    assert error.remedy == {name: defaults[name].default for name in ("pressure_angle", "addendum", "dedendum")}
    assert error.param == "pressure_angle"
    # after the counts tried first, which the line says
    assert "; use --pressure-angle 20 --addendum 1 --dedendum 1.25 (tried first: --z 36 still gives " in error.limit
    builds.clear()
    error, _ = _refusal(lambda design: verify(design.model_copy(update={"pressure_angle": 15.0})))
    assert [z for z, _, _ in builds] == [36, 40, 44, 50, 56] and error.remedy == {}


def test_a_ripple_more_teeth_do_not_cure_is_offered_fewer_teeth():
    """A ripple alone (the flanks' micron deviations over too small a pitch): after the tries
    of more teeth, the count :func:`ripple_teeth_remedy` points to is built and offered."""
    from types import SimpleNamespace

    from wheelstep_cli.errors import DesignError
    from wheelstep_cli.parts.mesh_bounds import require_within_bounds

    builds = []
    rippling = record(drive=flank(ripple=1.6), coast=flank(ripple=1.5))

    def verify(design):
        builds.append(design.z)
        pair = SimpleNamespace(generated=SimpleNamespace(law=generation_law(design)[1]), printing=None,
                               spec=design, as_asked=design, opening=0.0)
        return pair, record() if design.z < 100 else rippling

    spec = GearPairSpec(z=100)
    pair = SimpleNamespace(generated=SimpleNamespace(law=generation_law(spec)[1]), printing=None,
                           spec=spec, as_asked=spec, opening=0.0)
    with pytest.raises(DesignError) as err:
        require_within_bounds(pair, rippling, verify=verify)
    # the play first (less backlash); the ripple it left is the teeth's: two periods more teeth,
    # then less play for them and, left again, more teeth, twice; all found wanting: fewer teeth
    assert builds[:-1] == [100, 104, 104, 108, 112]
    assert builds[-1] == ripple_teeth_remedy(rippling, 100, 2) == 56
    assert err.value.remedy == {"z": 56} and "; use --z 56 (tried first: --backlash " in err.value.limit


def test_more_teeth_on_a_given_module_that_outgrow_the_printer_keep_the_size_asked_for():
    """--module 2 --z 32: the first try keeps the module given; refused as larger than the
    printer, the tries scale the module by 32 / z' from then on (module x z stays 64, so the
    centre distance the module is solved for stays), also a try that follows a refusal's own
    remedy."""
    from types import SimpleNamespace

    from wheelstep_cli.errors import DesignError

    tries = []

    def verify(design):
        tries.append((design.z, design.module))
        if design.module == 2:
            error = DesignError("printer", "fdm-0.4-pla", "part 'wheel' does not fit the bed")
            error.beyond_printer = "fdm-0.4-pla"
            raise error
        if design.z == 36:
            error = DesignError("z", 36, "teeth too thin; nothing written; use --z 34")
            error.remedy = {"z": 34}
            raise error
        pair = SimpleNamespace(generated=SimpleNamespace(law=generation_law(design)[1]), printing=None,
                               spec=design, as_asked=design, opening=0.0)
        return pair, record()

    error, _ = _refusal(verify, module=2)
    assert tries == [(36, 2), (36, round(64 / 36, 3)), (34, round(64 / 34, 3))]
    assert error.remedy == {"z": 34, "module": round(64 / 34, 3)}


def test_the_try_a_given_module_outgrows_the_printer_with_is_not_one_of_the_tries():
    """The sized tries get their REMEDY_TRIES builds after the one refused as too large."""
    from types import SimpleNamespace

    from wheelstep_cli.errors import DesignError
    from wheelstep_cli.parts.mesh_bounds import REMEDY_TRIES

    tries = []

    def verify(design):
        tries.append(design.z)
        if design.module == 2:
            error = DesignError("printer", "fdm-0.4-pla", "part 'wheel' does not fit the bed")
            error.beyond_printer = "fdm-0.4-pla"
            raise error
        pair = SimpleNamespace(generated=SimpleNamespace(law=generation_law(design)[1]), printing=None,
                               spec=design, as_asked=design, opening=0.0)
        return pair, record(drive=flank(total=18.0, tooth=6.0))

    error, _ = _refusal(verify, module=2)
    assert len(tries) == 1 + REMEDY_TRIES and error.remedy == {}


def test_a_try_the_bed_refuses_is_followed_by_the_same_try_drawn_smaller():
    """More teeth at the installed distance given widen the wheel past the bed's edge (its
    refusal carries the scale the bed allows): the same count is tried at that distance scaled
    (rounded down to 0.1 mm), and offered once within the bounds."""
    from types import SimpleNamespace

    from wheelstep_cli.errors import DesignError

    tries = []

    def verify(design):
        tries.append((design.z, design.install_distance))
        if design.install_distance == 100.0:
            error = DesignError("printer", "fdm-0.4-pla", "part 'wheel' does not fit the bed")
            error.beyond_printer, error.bed_scale = "fdm-0.4-pla", 0.9504
            raise error
        pair = SimpleNamespace(generated=SimpleNamespace(law=generation_law(design)[1]), printing=None,
                               spec=design, as_asked=design, opening=0.0)
        return pair, record()

    error, _ = _refusal(verify, install_distance=100.0)
    assert tries[:2] == [(36, 100.0), (36, 95.0)]
    assert error.remedy["install_distance"] == 95.0 and 32 < error.remedy["z"] <= 36
    assert "--install-distance 95" in error.limit


def test_a_sized_try_still_off_the_bed_is_drawn_smaller_by_the_scale_the_bed_allows():
    """A module given: the count's try keeps the pair's size (module x z); when that size is
    itself off the bed (a bed remedy's smaller pair, whose teeth then change), the try is drawn
    smaller by the refusal's scale, not given up."""
    from types import SimpleNamespace

    from wheelstep_cli.errors import DesignError

    tries = []

    def verify(design):
        tries.append((design.z, design.module))
        size = design.module * design.z
        if size > 60.0 + 1e-9:
            error = DesignError("printer", "fdm-0.4-pla", "part 'wheel' does not fit the bed")
            error.beyond_printer, error.bed_scale = "fdm-0.4-pla", 60.0 / size
            raise error
        pair = SimpleNamespace(generated=SimpleNamespace(law=generation_law(design)[1]), printing=None,
                               spec=design, as_asked=design, opening=0.0)
        return pair, record()

    error, _ = _refusal(verify, module=2.0)
    assert tries[:3] == [(36, 2.0), (36, round(64 / 36, 3)), (36, 1.666)], tries
    assert error.remedy["module"] * error.remedy["z"] <= 60.0 and 32 < error.remedy["z"] <= 36, error.remedy


def test_a_remedy_the_pipeline_refuses_is_not_offered():
    from wheelstep_cli.errors import DesignError

    def verify(design):
        raise DesignError("thickness", 5, "makes it too tall; nothing written; use --thickness 4")

    error, _ = _refusal(verify)
    assert error.remedy == {}
    assert "no remedy found (--z 36 is refused: --thickness = 5: makes it too tall)" in error.limit


def test_a_remedy_already_tried_is_not_built_again():
    """F'i over its bound at 36 (its remedy 40) and thin teeth at 40 (their remedy 36): the
    tries go 36 -> 40 and do not build 36 again."""
    from types import SimpleNamespace

    from wheelstep_cli.errors import DesignError

    builds = []

    def verify(design):
        builds.append(design.z)
        if design.z == 40:
            error = DesignError("z", 40, "the teeth are too thin; nothing written; use --z 36")
            error.remedy = {"z": 36}
            raise error
        pair = SimpleNamespace(generated=SimpleNamespace(law=generation_law(design)[1]), printing=None,
                               spec=design, as_asked=design, opening=0.0)
        return pair, record(drive=flank(total=18.0, tooth=6.0))

    error, _ = _refusal(verify)
    assert builds == [36, 40] and error.remedy == {}, builds


def test_a_batch_remedy_said_as_keys_leaves_longer_numbers_alone():
    """A tried z 24 is said as the entry's keys without touching z 240 elsewhere in the line."""
    from wheelstep_cli.errors import DesignError
    from wheelstep_cli.config.names import remedy_in_yaml

    error = DesignError("z", 20, "no remedy found (--z 24 still gives F'i 20 um; the limit is --z 240)")
    error.tried = [{"z": 24}]
    said = remedy_in_yaml(error)
    assert "overrides {z: 24} still gives" in said and "z 240" in said, said


@pytest.mark.parametrize("z, periods, prints, uncut_below, expect", [
    (94, 2, (32, 60), 32, 60),        # 17 periods above what prints: doubling, then halving
    (140, 2, (32, 60), 32, 60),       # more than 32 periods above
    (94, 2, (32, 60), 40, 60),        # the doubling steps past the printing counts into undercut ones
    (20, 1, (6, 12), 6, 12),          # down to the least count
    (94, 2, (200, 300), 18, None),    # nothing below prints
    (50, 2, (6, 10), 30, None),       # the printing counts undercut
])
def test_fewer_teeth_finds_the_largest_count_that_prints(monkeypatch, z, periods, prints, uncut_below, expect):
    """The search over counts below the design's (stood in for by a stub of the pinion's state):
    the largest count that prints, past counts too thin above it and undercut ones below."""
    from types import SimpleNamespace

    import wheelstep_cli.parts.printed_teeth as printed_teeth

    def state(design, count, printer, width, inset, per):
        assert (z - count) % periods == 0 and count >= 6
        if count < uncut_below or count < prints[0]:
            return "uncut"
        return "prints" if count <= prints[1] else "thin"

    monkeypatch.setattr(printed_teeth, "_printing", state)
    pair = SimpleNamespace(generated=SimpleNamespace(law=SimpleNamespace(pinion_periods=periods)), inset=0.0)
    assert printed_teeth.fewer_teeth(pair, SimpleNamespace(z=z, module=None), None, 0.8) == expect


def test_a_remedy_the_plates_bed_cannot_hold_is_refused_before_its_meshing_check():
    """A remedy's build laid out on a printer's bed must fit it: z 48 on module 4 (a centre
    distance of about 290 mm) is refused naming the bed; without a bed to fit it is checked."""
    from wheelstep_cli.config.profiles import load_printer
    from wheelstep_cli.errors import DesignError
    from wheelstep_cli.parts.mesh_bounds import remedy_check

    printer = load_printer("fdm-0.4-pla")
    design = GearPairSpec(z=48, module=4.0)
    with pytest.raises(DesignError, match="does not fit the bed of printer 'fdm-0.4-pla'"):
        remedy_check(printer, bed=printer)(design)
    pair, record = remedy_check(printer)(design)
    assert record["samples"] >= 1536 and pair.wheel.bounds[1][0] - pair.wheel.bounds[0][0] > 246


def test_a_scaled_module_stays_a_module_a_spec_takes():
    from wheelstep_cli.config.specs import MIN_MODULE
    from wheelstep_cli.parts.printed_teeth import sized_remedy as _sized

    design = GearPairSpec(z=24, module=0.2)
    assert _sized(design, {"z": 72}) == {"z": 72, "module": MIN_MODULE}       # 0.067 would be refused
    assert _sized(design, {"z": 24, "module": 0.15, "backlash": 0.1}) == {"z": 24, "backlash": 0.1}
    assert _sized(GearPairSpec(z=24), {"z": 72}) == {"z": 72}                # no module given: none set


@pytest.mark.parametrize("clearance", [0.2, 0.0])
def test_a_ripple_no_remedy_cures_points_to_a_fit_when_a_printers_clearance_draws_the_play(clearance):
    """A ripple that no try brings within the bound, on a pair drawn with a printer's tooth
    clearance: the refusal points to a fit to the printer's band (which replaces the clearance
    with less play), in the command's and the profile's words; without a clearance it does not."""
    from types import SimpleNamespace

    from wheelstep_cli.errors import DesignError
    from wheelstep_cli.parts.mesh_bounds import require_within_bounds

    spec = GearPairSpec(z=42)
    printing = SimpleNamespace(printer=SimpleNamespace(tooth_clearance=clearance, band=object()))
    pair = SimpleNamespace(generated=SimpleNamespace(law=generation_law(spec)[1]), printing=printing,
                           spec=spec, as_asked=spec, opening=0.0)
    rippled = record(coast=flank(ripple=1.3))

    def verify(design):
        return SimpleNamespace(generated=pair.generated, printing=printing, spec=design, as_asked=design,
                               opening=0.0), rippled

    with pytest.raises(DesignError) as err:
        require_within_bounds(pair, rippled, verify=verify)
    hint = (f"the play of the printer's {clearance:g} mm tooth clearance costs ripple: a fit to its band draws "
            "less (`wheelstep gears --fit auto`, or `fit: auto` in the printer profile's band section)")
    assert "no remedy found" in err.value.limit or "no tooth count" in err.value.limit, err.value.limit
    assert (hint in err.value.limit) is (clearance > 0), err.value.limit


@pytest.mark.parametrize("falls, next_z", [(True, 100), (False, 104)])
def test_less_play_that_hardly_lowers_the_ripple_is_followed_by_more_teeth(falls, next_z):
    """A ripple the play costs (it falls with the backlash) is followed with less play again;
    one that less play hardly lowered is the tooth form's: the next try has more teeth."""
    from types import SimpleNamespace

    from wheelstep_cli.errors import DesignError
    from wheelstep_cli.parts.mesh_bounds import require_within_bounds

    spec = GearPairSpec(z=100)
    start = record(drive=flank(ripple=1.6), coast=flank(ripple=1.5))
    tries = []

    def verify(design):
        tries.append((design.z, design.backlash))
        ripple = 1.6 * design.backlash_mm / spec.backlash_mm if falls else 1.6
        pair = SimpleNamespace(generated=SimpleNamespace(law=generation_law(design)[1]), printing=None,
                               spec=design, as_asked=design, opening=0.0)
        return pair, record(drive=flank(ripple=max(ripple, 1.05)))

    pair = SimpleNamespace(generated=SimpleNamespace(law=generation_law(spec)[1]), printing=None,
                           spec=spec, as_asked=spec, opening=0.0)
    with pytest.raises(DesignError):
        require_within_bounds(pair, start, verify=verify)
    (z1, first), (z2, then) = tries[:2]
    assert z1 == 100 and first < spec.backlash_mm       # the play first
    # fallen by more than a quarter of its excess: less play again; else two periods more teeth
    assert z2 == next_z and (then < first if falls else True), tries


def test_a_bed_remedy_on_a_given_module_says_the_size_of_the_pair_it_offers():
    """The pair drawn smaller on a module given (module x z sizes it) whose smaller teeth then
    need more of them: the remedy's size is module x z against the design's (90 %), not the
    module's ratio (80 %), and the count it changes is said."""
    from types import SimpleNamespace

    from wheelstep_cli.errors import DesignError
    from wheelstep_cli.parts.bed_remedy import scaled_to_bed

    def off_the_bed(size):
        error = DesignError("printer", "fdm-0.4-pla", "part 'wheel' does not fit the bed; nothing written")
        error.beyond_printer, error.bed_scale = "fdm-0.4-pla", 57.6 / size
        return error

    def verify(design):
        if design.module * design.z > 57.6 + 1e-9:
            raise off_the_bed(design.module * design.z)
        pair = SimpleNamespace(generated=SimpleNamespace(law=generation_law(design)[1]), printing=None,
                               spec=design, as_asked=design, opening=0.0)
        return pair, record(drive=flank(total=18.0, tooth=6.0) if design.z < 36 else flank())

    def build():
        raise off_the_bed(64.0)

    with pytest.raises(DesignError) as err:
        scaled_to_bed(build, GearPairSpec(z=32, module=2.0), verify)
    assert err.value.remedy == {"module": 1.6, "z": 36}
    assert "use --module 1.6 --z 36 (the pair drawn at 90 % of its size with 36 teeth, which the bed holds)" \
        in err.value.limit, err.value.limit
