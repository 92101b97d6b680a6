"""The room and channel studies from Python: depo.room and depo.channel, and their results.

The native module runs each study (python/src/studies.rs) and returns the JSON the `depo`
command prints for it; the result objects here read that JSON, so that ``to_dict()`` is
``depo room --format json`` for the same scene and seed, and give numpy arrays and, where pandas
is installed, DataFrames.
"""

import copy
import json
import os
import sys
import warnings
from typing import Any, Callable, Dict, List, NamedTuple, Optional, Sequence, Union

import numpy as np

from depo import _depo

__all__ = ["ChannelResult", "ChannelRun", "DecayCurve", "RoomResult", "channel", "room"]


class DecayCurve(NamedTuple):
    """The airborne share of one size's release over the run, as numpy arrays."""

    times_s: np.ndarray
    """Sample times, s."""
    airborne: np.ndarray
    """The share of the released particles still airborne."""
    error: np.ndarray
    """Its standard error."""
    count: np.ndarray
    """The airborne particles counted."""


class RoomResult:
    """A room study's result: what ``depo room --format json`` prints, with numpy views.

    Attributes:
        sizes: one dict per size (per bin with a size distribution), the JSON's rows.
        diameters_um: the sizes' diameters, um (numpy array).
        beta_per_hour, beta_error_per_hour: the loss rate by deposition and its standard error,
            1/h, per size.
        decay: one DecayCurve per size.
        maps: one dict per size, surface name -> 2-D array of deposit counts (rows over the
            map's ``rows`` axis, columns over its ``columns`` axis, as in the JSON).
        seconds: the runs' wall-clock time, s (not part of the JSON).
        warnings: the scene reader's warnings (also issued as UserWarning).
    """

    def __init__(self, report, seconds, warnings_=()):
        self._report = report
        self.seconds = seconds
        self.warnings = list(warnings_)
        self.sizes = report["sizes"]
        self.diameters_um = np.array([r["diameter_um"] for r in self.sizes], dtype=float)
        self.beta_per_hour = np.array([r["beta_per_hour"]["value"] for r in self.sizes], dtype=float)
        self.beta_error_per_hour = np.array([r["beta_per_hour"]["error"] for r in self.sizes], dtype=float)
        self.decay = [
            DecayCurve(
                np.array(r["decay"]["times_s"], dtype=float),
                np.array(r["decay"]["airborne"], dtype=float),
                np.array(r["decay"]["error"], dtype=float),
                np.array(r["decay"]["count"], dtype=np.int64),
            )
            for r in self.sizes
        ]
        self.maps = [
            {m["surface"]: np.array(m["cells"], dtype=np.uint32) for m in r["maps"]} for r in self.sizes
        ]

    def __getitem__(self, key):
        """A key of the JSON's top level (``size_m``, ``air_changes_per_hour``, ...)."""
        return self._report[key]

    def to_dict(self) -> Dict[str, Any]:
        """What ``depo room --format json`` prints for the same scene and seed, as a new dict."""
        return copy.deepcopy(self._report)

    def to_pandas(self):
        """The per-size, per-surface table as a pandas DataFrame (pandas must be installed).

        One row per size and surface: floor, ceiling, walls (the four together), x0, x1, y0,
        y1, and each furnishing face as ``NAME.FACE``. Columns: diameter_um, density (kg/m^3),
        surface, velocity (deposition velocity, m/s), error (its standard error, m/s), events
        (deposit events it rests on), upper_bound (95 % bound where there is no event, else
        NaN), lai_nazaroff (the model's velocity for floor, ceiling and walls, else NaN),
        deposited (tracked particles deposited over the run), deposited_kg, beta_per_hour
        (the size's loss rate, 1/h).
        """
        import pandas as pd

        records = []
        for r in self.sizes:
            base = {"diameter_um": r["diameter_um"], "density": r["density"]}
            beta = r["beta_per_hour"]["value"]

            def add(surface, m, model, deposited, kg):
                bound = m["upper_bound"]
                records.append(
                    dict(
                        base,
                        surface=surface,
                        velocity=m["value"],
                        error=m["error"],
                        events=m["events"],
                        upper_bound=np.nan if bound is None else bound,
                        lai_nazaroff=model,
                        deposited=deposited,
                        deposited_kg=kg,
                        beta_per_hour=beta,
                    )
                )

            for s in ("floor", "ceiling", "walls"):
                add(s, r[s], r["lai_nazaroff"][s], r["deposited"][s], r["deposited"][s + "_kg"])
            for w in r["each_wall"]:
                add(w["wall"], w["velocity"], np.nan, w["deposited"], w["deposited_kg"])
            for f in r.get("furnishings", []):
                for face in f["faces"]:
                    add(f"{f['name']}.{face['face']}", face["velocity"], np.nan, face["deposited"], face["deposited_kg"])
        return pd.DataFrame.from_records(records)

    def __repr__(self):
        sizes = ", ".join(f"{d:g}" for d in self.diameters_um)
        return f"<depo.RoomResult: {len(self.sizes)} sizes ({sizes} um), {self.seconds:.1f} s>"


class ChannelRun:
    """One run of a channel study: ``name`` (``depo, resolved`` or ``depo, wall function``),
    its points (the JSON's), numpy arrays of tau_plus, v_plus and v_plus_error, and seconds."""

    def __init__(self, name, report, seconds):
        self.name = name
        self._report = report
        self.seconds = seconds
        self.points = report["points"]
        self.tau_plus = np.array([p["tau_plus"] for p in self.points], dtype=float)
        self.v_plus = np.array([p["v_plus"]["value"] for p in self.points], dtype=float)
        self.v_plus_error = np.array([p["v_plus"]["error"] for p in self.points], dtype=float)
        self.wood = np.array([p["wood"] for p in self.points], dtype=float)

    def __getitem__(self, key):
        return self._report[key]

    def to_dict(self) -> Dict[str, Any]:
        """What ``depo channel --format json`` prints for this run, as a new dict."""
        return copy.deepcopy(self._report)

    def to_pandas(self):
        """One row per tau+: tau_plus, diameter_um, v_plus, error, events, wood,
        papavergos_hedley, method (pandas must be installed)."""
        import pandas as pd

        return pd.DataFrame.from_records(
            [
                {
                    "tau_plus": p["tau_plus"],
                    "diameter_um": p["diameter_um"],
                    "v_plus": p["v_plus"]["value"],
                    "error": p["v_plus"]["error"],
                    "events": p["v_plus"]["events"],
                    "wood": p["wood"],
                    "papavergos_hedley": p["papavergos_hedley"],
                    "method": p["method"],
                }
                for p in self.points
            ]
        )

    def __repr__(self):
        return f"<depo.ChannelRun {self.name!r}: {len(self.points)} points, {self.seconds:.1f} s>"


class ChannelResult:
    """A channel study's result: ``runs``, one ChannelRun per near-wall model run (two with
    ``near_wall="all"``)."""

    def __init__(self, runs):
        self.runs = runs

    def to_dict(self) -> List[Dict[str, Any]]:
        """What ``depo channel --format json`` prints, one dict per run, as a list."""
        return [run.to_dict() for run in self.runs]

    def to_pandas(self):
        """The runs' tables one after the other, with a column ``run`` naming each."""
        import pandas as pd

        return pd.concat([run.to_pandas().assign(run=run.name) for run in self.runs], ignore_index=True)

    def __repr__(self):
        return f"<depo.ChannelResult: {', '.join(repr(r.name) for r in self.runs)}>"


def _reporter(progress):
    """The native module's report(what, done, total) for ``progress``: None, a bar (tqdm if
    installed, else a line of text on stderr), or the caller's own callable."""
    if progress is None or progress is False:
        return None, lambda: None
    if callable(progress):
        return progress, lambda: None
    try:
        from tqdm.auto import tqdm
    except ImportError:
        tqdm = None
    state = {"bar": None, "what": None}

    def report(what, done, total):
        if tqdm is not None:
            if state["bar"] is None or state["what"] != what:
                if state["bar"] is not None:
                    state["bar"].close()
                state["bar"] = tqdm(total=total, unit=" " + what, desc="depo")
                state["what"] = what
            state["bar"].n = done
            state["bar"].refresh()
        else:
            state["what"] = what
            sys.stderr.write(f"\rdepo: {done}/{total} {what}")
            sys.stderr.flush()

    def close():
        if state["bar"] is not None:
            state["bar"].close()
        elif state["what"] is not None:
            sys.stderr.write("\n")

    return report, close


Scene = Union[None, str, "os.PathLike[str]", Dict[str, Any]]
"""A scene: None (the built-in one), a scene file's path, or a dict of its keys."""

Progress = Union[bool, Callable[[str, int, int], None]]
"""False, True (a bar) or a callable progress(what, done, total)."""


def room(scene: Scene = None, *, seed: Optional[int] = None, progress: Progress = False) -> "RoomResult":
    """Runs a room study: deposition onto the floor, ceiling, walls (and furnishings) of a
    room per particle size, beside Lai & Nazaroff (2000), as ``depo room`` does.

    Args:
        scene: None for the built-in room (4 x 3 x 2.5 m, u* = 1 cm/s, 0.01-10 um particles,
            1800 s); a path to a scene file (TOML); or a dict with the scene file's keys, e.g.
            ``{"room": {"size": [4.0, 3.0, 2.5]}, "particles": {"diameters": [1e-6], "count":
            200}, "ventilation": {"air_changes_per_hour": 0.5}}``. Every key is optional (the
            built-in room's value stands in; a value None leaves the key out);
            examples/room.toml lists them all with their units, SI throughout: lengths and
            diameters in m, times in s (``run.dt``, ``run.duration``), velocities in m/s,
            densities in kg/m^3, air changes per hour in 1/h. A ``particles.size_bins`` file
            is read relative to the current directory.
        seed: the random seed (int), instead of the scene's ``run.seed``. The same scene and
            seed give the same result, bit for bit, on any number of threads.
        progress: False (nothing shown); True for a bar per size (tqdm where installed, else
            a line on stderr); or a callable ``progress(what, done, total)`` called on this
            thread as sizes complete.

    The scene's sections and main keys (every one optional; SI units):

    - ``room``: ``size`` [Lx, Ly, height] (m; z is up).
    - ``air``: ``temperature`` (K), ``pressure`` (Pa), ``density`` (kg/m^3), ``viscosity`` (Pa s).
    - ``flow``: ``friction_velocity`` u* at the surfaces (m/s), ``core_rms`` (m/s) or
      ``core_tke`` (m^2/s^2) of the well-mixed core, ``core_time`` (s), ``blend_length`` (m).
    - ``particles``: ``diameters`` (m, one run each), ``count`` per diameter,
      ``target_error`` (relative standard error to run more particles for; 0: just count),
      ``max_count``, ``density`` (kg/m^3); or a size distribution: ``modes`` (lognormal, each
      ``count_median`` or ``mass_median`` (m), ``geometric_sd``, a share or a concentration
      (1/m^3 or kg/m^3)), ``bins``, ``bin_range`` (m), or ``size_bins`` (a CSV file).
    - ``walls``: per surface (``all``, ``floor``, ``ceiling``, ``x0``, ``x1``, ``y0``, ``y1``)
      ``{"behaviour": "sink" | "reflect" | "law", "preset": ID}`` or a law's own ``k``,
      ``kappa``, ``vc`` (m/s), ``p``, ``q``, ``mu`` (depo.fit's scene_entry).
    - ``furnishings``: a list of boxes ``{"name", "low": [x, y, z], "high": [x, y, z]}`` (m).
    - ``openings``: a list of doors, windows and vents (examples/room.toml).
    - ``ventilation``: ``air_changes_per_hour`` (1/h), ``penetration`` (0-1),
      ``supply_share`` (0-1), ``supply_filter`` (efficiency), ``recirculation_per_hour``
      (1/h), ``recirculation_filter``.
    - ``run``: ``dt`` (s), ``duration`` (s), ``transient`` (share of the run left out of the
      averages), ``seed``, ``brownian``, ``gravity`` (m/s^2), ``drag``, ``scheme``,
      ``near_wall``, ``excursions``.

    Returns:
        A RoomResult: ``to_dict()`` is what ``depo room --format json`` prints for the same
        scene and seed; numpy arrays ``diameters_um``, ``beta_per_hour`` (1/h), ``decay``
        (airborne share over time per size) and ``maps`` (deposit counts per surface);
        ``to_pandas()`` the per-size, per-surface table.

    Raises:
        ValueError: a bad scene value, with the reader's one-line message naming the key.
        TypeError: a scene value of a type TOML cannot hold, naming the key.
        KeyboardInterrupt: Ctrl-C; the study stops (within a chunk of 8 particles' work per
            thread) before this is raised, and no thread goes on running it.

    The study runs with the GIL released on the threads ``depo.set_num_threads`` gives it.
    """
    report, close = _reporter(progress)
    try:
        text, reader_warnings, seconds = _depo._room(scene, seed, report)
    finally:
        close()
    for w in reader_warnings:
        warnings.warn(w, UserWarning, stacklevel=2)
    return RoomResult(json.loads(text), seconds, reader_warnings)


def channel(
    scene: Scene = None,
    *,
    seed: Optional[int] = None,
    tau_plus: Optional[Sequence[float]] = None,
    near_wall: Optional[str] = None,
    progress: Progress = False,
) -> "ChannelResult":
    """Runs a channel study: the deposition velocity V+ against the particle relaxation time
    tau+ in a turbulent channel, beside Wood (1981) and Papavergos & Hedley (1984), as
    ``depo channel`` does.

    Args:
        scene: None for the built-in channel; a path to a scene file (TOML); or a dict with
            the scene file's keys (examples/channel.toml lists them with their units; times in
            wall units with ``run.dt_plus``, ``run.duration_plus``).
        seed: the random seed (int), instead of the scene's ``run.seed``.
        tau_plus: the dimensionless relaxation times to run (positive numbers), instead of the
            scene's ``particles.tau_plus``.
        near_wall: None (the scene's ``run.near_wall``), "resolved" (the near-wall layer
            tracked to the wall), "wall-function" (deposition at Wood's rate within the wall
            function's layer) or "all" (both, one run each).
        progress: as for depo.room, per tau+.

    Returns:
        A ChannelResult: ``runs``, each with ``to_dict()`` equal to what ``depo channel
        --format json`` prints for it, numpy arrays ``tau_plus``, ``v_plus``,
        ``v_plus_error``, ``wood``, and ``to_pandas()``.

    Raises:
        ValueError, TypeError, KeyboardInterrupt: as depo.room.
    """
    if tau_plus is not None:
        tau_plus = [float(t) for t in np.atleast_1d(np.asarray(tau_plus, dtype=float))]
    report, close = _reporter(progress)
    try:
        runs = _depo._channel(scene, seed, tau_plus, near_wall, report)
    finally:
        close()
    return ChannelResult([ChannelRun(name, json.loads(text), seconds) for name, text, seconds in runs])
