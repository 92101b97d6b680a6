"""Shared fixtures: the repository, and the workspace's own builds that some tests compare with.

The C library (libdepo) and the `depo` command come from the Rust build, not from the wheel.
A test that needs one finds it through DEPO_LIBDEPO / DEPO_BIN, or else in the workspace's
target directory ($CARGO_TARGET_DIR or target/, debug or release). Where neither is set nor
found, the test is skipped with the reason printed; where the variable is set to a file that is
missing, the test fails (CI sets them, so that it cannot skip them).
"""

import os
import pathlib

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]


def _built(variable, name):
    given = os.environ.get(variable)
    if given:
        path = pathlib.Path(given)
        if not path.is_file():
            pytest.fail(f"{variable}={given}: no such file")
        return path
    dirs = [pathlib.Path(os.environ["CARGO_TARGET_DIR"])] if os.environ.get("CARGO_TARGET_DIR") else []
    dirs.append(REPO / "target")
    for d in dirs:
        for profile in ("debug", "release"):
            if (d / profile / name).is_file():
                return d / profile / name
    pytest.skip(f"{name} is not built (cargo build -p depo-capi / --bin depo), and {variable} is not set")


def optional(module, package):
    """Imports an optional `module` (of pip's `package`) for a test, which is skipped, with the
    reason shown, where it is not installed; but fails where DEPO_PY_EXTRAS (what test.sh
    installs, and CI sets) names the package, so that CI cannot skip it."""
    import importlib

    try:
        return importlib.import_module(module)
    except ImportError:
        wanted = os.environ.get("DEPO_PY_EXTRAS", "")
        if package in wanted:
            pytest.fail(f"{module} is not importable, though DEPO_PY_EXTRAS={wanted!r} installs {package}")
        pytest.skip(f"{package} is not installed (optional; DEPO_PY_EXTRAS=\"{package}\" python/test.sh installs it)")


def pytest_report_header(config):
    import depo

    return f"depo {depo.__version__} from {depo._depo.__file__}"


@pytest.fixture(scope="session")
def repo():
    return REPO


@pytest.fixture(scope="session")
def libdepo_path():
    return _built("DEPO_LIBDEPO", "libdepo.so")


@pytest.fixture(scope="session")
def depo_bin():
    return _built("DEPO_BIN", "depo")
