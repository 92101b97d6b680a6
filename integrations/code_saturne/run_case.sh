#!/usr/bin/env bash
# Builds and runs a depo case with Code_Saturne.
#
#   run_case.sh CASE_DIR WORK_DIR [NPROCS]
#
# CASE_DIR holds SRC/ and DATA/ (e.g. check_case); WORK_DIR is made anew and receives a
# Code_Saturne study with the case, whose results land in WORK_DIR/study/case/RESU/run.
# DEPO_PREFIX must name an install prefix of libdepo (include/depo.h, lib/libdepo.so).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
case_dir="$(cd "$1" && pwd)"
work="$2"
nprocs="${3:-1}"
: "${DEPO_PREFIX:?set DEPO_PREFIX to an install prefix of libdepo}"
# Code_Saturne 6.0 reads USER to find its scratch settings.
export USER="${USER:-$(id -un)}"
command -v code_saturne >/dev/null || { echo "code_saturne not found (apt-get install code-saturne code-saturne-include)" >&2; exit 2; }

rm -rf "$work"
mkdir -p "$work"
cd "$work"
code_saturne create -s study -c case >/dev/null
cp "$case_dir"/SRC/* "$here/depo_code_saturne.c" "$here/depo_code_saturne.h" study/case/SRC/
cp "$case_dir"/DATA/* "$here/cs_user_scripts.py" study/case/DATA/
mesh_args=$(cat "$case_dir/mesh_args")
python3 "$here/box_mesh.py" study/MESH/box.msh $mesh_args
cd study/case/DATA
code_saturne run --id run --nprocs "$nprocs"
