"""The room and channel studies from Python: the command's JSON, numpy arrays, errors naming the
key, progress, threads, and Ctrl-C. The studies are tiny (two sizes, a few particles, a short
run) so that the whole file takes seconds."""

import json
import os
import signal
import subprocess
import sys
import textwrap
import time

import numpy as np
import pytest

import depo
from conftest import optional

ROOM = {
    "room": {"size": [2.0, 2.0, 2.0]},
    "particles": {"diameters": [1e-6, 10e-6], "count": 40, "target_error": 0.0},
    "ventilation": {"air_changes_per_hour": 0.5},
    "run": {"duration": 120.0, "seed": 11},
}

ROOM_TOML = """\
[room]
size = [2.0, 2.0, 2.0]
[particles]
diameters = [1e-6, 10e-6]
count = 40
target_error = 0.0
[ventilation]
air_changes_per_hour = 0.5
[run]
duration = 120.0
seed = 11
"""

CHANNEL_TOML = """\
[particles]
count = 40
[run]
duration_plus = 400.0
seed = 5
"""


def cli_json(depo_bin, *args):
    out = subprocess.run([str(depo_bin), *map(str, args), "--format", "json"], capture_output=True, text=True, check=True)
    return out.stdout


def test_room_to_dict_is_the_command_s_json(depo_bin, tmp_path):
    """The same scene as a file (the command's) and as a dict give the command's JSON, key for
    key and bit for bit; a seed given beside the scene stands for its run.seed."""
    path = tmp_path / "room.toml"
    path.write_text(ROOM_TOML)
    expected = json.loads(cli_json(depo_bin, "room", path, "--no-plot"))
    assert depo.room(path).to_dict() == expected
    assert depo.room(str(path)).to_dict() == expected
    from_dict = depo.room(ROOM)
    assert from_dict.to_dict() == expected
    reseeded = dict(ROOM, run={"duration": 120.0})
    assert depo.room(reseeded, seed=11).to_dict() == expected
    assert depo.room(reseeded, seed=12).to_dict() != expected


def test_channel_to_dict_is_the_command_s_json(depo_bin, tmp_path):
    path = tmp_path / "channel.toml"
    path.write_text(CHANNEL_TOML)
    expected = json.loads(cli_json(depo_bin, "channel", path, "--tau-plus", "3,30"))
    result = depo.channel(path, tau_plus=[3, 30])
    assert result.to_dict() == [expected]
    run = result.runs[0]
    assert run.name == "depo, resolved"
    np.testing.assert_array_equal(run.tau_plus, [3.0, 30.0])
    assert run.v_plus.dtype == np.float64 and run.v_plus.shape == (2,)
    assert np.all(run.v_plus_error >= 0)


def test_channel_near_wall_all_runs_both_models(depo_bin, tmp_path):
    path = tmp_path / "channel.toml"
    path.write_text(CHANNEL_TOML)
    text = cli_json(depo_bin, "channel", path, "--tau-plus", "30", "--near-wall", "all")
    # The command prints one JSON document per run, one after the other.
    decoder, expected, at = json.JSONDecoder(), [], 0
    while at < len(text.strip()):
        doc, at = decoder.raw_decode(text, at)
        expected.append(doc)
        while at < len(text) and text[at].isspace():
            at += 1
    result = depo.channel(path, tau_plus=30, near_wall="all")
    assert [r.name for r in result.runs] == ["depo, resolved", "depo, wall function"]
    assert result.to_dict() == expected


def test_room_result_as_numpy_arrays():
    r = depo.room(ROOM)
    d = r.to_dict()
    np.testing.assert_array_equal(r.diameters_um, [1.0, 10.0])
    np.testing.assert_array_equal(r.beta_per_hour, [s["beta_per_hour"]["value"] for s in d["sizes"]])
    curve = r.decay[1]
    assert curve.times_s.dtype == np.float64 and curve.times_s.shape == curve.airborne.shape
    np.testing.assert_array_equal(curve.airborne, d["sizes"][1]["decay"]["airborne"])
    floor = r.maps[1]["floor"]
    assert floor.dtype == np.uint32 and floor.ndim == 2
    assert floor.sum() == d["sizes"][1]["deposited"]["floor"] > 0
    assert r["air_changes_per_hour"] == 0.5
    # to_dict gives a copy: changing it changes nothing in the result.
    d["sizes"].clear()
    assert len(r.to_dict()["sizes"]) == 2


def test_room_to_pandas():
    pd = optional("pandas", "pandas")
    r = depo.room(ROOM)
    df = r.to_pandas()
    assert isinstance(df, pd.DataFrame)
    assert len(df) == 2 * 7  # floor, ceiling, walls, x0, x1, y0, y1 per size
    floor = df[(df.surface == "floor") & (df.diameter_um == 10.0)].iloc[0]
    assert floor.velocity == r.sizes[1]["floor"]["value"]
    assert floor.lai_nazaroff == r.sizes[1]["lai_nazaroff"]["floor"]


def test_bad_scene_values_are_value_errors_naming_the_key(tmp_path):
    with pytest.raises(ValueError, match=r"^scene: `run.duration` = -1 must be finite and positive$"):
        depo.room({"run": {"duration": -1.0}})
    with pytest.raises(ValueError, match=r"^scene: `run.duration`: invalid type: string"):
        depo.room({"run": {"duration": "long"}})
    with pytest.raises(ValueError, match=r"`room.sizes`: unknown field `sizes`"):
        depo.room({"room": {"sizes": [1.0, 1.0, 1.0]}})
    with pytest.raises(ValueError, match=r"`particles.diameters` is empty"):
        depo.room({"particles": {"diameters": []}})
    with pytest.raises(TypeError, match=r"`run.duration`: a value of type object"):
        depo.room({"run": {"duration": object()}})
    with pytest.raises(TypeError, match=r"^scene: expected None, a dict"):
        depo.room(3.5)
    with pytest.raises(ValueError, match=r"cannot read"):
        depo.room(tmp_path / "missing.toml")
    with pytest.raises(ValueError, match=r"^near_wall = 'x'|^near_wall = \"x\""):
        depo.channel(near_wall="x")
    with pytest.raises(ValueError, match=r"^tau_plus: -1 is not a positive number"):
        depo.channel(tau_plus=[-1.0])
    path = tmp_path / "bad.toml"
    path.write_text("[run]\nduration = -1.0\n")
    with pytest.raises(ValueError, match=r"bad.toml line 2: `run.duration` = -1"):
        depo.room(path)


def test_numpy_values_and_none_in_a_scene():
    """numpy arrays and scalars stand for lists and numbers; None leaves a key out."""
    scene = {
        "room": {"size": np.array([2.0, 2.0, 2.0])},
        "particles": {"diameters": np.array([1e-6, 10e-6]), "count": np.int64(40), "target_error": 0.0},
        "ventilation": {"air_changes_per_hour": np.float32(0.5)},
        "run": {"duration": 120.0, "seed": 11, "dt": None},
    }
    assert depo.room(scene).to_dict() == depo.room(ROOM).to_dict()


def test_progress_is_told_each_size_on_the_calling_thread(capsys):
    import threading

    calls = []
    depo.room(ROOM, progress=lambda what, done, total: calls.append((what, done, total, threading.get_ident())))
    assert calls and calls[-1][:3] == ("sizes", 2, 2)
    assert {c[3] for c in calls} == {threading.get_ident()}
    depo.room(ROOM, progress=True)  # tqdm where installed, else a line on stderr
    err = capsys.readouterr().err
    assert "2/2" in err


def test_the_thread_setting_changes_no_result():
    expected = depo.room(ROOM).to_dict()
    try:
        for n in (1, 2):
            depo.set_num_threads(n)
            assert depo.room(ROOM).to_dict() == expected
    finally:
        depo.set_num_threads(0)


# The built-in room (minutes of work); and 0.2 um particles over 100 hours, each of them
# seconds of tracking (a chunk of 8 took 7-12 s to stop when runs stopped only between chunks).
CTRL_C_SCENES = {
    "built-in": None,
    "long particle runs": {"particles": {"diameters": [0.2e-6]}, "run": {"duration": 360000.0}},
}


@pytest.mark.parametrize("scene", list(CTRL_C_SCENES))
def test_ctrl_c_stops_a_study_within_a_second(scene):
    """A subprocess runs a long room study and is sent SIGINT: it raises KeyboardInterrupt
    within a second, and afterwards its process uses no CPU (no thread goes on tracking)."""
    child = textwrap.dedent(
        f"""
        import sys, time, depo
        print("ready", flush=True)
        try:
            depo.room({CTRL_C_SCENES[scene]!r})
        except KeyboardInterrupt:
            print("interrupted", time.monotonic(), flush=True)
            cpu = time.process_time()
            time.sleep(0.5)
            print("cpu", time.process_time() - cpu, flush=True)
            sys.exit(0)
        print("finished", flush=True)
        sys.exit(1)
        """
    )
    proc = subprocess.Popen([sys.executable, "-c", child], stdout=subprocess.PIPE, text=True)
    try:
        assert proc.stdout.readline().strip() == "ready"
        time.sleep(1.5)  # well inside the study
        assert proc.poll() is None, "the study ended before it was interrupted"
        sent = time.monotonic()
        os.kill(proc.pid, signal.SIGINT)
        line = proc.stdout.readline().split()
        assert line[0] == "interrupted", line
        stopped = float(line[1]) - sent
        cpu = float(proc.stdout.readline().split()[1])
        assert proc.wait(timeout=10) == 0
    finally:
        if proc.poll() is None:
            proc.kill()
    print(f"stopped {stopped:.3f} s after SIGINT; {cpu:.3f} s of CPU in the 0.5 s after")
    assert stopped < 1.0
    assert cpu < 0.05
