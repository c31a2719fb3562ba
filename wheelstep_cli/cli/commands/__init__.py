"""Thin Typer commands: parse, call the math, write, report. One module per command group."""

from __future__ import annotations

import typer


def register_all(app: typer.Typer) -> None:
    """Attach every command module's commands to ``app``."""
    from wheelstep_cli.cli.commands import (batch, gears, linkage, meshcheck, paper_tables, shoe, stairs,
                                           sweep, trajectory)

    paper_tables.register(app)
    gears.register(app)
    meshcheck.register(app)
    shoe.register(app)
    stairs.register(app)
    linkage.register(app)
    trajectory.register(app)
    batch.register(app)
    sweep.register(app)
