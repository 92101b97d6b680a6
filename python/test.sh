#!/usr/bin/env bash
# Tests the Python package as a user gets it: builds the wheel, installs it into a fresh
# virtual environment with numpy and pytest, and runs python/tests against it.
#
#   python/test.sh [PYTEST_ARGS...]
#
# The wheel is built in Cargo's dev profile (DEPO_PY_PROFILE=release for an optimised one), so
# that it reuses the dependencies `cargo test --workspace` has already compiled into the same
# target directory. The C library and the `depo` command that some tests compare with are built
# here too (quick after `cargo test`). Optional packages the tests use where installed (dask,
# pandas, matplotlib) go in with DEPO_PY_EXTRAS="dask[distributed] pandas matplotlib" (as
# .ci/run sets it); a test
# of a package DEPO_PY_EXTRAS names fails, rather than skips, where it is not importable.
set -euo pipefail
cd "$(dirname "$0")/.."

target="${CARGO_TARGET_DIR:-$PWD/target}"
profile="${DEPO_PY_PROFILE:-dev}"
venv="$target/python-test-venv"

rm -rf "$venv"
python3 -m venv "$venv"
# shellcheck disable=SC2086 # DEPO_PY_EXTRAS is a list of package names
"$venv/bin/pip" install -q --disable-pip-version-check maturin numpy pytest ${DEPO_PY_EXTRAS:-}

cargo build -q -p depo-capi -p depo --lib --bins
"$venv/bin/maturin" build -q --profile "$profile" --manifest-path python/Cargo.toml --out "$venv/wheels"
"$venv/bin/pip" install -q --disable-pip-version-check --no-index --find-links "$venv/wheels" depo

export DEPO_LIBDEPO="$target/debug/libdepo.so" DEPO_BIN="$target/debug/depo"
# From the repository's root, so that `import depo` is the installed wheel, not python/depo/.
"$venv/bin/python" -m pytest python/tests -p no:cacheprovider "$@"
