"""A design profile file (``profiles/NAME.yaml``): the mechanism and each part's section.

Sections hold any parameter of their part (the part's own model checks each value);
the mechanism section holds a, b and the strut as ``c`` or ``r_min``.
"""

from __future__ import annotations

from typing import Any, Optional

from pydantic import BaseModel, Field, PrivateAttr

from wheelstep_cli.config.fields import STRICT, Number
from wheelstep_cli.config.schema import section_model
from wheelstep_cli.config.specs import GearPairSpec, ShoeSpec


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
