"""depo: particle deposition, the Brach & Dunn (1998) rebound/capture wall law for Python.

The law on numpy arrays, in place and without copies::

    import numpy as np, depo
    law = depo.WallLaw.preset("li1997-sio2")
    vx, vy, vz = np.zeros(3), np.zeros(3), np.array([-1.0, -0.05, 0.2])
    outcome = law.apply(vx, vy, vz, normal=(0, 0, 1))   # vz is now the rebound velocity
    outcome.tolist() == [depo.REBOUND, depo.CAPTURED, depo.SKIPPED]

The room and channel studies, as the `depo` command runs them::

    result = depo.room({"particles": {"diameters": [1e-6, 5e-6], "count": 200}}, seed=1)
    result.beta_per_hour, result.to_dict()      # the dict is `depo room --format json`'s

Everything is in SI units (m/s, rad/s, m, J/kg). The outcome codes and capture modes are the C
library's (depo.h). See docs/python.md in the repository.
"""

from depo._depo import (
    CAPTURE_DEPOSIT,
    CAPTURE_KEEP_ON_WALL,
    CAPTURED,
    INVALID,
    MAX_THREADS,
    PARALLEL_MIN,
    REBOUND,
    SKIPPED,
    Tally,
    WallLaw,
    __version__,
    capture_velocity,
    fit,
    presets,
    set_num_threads,
)
from depo._studies import ChannelResult, ChannelRun, DecayCurve, RoomResult, channel, room

__all__ = [
    "CAPTURE_DEPOSIT",
    "ChannelResult",
    "ChannelRun",
    "DecayCurve",
    "RoomResult",
    "channel",
    "room",
    "CAPTURE_KEEP_ON_WALL",
    "CAPTURED",
    "INVALID",
    "MAX_THREADS",
    "PARALLEL_MIN",
    "REBOUND",
    "SKIPPED",
    "Tally",
    "WallLaw",
    "__version__",
    "capture_velocity",
    "fit",
    "presets",
    "set_num_threads",
]
