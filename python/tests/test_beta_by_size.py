"""examples/python/beta_by_size.py, the building scientist's figure, with small counts: it writes a
PNG, and the numbers it plots are the room studies' for its scenes and seed (skipped, with the
reason shown, where matplotlib is not installed)."""

import importlib.util
import subprocess
import sys

import numpy as np

import depo
from conftest import optional


def test_the_figure_plots_the_studies_beta_beside_the_model(repo, tmp_path):
    optional("matplotlib", "matplotlib")
    from matplotlib import image

    script = repo / "examples" / "python" / "beta_by_size.py"
    png = tmp_path / "beta.png"
    count, duration, seed = 16, 120.0, 3
    done = subprocess.run(
        [sys.executable, str(script), "--out", str(png), "--count", str(count), "--duration", str(duration),
         "--seed", str(seed)],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 0, done.stdout + done.stderr
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    height, width = image.imread(str(png)).shape[:2]
    assert width > 500 and height > 500

    # The printed table (what the figure shows) against the studies run here, room by room.
    spec = importlib.util.spec_from_file_location("beta_by_size", script)
    example = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(example)
    lines = done.stdout.splitlines()
    for furnished, label in [(False, "bare, infiltration"), (True, "furnished, infiltration")]:
        study = depo.room(example.room(furnished, count, duration), seed=seed)
        start = lines.index(f"{label}: d (um), beta (1/h), s.e., Lai & Nazaroff") + 1
        table = np.array([[float(x) for x in line.split()] for line in lines[start:start + len(study.sizes)]])
        model = [s["lai_nazaroff"]["beta_per_hour"] for s in study.sizes]
        expected = np.column_stack([study.diameters_um, study.beta_per_hour, study.beta_error_per_hour, model])
        # as printed: 2 decimals for the diameter, 4 for the rest
        np.testing.assert_allclose(table[:, 0], expected[:, 0], rtol=0, atol=0.005 + 1e-12)
        np.testing.assert_allclose(table[:, 1:], expected[:, 1:], rtol=0, atol=0.00005 + 1e-12)
        assert study["air_changes_per_hour"] == 0.5 and study["penetration"] == 0.8
        assert len(study.sizes[0].get("furnishings", [])) == (3 if furnished else 0)
