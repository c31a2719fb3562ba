"""A batch file: the parts to print, each a kind built from a design preset for a printer.

Entry values missing from an entry come from ``defaults:``; the kind's parameters in
``overrides:`` are checked against the kind's spec once the kind is known.
"""

from __future__ import annotations

from typing import Annotated, Any, Optional

from pydantic import BaseModel, Field

from wheelstep_cli.config.fields import STRICT, Choice, Whole


class KindName(Choice):
    """The part kinds a batch can build."""

    gear_pair = "gear-pair"
    shoe = "shoe"


KIND_NAMES = tuple(k.value for k in KindName)
MAX_QUANTITY = 200
NAME_PATTERN = r"^[A-Za-z0-9][A-Za-z0-9._-]*$"
#: The design preset of an entry that names none.
DEFAULT_DESIGN = "bntu-2024"

Kind = Annotated[Optional[KindName], Field(
    None, json_schema_extra={"limit": "unknown kind; allowed: " + ", ".join(KIND_NAMES)})]
ProfileName = Annotated[Optional[str], Field(
    None, strict=True, json_schema_extra={"limit": "must be a profile name"})]
# a whole number as z is (2.0 is 2), so that a quantity is read as every count is
Quantity = Annotated[Optional[Whole], Field(
    None, strict=True, ge=1, le=MAX_QUANTITY,
    json_schema_extra={"limit": f"must be between 1 and {MAX_QUANTITY}"})]


class BatchDefaults(BaseModel):
    """What an entry leaves out."""

    model_config = STRICT

    kind: Kind
    design: ProfileName
    printer: ProfileName
    quantity: Quantity


class BatchEntry(BaseModel):
    """One entry of ``parts:``."""

    model_config = STRICT

    name: Optional[str] = Field(None, strict=True, pattern=NAME_PATTERN, max_length=64, json_schema_extra={
        "limit": "must be 1..64 letters, digits, '.', '_' or '-', starting with a letter or digit "
                 "(it names the entry's files)"})
    kind: Kind
    design: ProfileName
    overrides: Optional[dict[str, Any]] = None
    quantity: Quantity
    printer: ProfileName
    allow_interference: Optional[bool] = Field(None, strict=True, json_schema_extra={
        "limit": "must be true or false (gear-pair entries: build a pair whose teeth interfere)"})


class BatchFile(BaseModel):
    """The whole batch file."""

    model_config = STRICT

    description: Optional[str] = Field(None, strict=True)
    defaults: Optional[BatchDefaults] = None
    parts: list[BatchEntry] = Field(min_length=1, json_schema_extra={
        "limit": "must be a list of at least one part"})
