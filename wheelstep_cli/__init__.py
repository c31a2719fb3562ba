"""wheelstep: design tool for wheel-step movers (non-circular gears, support shoes)."""

__version__ = "0.1.0"
