"""Planar walking linkages (SPEC §7): the solver (``solver``), the gait of a solved leg
(``gait``), the known legs (``presets``) and what ``wheelstep linkage`` reports (``study``).

The public names of the first three are re-exported here.
"""

from wheelstep_cli.mechanism.linkage.gait import Gait, gait
from wheelstep_cli.mechanism.linkage.presets import (PRESETS, chebyshev_lambda, four_bar,
                                                     four_bar_paper, jansen_leg, six_bar_source)
from wheelstep_cli.mechanism.linkage.solver import (Attached, Crank, Dyad, Fixed, Linkage, Solution,
                                                    Step, cycle_angles, is_full_cycle, joint_rates,
                                                    solve)

__all__ = ["Attached", "Crank", "Dyad", "Fixed", "Gait", "Linkage", "PRESETS", "Solution", "Step",
           "chebyshev_lambda", "cycle_angles", "four_bar", "four_bar_paper", "gait", "is_full_cycle",
           "jansen_leg", "joint_rates", "six_bar_source", "solve"]
