"""The print sheet's gear meshing table tells the person at the printer what the band check
found (a pair that jams over its printer's band was said only on stderr, not with -q)."""

from wheelstep_cli.render.print_sheet import _band


def test_the_band_verdict_says_a_jam_a_clear_band_and_an_unchecked_one():
    jams = {"printer": "fdm-0.4-petg", "checked": True, "jams": True, "least_backlash_mm": -0.05}
    assert _band(jams).startswith("**JAMS** on fdm-0.4-petg")
    clears = {"printer": "fdm-0.4-pla", "checked": True, "jams": False, "least_backlash_mm": 0.0412}
    assert _band(clears) == "clears on fdm-0.4-pla (least backlash 0.041 mm)"
    assert _band({"printer": "x", "checked": False, "jams": False}).startswith("not checked")
    assert _band(None) == "not checked"
