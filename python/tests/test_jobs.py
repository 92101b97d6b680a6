"""presets(), fit() and capture_velocity() give what the `depo` command prints with
--format json for the same inputs, and fail with its messages."""

import csv
import json
import subprocess
import warnings

import numpy as np
import pytest

import depo


def command(depo_bin, *args):
    done = subprocess.run([str(depo_bin), *args], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def test_presets_are_the_command_s(depo_bin):
    assert depo.presets() == command(depo_bin, "presets", "--format", "json")


def read_samples(path):
    with open(path) as f:
        rows = [r for r in csv.DictReader(line for line in f if not line.startswith("#"))]
    return np.array([float(r["vn"]) for r in rows]), np.array([float(r["e"]) for r in rows])


@pytest.mark.parametrize("args, kwargs", [
    (["--q", "0.5"], dict(q=0.5)),
    (["--q", "0.5", "--free-exponents", "--surface", "x0"], dict(q=0.5, free_exponents=True, surface="x0")),
])
def test_fit_is_the_command_s(repo, depo_bin, args, kwargs):
    data = repo / "examples" / "li1997-synthetic.csv"
    vn, e = read_samples(data)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ours = depo.fit(vn, e, **kwargs)
    theirs = command(depo_bin, "fit", str(data), "--format", "json", *args)
    assert ours == theirs
    assert ours["vc_low"] < ours["vc"] < ours["vc_high"]
    assert ours["scene_entry"].startswith(kwargs.get("surface", "floor") + " = { behaviour = \"law\"")


def test_a_failed_fit_says_what_to_try(repo, depo_bin):
    vn, e = read_samples(repo / "examples" / "li1997-synthetic.csv")
    with pytest.raises(ValueError) as caught:
        depo.fit(vn, e)
    done = subprocess.run([str(depo_bin), "fit", str(repo / "examples" / "li1997-synthetic.csv")],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 1
    ours = str(caught.value)
    assert ours.startswith("the fit failed: vc = ") and "free_exponents=True" in ours
    # the command's message, with the parameters named as in Python
    assert ours.split(";")[0] in done.stderr


@pytest.mark.parametrize("call, message", [
    (lambda: depo.fit([0.1, 0.0, 0.3], [0.2, 0.3, 0.4]), "vn[1] is zero (not an impact)"),
    (lambda: depo.fit([0.1, 0.2, 0.3], [0.2, 1.3, 0.4]), "e[1] = 1.3 is outside [0, 1]"),
    (lambda: depo.fit([0.1, 0.2, 0.3], [0.2, 0.3, 0.4], weight=[1, 0, 1]), "weight[1] = 0: weight must be positive"),
    (lambda: depo.fit([0.1, 0.2], [0.2, 0.3, 0.4]), "e has 3 values, vn 2"),
    (lambda: depo.fit([0.1, 0.2, 0.3], [0.2, 0.3, 0.4], q=-1), "q -1: the exponent must be finite and positive"),
    (lambda: depo.fit([0.1, 0.2, 0.3], [0.2, 0.3, 0.4], surface="roof"), 'surface "roof": expected one of all, floor'),
    (lambda: depo.capture_velocity(density=-1, particle_modulus=1e9, particle_poisson=0.3, wall_modulus=1e9,
                                   wall_poisson=0.3, work_of_adhesion=0.1), "density -1: must be finite and positive"),
    (lambda: depo.capture_velocity(density=1000, particle_modulus=1e9, particle_poisson=0.7, wall_modulus=1e9,
                                   wall_poisson=0.3, work_of_adhesion=0.1), "particle_poisson 0.7: must lie in [-1, 0.5]"),
])
def test_bad_inputs_are_value_errors_with_the_command_s_messages(call, message):
    with pytest.raises(ValueError) as caught:
        call()
    assert message in str(caught.value)


def test_capture_velocity_is_the_command_s(depo_bin):
    kwargs = dict(density=2200, particle_modulus=73e9, particle_poisson=0.17, wall_modulus=200e9,
                  wall_poisson=0.3, work_of_adhesion=0.1)
    flags = ["--density", "2200", "--particle-modulus", "73e9", "--particle-poisson", "0.17", "--wall-modulus",
             "200e9", "--wall-poisson", "0.3", "--work-of-adhesion", "0.1"]
    assert depo.capture_velocity(**kwargs) == command(depo_bin, "capture-velocity", *flags, "--format", "json")
    ours = depo.capture_velocity(**kwargs, diameters=np.array([1e-6, 5e-6]), yield_pressure=1e9, hamaker=1e-19,
                                 restitution=0.9)
    theirs = command(depo_bin, "capture-velocity", *flags, "--diameters", "1e-6,5e-6", "--yield-pressure", "1e9",
                     "--hamaker", "1e-19", "--restitution", "0.9", "--format", "json")
    assert ours == theirs
    assert ours["rows"][0]["dahneke_capture_velocity"] > 0 and ours["rows"][0]["elastic"] in (True, False)
