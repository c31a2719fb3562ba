"""A ripple refusal with no remedy among the teeth, drawn with a printer's tooth clearance, is
offered a fit to the printer's band once a fitted build passes (``gears``); a fit that does
not pass is said as tried. The fitted builds stand in for ``checked_pair`` here: the CLI test
(tests/cli/test_design_bounds.py) runs them for real."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from wheelstep_cli.cli.commands import gears_checks
from wheelstep_cli.cli.output import Output
from wheelstep_cli.config.specs import GearPairSpec
from wheelstep_cli.errors import DesignError

PRINTER = SimpleNamespace(name="fdm-test", tooth_clearance=0.2, band=object())


def ripple_refusal(broken=("coast flank band-limited ripple 1.06 % > 1 %",), remedy=None) -> DesignError:
    """A bounds refusal as parts.mesh_bounds raises it, with no remedy found."""
    error = DesignError("z", 42, f"the pair would mesh outside the bounds ({'; '.join(broken)}); nothing "
                                 "written; no remedy found (--z 46 still gives f'i 12 um > 10 um): change "
                                 "the mechanism (--a, --b, --c) or the centre distance; the play ... --fit auto")
    error = error.tied_to({"backlash": 0.15})
    error.remedy, error.tried = remedy or {}, [{"z": 46}]
    error.tried_words, error.broken = ["--z 46 still gives f'i 12 um > 10 um"], list(broken)
    return error


def offered(monkeypatch, builds, error=None, printer=PRINTER):
    """``_fit_offered`` of ``error`` with each fitted build taken from ``builds`` (a
    DesignError raised, anything else passes); (the refusal it returns, the specs built)."""
    built = []

    def fitted(spec, *args, **kwargs):
        built.append(spec)
        outcome = builds[len(built) - 1]
        if isinstance(outcome, DesignError):
            raise outcome
        return (None, None, None, None)

    monkeypatch.setattr(gears_checks, "checked_pair", fitted)
    monkeypatch.setattr("wheelstep_cli.parts.printed_teeth.require_printable_teeth", lambda pair: pair)
    pair = SimpleNamespace(printing=SimpleNamespace(printer=printer))
    result = gears_checks._fit_offered(error or ripple_refusal(), GearPairSpec(z=42), pair, printer,
                                       Output(quiet=True), None)
    return result, built


def thin(z: int) -> DesignError:
    error = DesignError("z", 42, f"the teeth are too thin for printer 'fdm-test'; nothing written; use --z {z}")
    error.remedy = {"z": z}
    return error


def test_a_fit_whose_build_passes_is_offered_with_the_options_its_refusals_asked_for(monkeypatch):
    refusal, built = offered(monkeypatch, [thin(36), "passes"])
    assert [spec.z for spec in built] == [42, 36]
    assert refusal.remedy == {"fit": "auto", "z": 36}
    assert refusal.limit.startswith("the pair would mesh outside the bounds (coast flank band-limited ripple")
    assert refusal.limit.endswith("nothing written; use --fit auto --z 36 (the fit to the band of printer "
                                  "fdm-test replaces its 0.2 mm tooth clearance, whose play costs the ripple)")
    # the input that shares the blame states the same advice
    assert refusal.for_given(["backlash"]).limit.endswith("use --fit auto --z 36 (the fit to the band of "
                                                          "printer fdm-test replaces its 0.2 mm tooth "
                                                          "clearance, whose play costs the ripple)")


def test_a_fit_that_does_not_pass_is_said_as_tried_and_no_longer_hinted(monkeypatch):
    jam = DesignError("fit", "auto", "cannot keep 0.01 mm over the band; nothing written; print without --fit")
    refusal, built = offered(monkeypatch, [thin(36), jam])
    assert len(built) == 2 and refusal.remedy == {}
    assert refusal.limit.endswith("nothing written; no remedy found (--z 46 still gives f'i 12 um > 10 um; "
                                  "--fit auto is refused: the teeth are too thin for printer 'fdm-test'; "
                                  "--fit auto --z 36 is refused: cannot keep 0.01 mm over the band): change "
                                  "the mechanism (--a, --b, --c) or the centre distance"), refusal.limit


def test_the_fit_is_not_tried_for_a_design_outside_the_bounds_without_the_clearance(monkeypatch):
    """The fitted design is drawn without the clearance: outside the bounds there, its teeth
    are the cause, which no fit cures (its refusal's remedy is not followed)."""
    outside = ripple_refusal(remedy={"z": 50})
    refusal, built = offered(monkeypatch, [outside])
    assert len(built) == 1 and refusal.remedy == {} and "--fit auto is refused" in refusal.limit


@pytest.mark.parametrize("broken, printer", [
    (["coast flank f'i 12.10 um > 10 um"], PRINTER),                               # no ripple broken
    (["coast flank band-limited ripple 1.06 % > 1 %"], SimpleNamespace(name="p", tooth_clearance=0.0,
                                                                       band=object())),
    (["coast flank band-limited ripple 1.06 % > 1 %"], SimpleNamespace(name="p", tooth_clearance=0.2,
                                                                       band=None)),
])
def test_no_fit_is_tried_where_the_clearance_is_not_the_cause(monkeypatch, broken, printer):
    error = ripple_refusal(broken=broken)
    refusal, built = offered(monkeypatch, [], error, printer)
    assert built == [] and refusal is error


def test_a_refusal_restated_with_other_advice_keeps_its_cause():
    error = DesignError("z", 42, "breaks the bounds (x); nothing written; use --z 44").tied_to({"backlash": 0.1})
    error.remedy = {"z": 44}
    other = error.with_advice("use --fit auto", {"fit": "auto"})
    assert other.limit == "breaks the bounds (x); nothing written; use --fit auto"
    assert other.remedy == {"fit": "auto"} and error.remedy == {"z": 44}
    assert other.for_given(["backlash"]).limit == ("with it, z = 42 fails: breaks the bounds (x); nothing "
                                                   "written; use --fit auto")
    plain = DesignError("z", 42, "breaks the bounds").with_advice("use --z 44", {"z": 44})
    assert plain.limit == "breaks the bounds; nothing written; use --z 44"
