"""The fewest teeth a remedy that adds teeth needs (issue 13): the deviations of generated
teeth fall at least as fast as 1/z^2 on the crank law, much faster on some laws (a CSV law
measured 143 um at z 48 and 9 um at z 80), so the count a remedy's estimate reaches may be
far more than needed. Counts in whole law periods."""

from __future__ import annotations

from typing import Callable

from wheelstep_cli.errors import DesignError
from wheelstep_cli.parts.bound_figures import MeshBounds, bound_violations

#: Builds spent halving the gap between the most teeth that failed and the count that passed.
HALVING_TRIES = 3


def fewest_teeth(design, found: dict, failed: list[dict], periods: int, verify: Callable,
                 bounds: MeshBounds) -> dict:
    """``found`` (a remedy whose build is within the bounds), or, when it adds teeth to
    ``design`` (no module given: that sizes the pair with the count), the same remedy with
    fewer teeth whose build is also within them: the gap from the most teeth a ``failed``
    try (or the design) had below it is halved, each half built by ``verify(design)`` ->
    (pair, meshing record), at most HALVING_TRIES times. Only a count that built within the
    bounds is returned."""
    high = found.get("z")
    if high is None or high <= design.z or design.module is not None:
        return found
    low = max([design.z, *(c["z"] for c in failed if "z" in c and c["z"] < high)])
    for _ in range(HALVING_TRIES):
        middle = low + periods * ((high - low) // (2 * periods))
        if middle <= low:
            break
        candidate = {**found, "z": middle}
        try:
            _, record = verify(design.model_copy(update=candidate))
            within = not bound_violations(record, bounds)
        except DesignError:
            within = False
        if within:
            found, high = candidate, middle
        else:
            low = middle
    return found
