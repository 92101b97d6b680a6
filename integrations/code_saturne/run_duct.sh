#!/usr/bin/env bash
# The duct case: a flow stage develops the flow from rest (no particles), then four particle
# runs restart from its checkpoint, so that all four see the same developed flow: with
# Code_Saturne's deposition walls as a perfect sink, with depo's law at the walls, with depo's
# deposition wall function, and with Code_Saturne's own deposition model (Guingo & Minier
# 2008); then the report (duct_report.py): where the particles of each size went, per wall,
# and the wall function's and the model's deposits against the correlation's prediction.
#
#   run_duct.sh WORK_DIR
#
# DEPO_PREFIX must name an install prefix of libdepo. DUCT_WALLS chooses the particle runs
# (default "sink depo wall-function model"; the report needs all four); the flow stage always
# runs first. About 2 min on 2 cores.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
work="$1"
mkdir -p "$work"
work="$(cd "$work" && pwd)"
for walls in flow ${DUCT_WALLS:-sink depo wall-function model}; do
  rm -rf "$work/case-$walls"
  cp -r "$here/duct_case" "$work/case-$walls"
  echo "$walls" > "$work/case-$walls/DATA/walls"
  if [ "$walls" = wall-function ]; then
    cp "$here/duct_case/DATA/depo_zones_wall_function" "$work/case-$walls/DATA/depo_zones"
  fi
  restart=""
  [ "$walls" = flow ] || restart="$work/flow/study/case/RESU/run/checkpoint"
  start=$(date +%s)
  DEPO_CS_RESTART="$restart" "$here/run_case.sh" "$work/case-$walls" "$work/$walls" 1 > "$work/$walls.log" 2>&1 ||
    { echo "the $walls run failed: see $work/$walls.log and $work/$walls/study/case/RESU/run" >&2; exit 1; }
  echo "$walls: $(( $(date +%s) - start )) s"
done
if [ -z "${DUCT_WALLS:-}" ]; then
  python3 "$here/duct_report.py" "$work/sink/study/case/RESU/run" "$work/depo/study/case/RESU/run" \
    "$work/wall-function/study/case/RESU/run" "$work/model/study/case/RESU/run" "$work"
fi
