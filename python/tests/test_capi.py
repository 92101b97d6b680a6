"""Bit-identity with the C library: the same inputs through libdepo (loaded with ctypes) and
through depo.WallLaw give the same bytes: velocities, spins, outcomes and tallies."""

import ctypes

import numpy as np
import pytest

import depo

c_double_p = ctypes.POINTER(ctypes.c_double)
c_float_p = ctypes.POINTER(ctypes.c_float)


def impacts(real, pointer):
    class Impacts(ctypes.Structure):
        _fields_ = [("n", ctypes.c_size_t)] + [
            (name, pointer) for name in ["vx", "vy", "vz", "wx", "wy", "wz", "radius", "nx", "ny", "nz"]
        ] + [("normal", real * 3), ("outcome", ctypes.POINTER(ctypes.c_uint8))]

    return Impacts


ImpactsF64 = impacts(ctypes.c_double, c_double_p)
ImpactsF32 = impacts(ctypes.c_float, c_float_p)


class Tally(ctypes.Structure):
    _fields_ = [(name, ctypes.c_uint64) for name in ["rebound", "captured", "skipped", "invalid"]] + [
        (name, ctypes.c_double) for name in ["energy_material", "energy_adhesion", "energy_friction", "energy_deposition"]
    ]


class LawParams(ctypes.Structure):
    _fields_ = [(name, ctypes.c_double) for name in ["k1", "k2", "kappa1", "kappa2", "p", "q", "vc", "mu"]]


@pytest.fixture(scope="module")
def lib(libdepo_path):
    lib = ctypes.CDLL(str(libdepo_path))
    lib.depo_last_error.restype = ctypes.c_char_p
    lib.depo_version.restype = ctypes.c_char_p
    return lib


def c_law(lib, law):
    """The same law made through the C ABI, from its constants and capture mode."""
    made, moded = ctypes.c_void_p(), ctypes.c_void_p()
    assert lib.depo_law_new(ctypes.byref(LawParams(**law.params)), ctypes.byref(made)) == 0
    assert lib.depo_law_with_capture_mode(made, law.capture_mode, ctypes.byref(moded)) == 0
    lib.depo_law_free(made)
    return moded


def ptr(array, pointer):
    return None if array is None else array.ctypes.data_as(pointer)


LAWS = [
    depo.WallLaw.preset("li1997-sio2"),
    depo.WallLaw.preset("dahneke1975-quartz").with_capture_mode(depo.CAPTURE_KEEP_ON_WALL),
    depo.WallLaw(50.0, 40.0, 0.2, 0.3, p=1.3, q=0.7, vc=0.2, mu=0.3),
    depo.WallLaw(12.5, 12.5, 0.065, 0.065, q=0.5, vc=0.3, mu=0.5).with_capture_mode("keep-on-wall"),
]


def inputs(n, seed, dtype, spin, normals, sized):
    rng = np.random.default_rng(seed)
    v = rng.normal(0.0, 0.7, size=(3, n))
    v[2] -= 0.3
    v[:, rng.integers(0, n, size=n // 200 + 1)] = np.inf
    arrays = {k: np.ascontiguousarray(v[i], dtype=dtype) for i, k in enumerate(["vx", "vy", "vz"])}
    if spin:
        for k in ["wx", "wy", "wz"]:
            arrays[k] = rng.normal(0.0, 2e4, n).astype(dtype)
        arrays["radius"] = rng.uniform(1e-6, 3e-5, n).astype(dtype)
    if normals:
        m = rng.normal(size=(3, n))
        m[2] = np.abs(m[2]) + 0.5
        m /= np.linalg.norm(m, axis=0)
        m[0, rng.integers(0, n, size=n // 300 + 1)] += 0.1  # some not of unit length: invalid
        for i, k in enumerate(["nx", "ny", "nz"]):
            arrays[k] = np.ascontiguousarray(m[i], dtype=dtype)
    if sized:
        arrays["capture_velocity"] = rng.uniform(0.01, 0.5, n).astype(dtype)
    return arrays


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
@pytest.mark.parametrize("n", [1000, depo.PARALLEL_MIN + 4321])
@pytest.mark.parametrize("spin, normals, sized", [(False, False, False), (True, False, False), (True, True, False),
                                                  (False, True, True)])
def test_apply_is_the_c_abi_s_bit_for_bit(lib, dtype, n, spin, normals, sized):
    f64 = dtype == np.float64
    Impacts, pointer = (ImpactsF64, c_double_p) if f64 else (ImpactsF32, c_float_p)
    for law_index, law in enumerate(LAWS):
        ours = inputs(n, 100 * law_index + n, dtype, spin, normals, sized)
        theirs = {k: a.copy() for k, a in ours.items()}
        normal = (0.0, 0.6, 0.8)
        tally = depo.Tally()
        outcome = law.apply(normal=normal, tally=tally, **ours)

        c_outcome = np.full(n, 255, dtype=np.uint8)
        batch = Impacts(n, *[ptr(theirs.get(k), pointer) for k in ["vx", "vy", "vz", "wx", "wy", "wz", "radius",
                                                                  "nx", "ny", "nz"]],
                        (Impacts._fields_[11][1])(*normal), c_outcome.ctypes.data_as(ctypes.POINTER(ctypes.c_uint8)))
        c_tally = Tally()
        handle = c_law(lib, law)
        try:
            if sized:
                apply = lib.depo_apply_sized_f64 if f64 else lib.depo_apply_sized_f32
                status = apply(handle, ctypes.byref(batch), ptr(theirs["capture_velocity"], pointer), ctypes.byref(c_tally))
            else:
                apply = lib.depo_apply_f64 if f64 else lib.depo_apply_f32
                status = apply(handle, ctypes.byref(batch), ctypes.byref(c_tally))
        finally:
            lib.depo_law_free(handle)
        assert status == 0, lib.depo_last_error()
        assert outcome.tobytes() == c_outcome.tobytes()
        for k in ours:
            assert ours[k].tobytes() == theirs[k].tobytes(), k
        assert tally.to_dict() == {name: getattr(c_tally, name) for name, _ in Tally._fields_}
        assert len(set(outcome.tolist())) >= 3, "the inputs exercise several outcomes"


def test_coefficients_are_the_c_abi_s_bit_for_bit(lib):
    vn = np.concatenate([np.geomspace(1e-4, 1e3, 500), -np.geomspace(1e-4, 1e3, 77), [0.0, 0.074, 0.0741]])
    for law in LAWS:
        e, R, rho, captured = law.coefficients(vn)
        out = [np.empty_like(vn) for _ in range(3)] + [np.empty(vn.size, dtype=np.uint8)]
        handle = c_law(lib, law)
        try:
            status = lib.depo_coefficients(handle, ctypes.c_size_t(vn.size), ptr(vn, c_double_p),
                                           *[ptr(o, c_double_p) for o in out[:3]],
                                           out[3].ctypes.data_as(ctypes.POINTER(ctypes.c_uint8)))
        finally:
            lib.depo_law_free(handle)
        assert status == 0
        for ours, theirs in zip([e, R, rho, captured.astype(np.uint8)], out):
            assert ours.tobytes() == theirs.tobytes()


def test_the_c_library_is_this_version(lib):
    assert lib.depo_version().decode() == depo.__version__
