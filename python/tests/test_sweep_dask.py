"""examples/python/sweep_dask.py on a LocalCluster of 2 workers, with a tiny sweep: the same
results, bit for bit, as the serial loop, whatever order the tasks finish in."""

import subprocess
import sys

from conftest import optional


def test_the_dask_sweep_is_the_serial_loop_bit_for_bit(repo):
    optional("distributed", "dask[distributed]")
    script = repo / "examples" / "python" / "sweep_dask.py"
    out = subprocess.run(
        [sys.executable, str(script), "--size", "tiny", "--workers", "2", "--check"],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert out.returncode == 0, out.stdout + out.stderr
    lines = out.stdout.splitlines()
    assert lines[0].startswith("8 tasks in "), out.stdout
    assert lines[-1] == "serial loop: the same results, bit for bit", out.stdout
    print(lines[0])
