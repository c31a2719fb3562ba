"""A design profile file (``profiles/NAME.yaml``): the mechanism and each part's section.

Sections hold any parameter of their part (the part's own model checks each value);
the mechanism section holds a, b and the strut as ``c`` or ``r_min``.
"""

from __future__ import annotations

from typing import Any, Optional

from pydantic import BaseModel, Field, PrivateAttr

from wheelstep_cli.config.fields import STRICT, Number
from wheelstep_cli.config.schema import section_model
from wheelstep_cli.config.specs import DEFAULT_R_MIN, MECHANISM_KEYS, GearPairSpec, ShoeSpec
from wheelstep_cli.errors import DesignError


class MechanismSection(BaseModel):
    """Crank mechanism lengths in mm: a, b and the strut as c or R_min (= a - 4b + c)."""

    model_config = STRICT

    a: Optional[Number] = None
    b: Optional[Number] = None
    c: Optional[Number] = None
    r_min: Optional[Number] = None


class DesignProfile(BaseModel):
    """A design preset: description, mechanism and the sections of the parts."""

    model_config = STRICT

    description: Optional[str] = Field(None, strict=True)
    mechanism: Optional[MechanismSection] = None
    gears: Optional[section_model(GearPairSpec)] = None
    shoe: Optional[section_model(ShoeSpec)] = None

    #: (section, key) -> ``file:line`` of each value the file gives (set when it is read)
    _where: dict = PrivateAttr(default_factory=dict)
    #: one of the presets shipped with wheelstep (not a file of the user's to edit)
    _shipped: bool = PrivateAttr(default=False)

    @property
    def shipped(self) -> bool:
        """Whether the profile is a preset shipped with wheelstep: its values are overridden
        on the command line, not edited in its file."""
        return self._shipped

    def where(self, section: str, key: str) -> str | None:
        """``file:line`` of ``section.key`` in the profile's file (None: not given there)."""
        return self._where.get((section, key))

    def values(self, section: str) -> dict[str, Any]:
        """The values a section gives (``mechanism``, ``gears``, ``shoe``), without the unset."""
        given = getattr(self, section)
        return {} if given is None else given.model_dump(exclude_none=True)


def mechanism_conflicts(values) -> list[tuple[str, str, str]]:
    """(section, key, why) of each mechanism length a part's section gives that differs
    from the mechanism's (the ``mechanism:`` section over the source design's): the
    gears' law and the shoe's sole come from one crank mechanism, and ``kinematics`` reads
    it for both. A gear pair following a law CSV has no crank law: what sets one (the
    lengths, ``turns``) is refused beside it, as on the command line. ``values(section)``:
    the values a section gives (mm)."""
    shared = values("mechanism")
    base = _crank([shared])
    conflicts = _struts_contradicting(values)
    for section in ("gears", "shoe"):
        part = values(section)
        if section == "gears" and part.get("law_csv") is not None:
            conflicts += [(section, key, "sets the crank law, which gears.law_csv replaces (the gears "
                                         "follow the law read from the CSV)")
                          for key in ("a", "b", "c", "turns") if key in part]
            continue
        keys = [k for k in MECHANISM_KEYS if k in part]
        own = _crank([shared, part]) if keys else None
        if base is None or own is None or all(abs(x - y) <= 1e-9 for x, y in zip(base, own)):
            continue
        lengths = dict(zip(("a", "b", "c", "r_min"), (*base, base[0] - 4 * base[1] + base[2])))
        differing = [k for k in keys if abs(float(part[k]) - lengths[k]) > 1e-9] or keys
        shown = "a = {:g}, b = {:g}, c = {:g} mm"
        where = "the mechanism section" if shared else "the mechanism (no mechanism section: the source design's)"
        why = (f"gives the {section} the mechanism {shown.format(*own)}, {where} {shown.format(*base)}: "
               "a mover's parts share one mechanism; give a, b and the strut in mechanism: only")
        conflicts += [(section, key, why) for key in differing]
    return conflicts


def _struts_contradicting(values) -> list[tuple[str, str, str]]:
    """(section, "r_min", why) of each section that gives the strut both as c and as R_min,
    the two disagreeing (a and b: the section's, else the mechanism's, else the source design's)."""
    from wheelstep_cli.config.specs import strut_contradiction

    found = []
    for section in ("mechanism", "gears", "shoe"):
        given = values(section)
        if "c" in given and "r_min" in given:
            lengths = {"a": 60.0, "b": 100.0, **values("mechanism"), **given}
            why = strut_contradiction(lengths["a"], lengths["b"], given["c"], given["r_min"])
            found += [(section, "r_min", why)] if why else []
    return found


def _crank(layers: list[dict]) -> tuple[float, float, float] | None:
    """(a, b, c) in mm the layers give, higher layers winning, a strut given as c or R_min
    replacing the lower layers' (R_min 20 mm when none gives one); None: no such mechanism."""
    from wheelstep_cli.mechanism.crank import CrankMechanism

    merged: dict = {}
    for layer in layers:
        if "c" in layer or "r_min" in layer:
            merged.pop("c", None)
            merged.pop("r_min", None)
        merged.update({k: layer[k] for k in MECHANISM_KEYS if k in layer})
    a, b = merged.get("a", 60.0), merged.get("b", 100.0)
    if "c" in merged:
        return a, b, merged["c"]
    try:
        return a, b, CrankMechanism.from_r_min(a, b, merged.get("r_min", DEFAULT_R_MIN)).c
    except DesignError:
        return None
