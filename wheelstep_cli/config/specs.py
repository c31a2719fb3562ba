"""The user parameters of the printed parts, as models: every type, bound and choice once.

Defaults are the source design (BNTU prototype, profiles/bntu-2024.yaml). Lengths in mm,
angles in degrees (user-facing values; converted to radians where they are used). The
mechanism's own rules (R_min = a - 4b + c > 0, k > 0, lengths > 0) stay with the mechanism,
which raises them when the spec is used; the turns the law takes are a field's, so a profile
states them wrong at its line.
"""

from __future__ import annotations

from typing import Annotated, Optional

import numpy as np
from pydantic import AfterValidator, BaseModel, Field, model_validator
from pydantic_core import PydanticCustomError

from wheelstep_cli.config.fields import STRICT, Choice, Number, Real, Whole, length, quantity
from wheelstep_cli.config.shaft_rules import bore_defaults, shaft_rules
from wheelstep_cli.errors import DesignError, require, rounded_down, rounded_up
from wheelstep_cli.gears.cutter_limits import ADDENDUM, CLEARANCE, DEDENDUM_MAX, FILLET, PRESSURE_ANGLE_DEG, range_text
from wheelstep_cli.gears.laws import TURNS, TURNS_LIMIT

#: Mechanism parameters (the ``mechanism:`` section of a design profile).
MECHANISM_KEYS = ("a", "b", "c", "r_min")
#: The source design's strut when neither c nor R_min is given: R_min = 20 mm.
DEFAULT_R_MIN = 20.0
#: Longest mechanism length taken, mm (a 10 m mover; bounds the work and the part sizes).
MAX_LENGTH = 10_000.0
#: Installed centre distance when none is given (the source's, mm), and how much closer the
#: source's paper sectors roll (its L_p = 143.5 mm, installed 0.5 mm apart for backlash).
DEFAULT_INSTALL, PAPER_OPENING = 144.0, 0.5
#: The paper teeth's backlash when none is given, per mm of module (SPEC §5: j_n = 0.25 m).
PAPER_BACKLASH_PER_MODULE = 0.25
#: Pinion tooth counts taken: the generator's floor, and a ceiling that bounds its work.
MIN_TEETH, MAX_TEETH = 6, 240
#: Least centre distance (mm): a pair closer than this cannot be printed, and far below it the
#: pitch-curve solvers meet floating-point underflow.
MIN_DISTANCE = 1.0
#: Greatest centre distance (mm): beyond any printer's bed, and it bounds the work (outlines
#: are sampled in micrometres: about 0.8 GB and 15 s at 1000 mm, linear in the distance).
MAX_DISTANCE = 1000.0
#: Least plastic of a shoe (mm): around and under its strut socket, and its body's height
#: above the sole's ends (thinner, the ends print as knife edges that break off).
MIN_SHOE_WALL = 2.0
#: Least socket bore (mm): a smaller hole does not print, and far below it the bore's polygon
#: degenerates before the solid is made.
MIN_BORE = 1.0
#: Least module (mm): finer teeth do not print on any printer, and far below it the rack
#: cutter's tooth degenerates.
MIN_MODULE = 0.1
#: Least gear thickness (mm): a few layers of any printer; far below it the extrusion is flat
#: and no solid.
MIN_THICKNESS = 0.5


def _law_turns(value: int) -> int:
    """Pinion turns per carrier turn, one of those the crank law takes."""
    if value not in TURNS:
        raise PydanticCustomError("turns", TURNS_LIMIT)
    return value


def paper_design_distance(center: float | None, install: float | None) -> float:
    """The paper teeth's design distance L_p (mm): the centre distance given, else the
    installed distance (the source's 144 when none) less the source's 0.5 mm opening."""
    if center is not None:
        return float(center)
    return (DEFAULT_INSTALL if install is None else float(install)) - PAPER_OPENING


class Teeth(Choice):
    """How the teeth are made: generated conjugate teeth (SPEC §9) or the paper's involutes (§5)."""

    generated = "generated"
    paper = "paper"


class Corner(Choice):
    """What the generated pinion centres on each pitch-curve corner."""

    space = "space"
    tooth = "tooth"


class BoreShape(Choice):
    """The shaft hole of each gear: round, D-flat (motor shafts), DIN 6885 keyway, hexagon."""

    round = "round"
    d_flat = "d-flat"
    keyway = "keyway"
    hex = "hex"


#: Settings of the rack cutter and the generator: they shape generated teeth only, and a
#: remedy may return them to their defaults (which give pairs within the bounds across the
#: design space: benchmarks/design_space.py).
GENERATOR_SETTINGS = ("tilt", "pressure_angle", "addendum", "dedendum", "fillet", "clearance",
                      "blend", "corner")


class GearPairSpec(BaseModel):
    """Everything that defines a printed gear pair. Lengths in mm, angles in deg.

    Numbers are kept as given (an int stays an int) so reports repeat the user's figures.
    """

    model_config = STRICT

    a: Number = length(60.0, le=MAX_LENGTH)
    b: Number = length(100.0, le=MAX_LENGTH)
    c: Number = length(360.0, le=MAX_LENGTH)
    z: Whole = quantity(48, limit=f"must be {MIN_TEETH}..{MAX_TEETH} (pinion teeth)", strict=True,
                      ge=MIN_TEETH, le=MAX_TEETH)
    turns: Annotated[Whole, AfterValidator(_law_turns)] = quantity(2, limit=TURNS_LIMIT, strict=True)
    # generated teeth: the distance the pitch curves roll at (None: the installed distance, or
    # the one a --module fits); paper teeth: the sectors' design distance L_p (None: the
    # installed less the source's 0.5 mm opening, 143.5)
    center_distance: Optional[Number] = length(None, ge=MIN_DISTANCE, le=MAX_DISTANCE)
    # the distance the pair is mounted and checked at (None: where generated teeth roll;
    # paper teeth L_p + 0.5 mm; 144 when neither is given)
    install_distance: Optional[Number] = length(None, ge=MIN_DISTANCE, le=MAX_DISTANCE)
    # generated teeth: None takes the module from the pitch curves at the distance; a module
    # solves the design centre distance for it (SPEC §9). Paper teeth: None is 2 mm.
    module: Optional[Number] = length(None, ge=MIN_MODULE)
    backlash: Optional[Number] = length(None, ge=0)   # None: 0.25 * module (2 mm when none)
    thickness: Number = length(10.0, ge=MIN_THICKNESS, limit=f"must be >= {MIN_THICKNESS:g} mm, and at least twice "
                               "the mark depth (1 mm with the default 0.5 mm marks)")
    bore: Number = length(8.0, ge=0)   # shaft diameter; across flats for a hex bore
    bore_shape: BoreShape = BoreShape.round.value
    flat_depth: Optional[Number] = length(None, gt=0)  # d-flat; None: 0.1 x bore
    key_width: Optional[Number] = length(None, gt=0)   # keyway; None: DIN 6885 b of the bore
    key_depth: Optional[Number] = length(None, gt=0)   # keyway hub depth t2; None: DIN 6885
    key_angle: Number = quantity(0.0, unit="deg", limit="must be -360..360 deg", ge=-360, le=360)
    mark_depth: Number = length(0.5, ge=0, le=2)       # timing mark engraving, 0: none
    lighten: bool = Field(False, strict=True)          # spoked pockets in the wheel (and pinion)
    # 45 deg top/bottom edges, 0: none; None: the printer's (config.printers), else none
    chamfer: Optional[Number] = length(None, ge=0, le=5)
    hub_d: Optional[Number] = length(None, gt=0)       # boss on the top face round the bore
    set_screw: Optional[str] = Field(None, strict=True)  # M2..M6 radial screw + nut in the hub
    hub_length: Optional[Number] = length(None, gt=0, le=MAX_LENGTH)  # None: 8 mm with a hub
    teeth: Teeth = Teeth.generated.value
    # generated teeth: the rack cutter's tooth form (the dedendum must also exceed the addendum)
    pressure_angle: Number = quantity(20.0, unit="deg", limit=range_text(PRESSURE_ANGLE_DEG, "deg"),
                                      ge=PRESSURE_ANGLE_DEG[0], le=PRESSURE_ANGLE_DEG[1])
    addendum: Number = quantity(1.0, limit=range_text(ADDENDUM, "x module"), ge=ADDENDUM[0], le=ADDENDUM[1])
    dedendum: Number = quantity(1.25, limit=f"must be above the addendum and <= {DEDENDUM_MAX:g} x module",
                                gt=0, le=DEDENDUM_MAX)
    fillet: Number = quantity(0.25, limit=range_text(FILLET, "x module"), ge=FILLET[0], le=FILLET[1])  # tip radius
    # the wheel's spaces below the pinion's tips
    clearance: Number = quantity(0.25, limit=range_text(CLEARANCE, "x module"), ge=CLEARANCE[0], le=CLEARANCE[1])
    blend: Number = quantity(0.0, unit="deg", limit="must be 0..20 deg", ge=0, le=20)
    corner: Corner = Corner.space.value
    tilt: Number = quantity(0.6, limit="must be 0..1.5", ge=0, le=1.5)
    law_csv: Optional[str] = Field(None, strict=True)  # driving/driven angle samples (deg)

    @model_validator(mode="before")
    @classmethod
    def _bore_defaults(cls, values):
        """Fill the key and flat from the bore (so a printer's hole compensation widens them
        as given), and refuse dimensions the shape does not use."""
        if not isinstance(values, dict):
            return values
        return bore_defaults(strut_default(values))

    @model_validator(mode="after")
    def _distances(self) -> "GearPairSpec":
        require(self.law_csv is None or self.teeth == Teeth.generated, "law_csv", self.law_csv,
                "needs generated teeth")
        if self.teeth == Teeth.paper:
            self._generator_settings_unset()
            center, install = self.paper_distances
            if not install >= center:
                raise DesignError("install_distance", install,
                                  f"must be >= the centre distance {center:g} mm",
                                  {"center_distance": (center, "must be <= the installed "
                                                       f"distance {install:g} mm")})
            require(install <= center + self.paper_module, "install_distance", install,
                    f"must be <= the centre distance + module = {center + self.paper_module:g} mm "
                    "(farther apart the teeth lose contact)")
        elif self.module is not None and self.center_distance is not None:
            # the module fixes the perimeter, so the distance the pitch curves roll at
            raise DesignError("center_distance", self.center_distance,
                              "cannot be combined with --module: generated teeth roll at the "
                              "distance the module fits (SPEC §9)",
                              {"module": (self.module, "cannot be combined with --center-distance: "
                                          "generated teeth roll at the distance the module "
                                          "fits (SPEC §9)")})
        if self.teeth == Teeth.generated:
            # the rack's own rules (the dedendum above the addendum) with the other values', before
            # any tooth is cut: a rule of the tooth form is not blamed on what sizes the pair
            self.cutter()
        shaft_rules(self)
        return self

    def _generator_settings_unset(self) -> None:
        """Paper teeth are the source's sector involutes: the rack cutter's and the
        generator's settings do not shape them, so one changed from its default is refused
        rather than ignored."""
        for name in GENERATOR_SETTINGS:
            value, default = getattr(self, name), type(self).model_fields[name].default
            require(getattr(value, "value", value) == getattr(default, "value", default), name,
                    getattr(value, "value", value),
                    "shapes generated teeth only (the paper teeth are the source's sector involutes)")

    def sizing(self) -> dict[str, object]:
        """The inputs that set the pitch curves and the size of the teeth (name -> value as
        given, None: not set): a rule the pair breaks may be any of theirs to mend."""
        return {"a": self.a, "b": self.b, "c": self.c, "center_distance": self.center_distance,
                "install_distance": self.install_distance, "module": self.module,
                "turns": self.turns, "z": self.z}

    @property
    def hub_mm(self) -> tuple[float, float]:
        """Hub diameter and length above the top face (mm); (0, 0) without a hub."""
        if self.hub_d is None:
            return 0.0, 0.0
        return float(self.hub_d), 8.0 if self.hub_length is None else float(self.hub_length)

    @property
    def paper_distances(self) -> tuple[float, float]:
        """The paper teeth's design distance L_p and installed distance (mm): as given, else
        the source's 0.5 mm apart (143.5 and 144 when neither is given)."""
        center = paper_design_distance(self.center_distance, self.install_distance)
        given = self.install_distance
        if self.center_distance is not None:
            return center, float(given) if given is not None else center + PAPER_OPENING
        return center, DEFAULT_INSTALL if given is None else float(given)

    @property
    def chamfer_mm(self) -> float:
        """The edge chamfer drawn (mm): the one given, 0 when none is (a printer's fills it in
        parts.kinds.printed_spec before the part is built)."""
        return 0.0 if self.chamfer is None else float(self.chamfer)

    @property
    def backlash_mm(self) -> float:
        return PAPER_BACKLASH_PER_MODULE * self.paper_module if self.backlash is None else self.backlash

    @property
    def paper_module(self) -> float:
        """The module (mm) the paper teeth and the default backlash use: 2 when none is given."""
        return 2.0 if self.module is None else self.module

    def mechanism(self):
        """The crank mechanism (mechanism.crank.CrankMechanism); DesignError for an impossible one."""
        from wheelstep_cli.mechanism.crank import CrankMechanism

        return CrankMechanism(self.a, self.b, self.c)

    def law(self):
        """The crank law of the pair (gears.laws.CrankLaw)."""
        from wheelstep_cli.gears.laws import CrankLaw

        return CrankLaw(self.mechanism(), self.turns)

    def tooth_form(self):
        from wheelstep_cli.gears.paper_teeth import ToothForm

        return ToothForm(self.paper_module, self.backlash_mm)

    def cutter(self):
        from wheelstep_cli.gears.generation import RackCutter

        return RackCutter(np.radians(self.pressure_angle), self.addendum, self.dedendum,
                          self.fillet, self.backlash_mm, self.clearance)


def strut_default(values: dict) -> dict:
    """``values`` (a GearPairSpec's raw fields) with the strut c filled when not given: the
    source's R_min = 20 mm for the given a and b (c = R_min - a + 4b), as the shoe takes it,
    so a gear pair and a shoe of the same a and b follow one mechanism."""
    if values.get("c") is not None:
        return values
    a, b = values.get("a", 60.0), values.get("b", 100.0)
    if not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in (a, b)):
        return values   # the field checks say what is wrong with them
    from wheelstep_cli.mechanism.crank import CrankMechanism

    c = CrankMechanism.from_r_min(a, b, DEFAULT_R_MIN).c     # refuses a and b no strut fits
    if c > MAX_LENGTH:
        # the strut nobody gave is the given a and b's: said of them, with their own limits
        why = f"(the strut c = R_min - a + 4b = {c:g} mm they set must be <= {MAX_LENGTH:g} mm)"
        raise DesignError("c", c, f"must be <= {MAX_LENGTH:g} mm", {
            "b": (b, f"must be <= {float(rounded_down((MAX_LENGTH - DEFAULT_R_MIN + a) / 4.0)):g} mm {why}"),
            "a": (a, f"must be >= {float(rounded_up(DEFAULT_R_MIN + 4.0 * b - MAX_LENGTH)):g} mm {why}")})
    return {**values, "c": c}


def strut_contradiction(a: float, b: float, c: float, r_min: float) -> str | None:
    """Why a strut given both as ``c`` and as ``r_min`` contradicts itself (a limit's words),
    None when R_min = a - 4b + c holds (mm)."""
    got = a - 4.0 * b + c
    if np.isclose(got, r_min, rtol=0, atol=1e-6):
        return None
    return f"contradicts c = {c:g} mm (a - 4b + c = {got:g} mm); give only one of c and R_min"


class ShoeSpec(BaseModel):
    """Everything that defines a printed shoe. Lengths in mm, stored as floats.

    Mechanism defaults are the source design (a = 60, b = 100, R_min = 20 -> c = 360).
    Give the strut as ``c`` or as the sole's smallest curvature radius ``r_min``
    (both: they must agree). Part defaults suit a plastic prototype at full scale.
    """

    model_config = STRICT

    a: Real = length(60.0, le=MAX_LENGTH)
    b: Real = length(100.0, le=MAX_LENGTH)
    c: Optional[Real] = length(None, le=MAX_LENGTH)
    r_min: Optional[Real] = length(None, le=MAX_LENGTH)
    width: Real = length(40.0, gt=0)            # across the track
    strut_diameter: Real = length(12.0, ge=MIN_BORE)   # socket bore (circumscribed polygon, the strut fits)
    socket_depth: Real = length(25.0, gt=0)
    rim: Real = length(15.0, ge=MIN_SHOE_WALL)  # body height above the sole's ends

    def design(self):
        """The mechanism sizing (mechanism.crank.CrankMechanism); DesignError for an invalid or
        inconsistent one."""
        from wheelstep_cli.mechanism.crank import CrankMechanism

        if self.c is None:
            r_min = DEFAULT_R_MIN if self.r_min is None else self.r_min
            return CrankMechanism.from_r_min(self.a, self.b, r_min)
        # both given: their contradiction first (a limit of c alone would lead to it)
        if self.r_min is not None and (why := strut_contradiction(self.a, self.b, self.c, self.r_min)):
            raise DesignError("r_min", self.r_min, why)
        return CrankMechanism(self.a, self.b, self.c)
