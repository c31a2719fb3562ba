"""The model of a sweep file (its keys, types and bounds), apart from reading and expanding
it (:mod:`wheelstep_cli.config.sweep_file`), so what tells a sweep file is known without it."""

from __future__ import annotations

from typing import Any, Literal, Optional

from pydantic import BaseModel, Field

from wheelstep_cli.config.fields import STRICT, Number, Whole

#: Most design points one sweep may hold (each takes seconds; more is a cluster's week).
MAX_POINTS = 10_000
#: Figures a sweep can rank designs by (columns of the results; smaller is better).
OBJECTIVES = ("drive_f_i_um", "coast_f_i_um", "drive_F_i_um", "coast_F_i_um", "drive_ripple_pct",
              "coast_ripple_pct", "backlash_max_mm", "backlash_min_mm", "volume_mm3", "mass_g")


class Range(BaseModel):
    """A grid axis from ``start`` to ``stop`` (included when hit) in steps of ``step``."""

    model_config = STRICT
    start: Number
    stop: Number
    step: Number = Field(gt=0, json_schema_extra={"limit": "must be > 0"})


class Bounds(BaseModel):
    """A random axis: uniform in [low, high]; whole numbers if both bounds are."""

    model_config = STRICT
    low: Number
    high: Number


class RandomAxes(BaseModel):
    """``samples`` seeded draws of every bounded parameter."""

    model_config = STRICT
    seed: Whole = Field(strict=True, ge=0)
    samples: Whole = Field(strict=True, ge=1, le=MAX_POINTS,
                         json_schema_extra={"limit": f"must be 1..{MAX_POINTS}"})
    bounds: dict[str, Bounds] = Field(min_length=1, json_schema_extra={
        "limit": "must map at least one parameter to {low, high}"})


class SweepFile(BaseModel):
    """The whole sweep file."""

    model_config = STRICT
    description: Optional[str] = Field(None, strict=True)
    command: Literal["gears", "shoe"]
    design: Optional[str] = Field(None, strict=True)
    printers: Optional[list[str]] = Field(None, min_length=1, json_schema_extra={
        "limit": "must name at least one printer profile (or leave `printers:` out: no printer)"})
    fixed: dict[str, Any] = {}
    grid: dict[str, Any] = {}          # name -> list of values or {start, stop, step} (a Range)
    random: Optional[dict[str, Any]] = None   # a RandomAxes, checked on its own
    objectives: Optional[list[str]] = Field(None, min_length=2, max_length=2, json_schema_extra={
        "limit": "must name two figures: " + ", ".join(OBJECTIVES) + " (a shoe's: volume_mm3, mass_g)"})
    allow_interference: bool = Field(False, strict=True)
    tolerance: bool = Field(False, strict=True)   # gears: also the check over the printer's band
