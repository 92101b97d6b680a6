"""Type stubs of depo's native module (depo._depo), re-exported by the package depo.

Every quantity is in SI units: m/s, rad/s, m, kg/m^3, Pa, J/m^2, J/kg.
"""

import os
from typing import Any, Callable, Dict, List, Literal, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str
"""The Cargo version of the package, e.g. "0.1.0" (the C library's DEPO_VERSION)."""

REBOUND: int
"""Outcome 0: the particle hit the wall and rebounded; velocity (and spin) updated."""
CAPTURED: int
"""Outcome 1: the particle hit the wall and was captured; velocity (and spin) zero, or with
CAPTURE_KEEP_ON_WALL only the normal velocity."""
SKIPPED: int
"""Outcome 2: not an impact (v . n >= 0); untouched."""
INVALID: int
"""Outcome 3: non-finite velocity or spin, a bad radius (with spin) or a per-particle normal
not of unit length within 1e-4; untouched."""
CAPTURE_DEPOSIT: int
"""Capture mode 0: a captured particle is deposited where it hit, velocity and spin zero."""
CAPTURE_KEEP_ON_WALL: int
"""Capture mode 1: a captured particle stays on the wall with zero normal velocity."""
PARALLEL_MIN: int
"""Batches of this many particles (65536) or more may run on several threads."""
MAX_THREADS: int
"""The largest thread count set_num_threads accepts (1024)."""

FloatArray = Union[npt.NDArray[np.float64], npt.NDArray[np.float32]]
CaptureMode = Union[int, Literal["deposit", "keep-on-wall", "keep_on_wall"]]

class Tally:
    """Counts of each outcome over one or more apply calls, and the energy lost by each
    mechanism, summed over impacts per unit particle mass (J/kg; multiply by the particle mass
    for joules). Tally() starts at zero; law.apply(..., tally=t) adds to it; tallies add with +."""

    def __init__(
        self,
        *,
        rebound: int = 0,
        captured: int = 0,
        skipped: int = 0,
        invalid: int = 0,
        energy_material: float = 0.0,
        energy_adhesion: float = 0.0,
        energy_friction: float = 0.0,
        energy_deposition: float = 0.0,
    ) -> None: ...
    @property
    def rebound(self) -> int:
        """Particles that rebounded."""
    @property
    def captured(self) -> int:
        """Particles captured."""
    @property
    def skipped(self) -> int:
        """Particles skipped (not an impact)."""
    @property
    def invalid(self) -> int:
        """Particles flagged invalid."""
    @property
    def energy_material(self) -> float:
        """Material dissipation T_n (1 - R^2), J/kg summed over impacts."""
    @property
    def energy_adhesion(self) -> float:
        """Adhesion dissipation T_n R^2 rho (2 - rho), J/kg summed over impacts."""
    @property
    def energy_friction(self) -> float:
        """Friction dissipation, J/kg summed over impacts."""
    @property
    def energy_deposition(self) -> float:
        """Kinetic energy carried onto the wall by deposited particles, J/kg summed over impacts."""
    @property
    def particles(self) -> int:
        """Particles counted, whatever their outcome."""
    def to_dict(self) -> Dict[str, Union[int, float]]:
        """The fields as a dict."""
    def __add__(self, other: "Tally") -> "Tally": ...

class WallLaw:
    """The Brach & Dunn (1998) rebound/capture law with validated constants (SI units).

    - k1, k2: material restitution velocities of Eq. (8), m/s, finite and > 0.
    - kappa1, kappa2: adhesion velocities of Eq. (9), m/s, finite and > 0.
    - p, q: the exponents of Eqs. (8) and (9), finite and > 0.
    - vc: capture velocity, m/s, finite; <= 0 means the law never captures by speed.
    - mu: Coulomb friction coefficient of the contact, finite and >= 0.
    - capture_mode: CAPTURE_DEPOSIT (default) or CAPTURE_KEEP_ON_WALL.

    A value out of range is a ValueError naming it. Laws are immutable, compare equal by
    value, and pickle."""

    def __init__(
        self,
        k1: float,
        k2: float,
        kappa1: float,
        kappa2: float,
        p: float = 1.0,
        q: float = 1.0,
        *,
        vc: float,
        mu: float = 0.0,
        capture_mode: Optional[CaptureMode] = None,
    ) -> None: ...
    @staticmethod
    def preset(id: str) -> "WallLaw":
        """The law of a row of the paper's Table 1 by id (e.g. "li1997-sio2"), friction 0. An
        unknown id is a ValueError listing the known ones (see presets())."""
    @property
    def params(self) -> Dict[str, float]:
        """The constants as a dict: k1, k2, kappa1, kappa2 (m/s), p, q, vc (m/s), mu."""
    @property
    def capture_mode(self) -> int:
        """CAPTURE_DEPOSIT (0) or CAPTURE_KEEP_ON_WALL (1)."""
    def with_capture_mode(self, mode: CaptureMode) -> "WallLaw":
        """A copy of the law that treats captured particles by mode: CAPTURE_DEPOSIT /
        "deposit" or CAPTURE_KEEP_ON_WALL / "keep-on-wall"."""
    def coefficients(
        self, vn: npt.ArrayLike
    ) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.bool_]]:
        """The law's coefficients (e, R, rho, captured) at normal speeds vn (m/s, any
        array-like; the sign is ignored): overall restitution e = R (1 - rho) (Eq. 2), material
        restitution R (Eq. 8), adhesion rho (Eq. 9, 1 where captured), and True where captured.
        Each has the shape of vn. A non-finite vn is a ValueError."""
    def apply(
        self,
        vx: FloatArray,
        vy: FloatArray,
        vz: FloatArray,
        normal: Sequence[float] = (0.0, 0.0, 1.0),
        wx: Optional[FloatArray] = None,
        wy: Optional[FloatArray] = None,
        wz: Optional[FloatArray] = None,
        radius: Optional[FloatArray] = None,
        nx: Optional[FloatArray] = None,
        ny: Optional[FloatArray] = None,
        nz: Optional[FloatArray] = None,
        capture_velocity: Optional[FloatArray] = None,
        tally: Optional[Tally] = None,
        out: Optional[npt.NDArray[np.uint8]] = None,
    ) -> npt.NDArray[np.uint8]:
        """Applies the law to a batch of wall contacts, in place, and returns one outcome per
        particle as a uint8 array: REBOUND (0), CAPTURED (1), SKIPPED (2, not an impact) or
        INVALID (3, left untouched).

        - vx, vy, vz: velocity (m/s), updated in place; 1-D numpy arrays, all float64 or all
          float32 (a TypeError otherwise), of one length.
        - normal: the wall's unit normal into the fluid for the whole batch (within 1e-4 of
          unit length), used unless nx, ny, nz are given.
        - wx, wy, wz: spin (rad/s), updated in place, with radius (m): all four or none.
        - nx, ny, nz: one unit normal per particle.
        - capture_velocity: one capture velocity per particle (m/s), in place of the law's vc.
        - tally: a Tally that this call's counts and energy are added to.
        - out: a uint8 array of n to write the outcomes into and return, in place of a new one.

        Contiguous arrays are used in place, without a copy; strided views (a column of an
        (n, 3) array) are gathered into a copy and written back, with the same results bit for
        bit. The GIL is released while the law runs. Results are those of the C library's
        depo_apply_f64 / depo_apply_f32 on the same values, bit for bit."""

def presets() -> List[Dict[str, Any]]:
    """The paper's Table 1 as depo ships it, one dict per row, as `depo presets --format json`
    prints it: id, source, particle, surface (what the row stands for), k, kappa, vc (m/s), p,
    q, mu, restitution_at_vc (R(vc) for vc > 0, else None), table_last_column and
    reconstructed. WallLaw.preset(id) makes the law."""

def fit(
    vn: npt.ArrayLike,
    e: npt.ArrayLike,
    p: float = 1.0,
    q: float = 1.0,
    weight: Optional[npt.ArrayLike] = None,
    free_exponents: bool = False,
    surface: str = "floor",
) -> Dict[str, Any]:
    """Fits the law (Eq. 10: k1 = k2 = k, kappa1 = kappa2 = kappa) to measured restitution by
    nonlinear least squares, as `depo fit` does.

    - vn: normal impact speeds (m/s; the sign is ignored, zero is not an impact).
    - e: measured overall restitution, in [0, 1], one per speed.
    - p, q: the exponents, held fixed unless free_exponents (then the starting values).
    - weight: positive weights of the residuals (default all 1).
    - surface: the scene-file key the returned scene entry is for.

    Returns the dict `depo fit --format json` prints: k, kappa, vc (m/s), p, q, k_se, kappa_se,
    vc_se, p_se, q_se (standard errors), vc_low, vc_high (95 % interval of vc, m/s),
    fitting_index (R^2 of e), rmse, vc_extrapolated, samples and scene_entry. A failed fit is a
    ValueError saying what to try; an extrapolated vc is a UserWarning."""

def capture_velocity(
    *,
    density: float,
    particle_modulus: float,
    particle_poisson: float,
    wall_modulus: float,
    wall_poisson: float,
    work_of_adhesion: float,
    diameters: Optional[npt.ArrayLike] = (1e-7, 3e-7, 1e-6, 3e-6, 1e-5, 3e-5, 1e-4),
    separation: float = 4e-10,
    yield_pressure: Optional[float] = None,
    hamaker: Optional[float] = None,
    restitution: Optional[float] = None,
) -> Dict[str, Any]:
    """The capture velocity from material properties, per diameter, as `depo capture-velocity`
    gives it (JKR after Thornton & Ning 1998; Dahneke 1971 with a Hamaker constant).

    density (kg/m^3); particle_modulus, wall_modulus (Pa; wall_modulus=inf: rigid wall);
    particle_poisson, wall_poisson in [-1, 0.5]; work_of_adhesion (J/m^2); diameters (m);
    separation at contact (m); yield_pressure (Pa); hamaker (J) with restitution in (0, 1].

    Returns the dict of `depo capture-velocity --format json`: effective_modulus (Pa),
    yield_velocity (m/s or None) and rows, one dict per diameter: diameter (m),
    jkr_capture_velocity (m/s), jkr_energy_loss (J), tabor_parameter, contact_regime,
    elastic, dahneke_capture_velocity (m/s or None)."""

def set_num_threads(n: int) -> None:
    """How many threads depo runs a large batch on (PARALLEL_MIN particles or more): 0 (the
    default) one per core, 1 the calling thread only, 2 to MAX_THREADS a pool of depo's own.
    A study (depo.room, depo.channel) runs its particles likewise: one thread per core (0), a
    single thread (1), or the pool of n. Process-wide; results are identical, bit for bit, for
    every setting."""

def _room(
    scene: Union[None, str, "os.PathLike[str]", Dict[str, Any]] = None,
    seed: Optional[int] = None,
    report: Optional[Callable[[str, int, int], None]] = None,
) -> Tuple[str, List[str], float]:
    """depo.room's engine: runs the room study of `scene` with the GIL released, watching for
    Ctrl-C, and returns (the JSON `depo room --format json` prints, the scene reader's
    warnings, the runs' seconds). `report(what, done, total)` is called on the calling thread
    as sizes complete. Use depo.room."""

def _channel(
    scene: Union[None, str, "os.PathLike[str]", Dict[str, Any]] = None,
    seed: Optional[int] = None,
    tau_plus: Optional[Sequence[float]] = None,
    near_wall: Optional[str] = None,
    report: Optional[Callable[[str, int, int], None]] = None,
) -> List[Tuple[str, str, float]]:
    """depo.channel's engine: one (name, JSON of `depo channel --format json`, seconds) per
    run. Use depo.channel."""

def _bench_apply(
    law: WallLaw,
    vx: npt.NDArray[np.float64],
    vy: npt.NDArray[np.float64],
    vz: npt.NDArray[np.float64],
    repeats: int,
    calls: int = 1,
) -> List[float]:
    """For the benchmark (python/benches/apply.py) only: times `calls` consecutive WallLaw::apply calls
    in Rust on a copy of (vx, vy, vz), normal (0, 0, 1), `repeats` times; seconds per repeat."""
