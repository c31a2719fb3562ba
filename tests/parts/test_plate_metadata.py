"""A plate's stored design is checked by the spec's model: a rule between fields that the
metadata breaks is named by its field, not by the whole metadata dict."""

from __future__ import annotations

import pytest

from wheelstep_cli.errors import DesignError
from wheelstep_cli.parts.plate_pairs import spec_from_metadata


def test_a_rule_between_fields_names_the_field_the_metadata_breaks():
    # paper teeth with a generator setting: what an older wheelstep wrote and this one refuses
    with pytest.raises(DesignError) as err:
        spec_from_metadata({"teeth": "paper", "pressure_angle": "25"}, "old.3mf")
    assert err.value.param == "pinion" and err.value.value == "old.3mf"
    assert err.value.limit == ("metadata pressure_angle = 25: shapes generated teeth only (the paper "
                               "teeth are the source's sector involutes)")


def test_a_bad_field_value_is_named_with_its_value():
    with pytest.raises(DesignError) as err:
        spec_from_metadata({"z": "many"}, "odd.3mf")
    assert err.value.limit.startswith("metadata z = 'many': ")


@pytest.mark.parametrize("values, expect", [
    # the law's turns: a field's rule, said of the metadata like any other value
    ({"turns": "3"}, "metadata turns = 3: must be 2 (balanced pinion) or 4 (one pinion turn per shoe)"),
    # a field's range in the words of every other refusal, not the validator's
    ({"z": "300"}, "metadata z = 300: must be 6..240 (pinion teeth)"),
])
def test_a_bad_field_value_is_said_in_the_models_words(values, expect):
    with pytest.raises(DesignError) as err:
        spec_from_metadata(values, "odd.3mf")
    assert (err.value.param, err.value.value, err.value.limit) == ("pinion", "odd.3mf", expect)


def test_two_gears_whose_fits_drew_them_with_different_insets_are_no_pair():
    """The check draws both outlines with one inset (the pinion's): a wheel of another fit
    is refused as another design, naming the inset."""
    import numpy as np

    from wheelstep_cli.formats.mesh_read import MeshObject
    from wheelstep_cli.parts.plate_pairs import _plate_pair

    def gear(part: str, inset: str) -> MeshObject:
        return MeshObject(part, np.zeros((3, 3)), np.array([[0, 1, 2]]), np.zeros((4, 3)),
                          {"part": part, "pair": "gears", "z": "42", "outline_inset": inset})

    same = _plate_pair("gears", {"pinion": ("a.3mf", gear("pinion", "0.05")), "wheel": ("b.3mf", gear("wheel", "0.05"))})
    assert same.inset == 0.05 and same.spec.z == 42
    with pytest.raises(DesignError) as err:
        _plate_pair("gears", {"pinion": ("a.3mf", gear("pinion", "0.05")), "wheel": ("b.3mf", gear("wheel", "0.08"))},
                    ("a.3mf:pinion", "b.3mf:wheel"))
    assert (err.value.param, err.value.value) == ("wheel", "b.3mf:wheel")
    assert err.value.limit.endswith("pair 'gears': outline_inset = 0.08 (the pinion's 0.05)")
