#!/usr/bin/env bash
# The duct case twice, with Code_Saturne's own deposition and with depo's law at the walls,
# then the report (duct_report.py): where the particles of each size went, per wall.
#
#   run_duct.sh WORK_DIR
#
# DEPO_PREFIX must name an install prefix of libdepo. About a minute on 2 cores.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
work="$1"
mkdir -p "$work"
work="$(cd "$work" && pwd)"
for walls in sink depo; do
  rm -rf "$work/case-$walls"
  cp -r "$here/duct_case" "$work/case-$walls"
  echo "$walls" > "$work/case-$walls/DATA/walls"
  "$here/run_case.sh" "$work/case-$walls" "$work/$walls" 1 > "$work/$walls.log" 2>&1 ||
    { echo "the $walls run failed: see $work/$walls.log and $work/$walls/study/case/RESU/run" >&2; exit 1; }
done
python3 "$here/duct_report.py" "$work/sink/study/case/RESU/run" "$work/depo/study/case/RESU/run" "$work"
