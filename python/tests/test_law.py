"""The wall law on numpy arrays: values, in-place updates, strided views, float32, tallies,
errors, and the constants shared with the C header."""

import pickle
import re

import numpy as np
import pytest

import depo


def random_batch(n, seed, dtype=np.float64):
    """Velocities of mixed impacts: most hit the floor (vz < 0), some leave it, a few are bad."""
    rng = np.random.default_rng(seed)
    v = rng.normal(0.0, 0.6, size=(3, n))
    v[2] = -np.abs(v[2]) * rng.choice([1.0, 1.0, 1.0, -1.0], size=n)
    v[:, rng.integers(0, n, size=max(n // 100, 1))] = np.nan
    return [np.ascontiguousarray(c, dtype=dtype) for c in v]


def test_version_is_the_cargo_version(repo):
    cargo = (repo / "Cargo.toml").read_text()
    version = re.search(r'\[workspace\.package\][^\[]*?version = "([^"]+)"', cargo).group(1)
    assert depo.__version__ == version


def test_outcome_codes_and_capture_modes_are_the_c_header_s(repo):
    header = (repo / "crates" / "capi" / "include" / "depo.h").read_text()
    defined = dict(re.findall(r"#define DEPO_(\w+) (\d+)", header))
    for name in ["REBOUND", "CAPTURED", "SKIPPED", "INVALID", "CAPTURE_DEPOSIT", "CAPTURE_KEEP_ON_WALL",
                 "PARALLEL_MIN", "MAX_THREADS"]:
        assert getattr(depo, name) == int(defined[name]), name


def test_presets_list_table_1_and_make_laws():
    rows = depo.presets()
    assert len(rows) == 10
    sio2 = next(r for r in rows if r["id"] == "li1997-sio2")
    assert (sio2["k"], sio2["kappa"], sio2["vc"], sio2["q"]) == (12.5, 0.065, 0.074, 0.5)
    assert sio2["surface"] == "SiO2" and "stainless" in sio2["particle"]
    law = depo.WallLaw.preset("li1997-sio2")
    assert law.params == {"k1": 12.5, "k2": 12.5, "kappa1": 0.065, "kappa2": 0.065, "p": 1.0, "q": 0.5,
                          "vc": 0.074, "mu": 0.0}
    assert law == depo.WallLaw(12.5, 12.5, 0.065, 0.065, q=0.5, vc=0.074)


def test_a_rebound_a_capture_and_a_skip_in_place():
    law = depo.WallLaw.preset("li1997-sio2")
    vx, vy, vz = np.array([0.1, 0.0, 0.3]), np.zeros(3), np.array([-1.0, -0.01, 0.5])
    outcome = law.apply(vx, vy, vz)
    assert outcome.dtype == np.uint8
    assert outcome.tolist() == [depo.REBOUND, depo.CAPTURED, depo.SKIPPED]
    e = law.coefficients(1.0)[0]
    assert abs(vz[0] - e) < 1e-12 and vz[1] == 0.0 and vz[2] == 0.5
    assert e == pytest.approx(0.7319907, abs=1e-6)


def test_outcomes_go_into_a_given_array():
    law = depo.WallLaw.preset("li1997-sio2")
    v1, v2 = random_batch(500, 7), random_batch(500, 7)
    out = np.full(500, 9, dtype=np.uint8)
    assert law.apply(*v1, out=out) is out
    assert out.tobytes() == law.apply(*v2).tobytes()
    column = np.zeros((500, 2), dtype=np.uint8)[:, 1]
    law.apply(*random_batch(500, 7), out=column)
    assert column.tobytes() == out.tobytes()
    with pytest.raises(TypeError, match="out: expected a 1-D numpy array of uint8"):
        law.apply(*v1, out=np.zeros(500))
    with pytest.raises(ValueError, match="batch array outcome has 3 elements, expected 500"):
        law.apply(*v1, out=np.zeros(3, dtype=np.uint8))


def test_coefficients_keep_the_shape_and_match_the_curve():
    law = depo.WallLaw.preset("li1997-sio2")
    vn = np.array([[0.01, 0.074], [0.0741, -1.0]])
    e, R, rho, captured = law.coefficients(vn)
    assert e.shape == R.shape == rho.shape == captured.shape == (2, 2)
    assert captured.dtype == np.bool_
    assert captured.tolist() == [[True, True], [False, False]]
    np.testing.assert_allclose(e, R * (1 - rho), rtol=1e-15, atol=0)
    assert e[1, 1] == law.coefficients([1.0])[0][0]
    with pytest.raises(ValueError, match=r"vn\[1\] = NaN is not finite"):
        law.coefficients([1.0, np.nan])


def test_strided_views_give_the_contiguous_results_bit_for_bit():
    law = depo.WallLaw(12.5, 12.5, 0.065, 0.065, q=0.5, vc=0.3, mu=0.3).with_capture_mode("keep-on-wall")
    vx, vy, vz = random_batch(5000, 1)
    rng = np.random.default_rng(2)
    w = [rng.normal(0, 1e3, 5000) for _ in range(3)]
    r = np.full(5000, 4e-6)
    packed = np.stack([vx, vy, vz], axis=1)           # (n, 3): each column a strided view
    spin = np.stack(w + [r], axis=1)
    reversed_vx = vx[::-1].copy()[::-1]               # a view with a negative stride
    t1, t2 = depo.Tally(), depo.Tally()
    o1 = law.apply(vx, vy, vz, normal=(0, 0, 1), wx=w[0], wy=w[1], wz=w[2], radius=r, tally=t1)
    o2 = law.apply(reversed_vx, packed[:, 1], packed[:, 2], normal=(0, 0, 1), wx=spin[:, 0], wy=spin[:, 1],
                   wz=spin[:, 2], radius=spin[:, 3], tally=t2)
    assert not packed[:, 1].flags.c_contiguous and reversed_vx.strides[0] < 0
    assert o1.tobytes() == o2.tobytes()
    assert vx.tobytes() == reversed_vx.tobytes()
    assert vy.tobytes() == packed[:, 1].copy().tobytes()
    assert vz.tobytes() == packed[:, 2].copy().tobytes()
    for k in range(3):
        assert w[k].tobytes() == spin[:, k].copy().tobytes()
    assert t1 == t2 and t1.particles == 5000
    assert set(np.unique(o1)) == {depo.REBOUND, depo.CAPTURED, depo.SKIPPED, depo.INVALID}


def test_contiguous_views_of_one_buffer_are_updated_in_place():
    law = depo.WallLaw.preset("li1997-sio2")
    base = np.zeros(3 * 1000)
    vx, vy, vz = base[:1000], base[1000:2000], base[2000:]
    vz[:] = -1.0
    law.apply(vx, vy, vz)
    assert np.all(base[2000:] == law.coefficients(1.0)[0])


def test_float32_runs_in_single_precision_close_to_float64():
    law = depo.WallLaw.preset("wall1990-mica")
    v64 = random_batch(2000, 3)
    v32 = [c.astype(np.float32) for c in v64]
    o64 = law.apply(*v64)
    o32 = law.apply(*v32)
    assert all(c.dtype == np.float32 for c in v32)
    speed = np.sqrt(sum(c.astype(np.float64) ** 2 for c in v64))
    agree = o64 == o32
    assert agree.mean() > 0.99
    for c64, c32 in zip(v64, v32):
        ok = agree & np.isfinite(c64)
        assert np.all(np.abs(c64[ok] - c32[ok]) <= 1e-4 * np.maximum(speed[ok], 1.0) + 1e-6)


def test_tally_counts_and_adds():
    law = depo.WallLaw.preset("li1997-sio2")
    tally = depo.Tally()
    for seed in range(3):
        outcome = law.apply(*random_batch(1000, seed), tally=tally)
    assert tally.particles == 3000
    assert tally.invalid > 0 and tally.rebound > 0 and tally.skipped > 0
    assert tally.energy_material > 0 and tally.energy_adhesion > 0
    assert (tally + tally).rebound == 2 * tally.rebound
    assert set(tally.to_dict()) == {"rebound", "captured", "skipped", "invalid", "energy_material",
                                    "energy_adhesion", "energy_friction", "energy_deposition"}
    assert outcome.size == 1000


def test_per_particle_normals_and_capture_velocities():
    law = depo.WallLaw.preset("li1997-sio2")
    n = 4
    vx, vy, vz = np.zeros(n), np.array([-0.05, -0.05, -1.0, -1.0]), np.zeros(n)
    nx, ny, nz = np.zeros(n), np.ones(n), np.zeros(n)
    ny[3] = 2.0                                        # not a unit normal: that particle is invalid
    vc = np.array([0.01, 1.0, 0.01, 0.01])
    outcome = law.apply(vx, vy, vz, nx=nx, ny=ny, nz=nz, capture_velocity=vc)
    assert outcome.tolist() == [depo.REBOUND, depo.CAPTURED, depo.REBOUND, depo.INVALID]
    assert vy[3] == -1.0


def test_laws_pickle_and_compare_by_value():
    law = depo.WallLaw(50.0, 40.0, 0.2, 0.3, p=1.3, q=0.7, vc=0.1, mu=0.3).with_capture_mode(depo.CAPTURE_KEEP_ON_WALL)
    again = pickle.loads(pickle.dumps(law))
    assert again == law and again.capture_mode == depo.CAPTURE_KEEP_ON_WALL
    assert again != law.with_capture_mode("deposit")
    tally = depo.Tally(rebound=3, energy_friction=1.5)
    assert pickle.loads(pickle.dumps(tally)) == tally


@pytest.mark.parametrize(
    "make, error, message",
    [
        (lambda: depo.WallLaw(0.0, 1.0, 1.0, 1.0, vc=0.1), ValueError, "invalid wall-law parameter k1 = 0: must be positive"),
        (lambda: depo.WallLaw(1.0, 1.0, 1.0, 1.0, vc=float("nan")), ValueError, "invalid wall-law parameter vc = NaN: must be finite"),
        (lambda: depo.WallLaw(1.0, 1.0, 1.0, 1.0, vc=0.1, mu=-1.0), ValueError, "mu = -1: must not be negative"),
        (lambda: depo.WallLaw.preset("granite"), ValueError, "unknown wall-law preset 'granite'; known presets: dahneke1975-quartz"),
        (lambda: depo.WallLaw.preset("li1997-sio2").with_capture_mode(7), ValueError, "capture mode 7: expected CAPTURE_DEPOSIT (0)"),
        (lambda: depo.set_num_threads(5000), ValueError, "threads = 5000"),
    ],
)
def test_bad_values_are_value_errors_naming_them(make, error, message):
    with pytest.raises(error) as caught:
        make()
    assert message in str(caught.value)


def test_bad_arrays_are_type_or_value_errors_never_a_crash():
    law = depo.WallLaw.preset("li1997-sio2")
    v = [np.zeros(3), np.zeros(3), -np.ones(3)]
    cases = [
        (dict(vx=np.zeros(3, dtype=np.int64)), TypeError, "vx: expected a 1-D numpy array of float64 or float32, got a 1-D array of int64"),
        (dict(vy=np.zeros(3, dtype=np.float32)), TypeError, "vy: expected a 1-D numpy array of float64 (as vx), got a 1-D array of float32"),
        (dict(vz=[0.0, 0.0, -1.0]), TypeError, "vz: expected a 1-D numpy array of float64 (as vx), got list"),
        (dict(vx=np.zeros((3, 1))), ValueError, "vx: expected a 1-D array, got 2 dimensions"),
        (dict(vz=np.zeros(2)), ValueError, "batch array vz has 2 elements, expected 3"),
        (dict(normal=(0.0, 0.0, 2.0)), ValueError, "batch normal has length 2, not 1 within 1e-4"),
        (dict(normal=(0.0, 1.0)), ValueError, "normal: expected 3 numbers (x, y, z), got tuple"),
        (dict(vy=v[0]), ValueError, "vy shares memory with another array"),
        (dict(wx=np.zeros(3)), ValueError, "wx, wy, wz: give all three"),
        (dict(wx=np.zeros(3), wy=np.zeros(3), wz=np.zeros(3)), ValueError, "radius is required with spin"),
        (dict(nx=np.zeros(3), ny=np.ones(3)), ValueError, "nx, ny, nz: give all three or none"),
    ]
    for change, error, message in cases:
        args = dict(vx=v[0], vy=v[1], vz=v[2])
        args.update(change)
        with pytest.raises(error) as caught:
            law.apply(**args)
        assert message in str(caught.value), (change, str(caught.value))
    frozen = np.zeros(3)
    frozen.flags.writeable = False
    with pytest.raises(ValueError, match="vx is read-only"):
        law.apply(frozen, v[1], v[2])
    assert v[2].tolist() == [-1.0, -1.0, -1.0], "a failing call changes nothing"


def test_help_says_the_units():
    for doc in [depo.WallLaw.apply.__doc__, depo.WallLaw.__doc__, depo.fit.__doc__, depo.capture_velocity.__doc__]:
        assert "m/s" in doc
    assert "normal=(0.0, 0.0, 1.0)" in depo.WallLaw.apply.__text_signature__
