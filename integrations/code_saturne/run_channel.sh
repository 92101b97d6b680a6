#!/usr/bin/env bash
# The channel case: the deposition velocity against tau+ in Code_Saturne, with its deposition
# model (Guingo & Minier 2008), without it, and with depo's deposition wall function, beside
# Wood (1981); see README.md.
#
#   run_channel.sh WORK_DIR
#
# Serial Code_Saturne runs in one study under WORK_DIR: the flow developed from a plug flow
# (stage "flow"), then restarts from it with particles: the model on ("model"), off
# ("no-model"), and depo's wall function on both walls with the model off ("wall-function",
# linked against libdepo from DEPO_PREFIX); then channel_report.py writes
# WORK_DIR/channel_peer.csv. The run's size can be changed through the environment:
#   CHANNEL_STAGES          particle stages run (default "model no-model wall-function")
#   CHANNEL_CLASSES         the tau+ of the classes injected, comma-separated (default all:
#                           0.1,0.3,1,3,10,30)
#   CHANNEL_PARTICLES       particles per class (default 15000)
#   CHANNEL_WF_PARTICLES    particles per class of the wall-function stage (default 10000,
#                           to keep the whole run near 11 min on one core)
#   CHANNEL_PARTICLE_STEPS  steps of each particle stage (default 2500: 0.5 s at 0.2 ms)
#   CHANNEL_PARTICLE_DT     time step of the particle stages, s (default 2e-4)
#   CHANNEL_TRANSIENT       seconds after the injection left out of the count (default 0.2)
#   CHANNEL_FLOW_STEPS      steps of 2 ms of the flow stage (default 3000: 6 s)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
work="$1"
particles="${CHANNEL_PARTICLES:-15000}"
wf_particles="${CHANNEL_WF_PARTICLES:-10000}"
particle_steps="${CHANNEL_PARTICLE_STEPS:-2500}"
particle_dt="${CHANNEL_PARTICLE_DT:-2e-4}"
transient="${CHANNEL_TRANSIENT:-0.2}"
flow_steps="${CHANNEL_FLOW_STEPS:-3000}"
stages="${CHANNEL_STAGES:-model no-model wall-function}"
classes="${CHANNEL_CLASSES:-}"
case " $stages " in
  *" wall-function "*) : "${DEPO_PREFIX:?set DEPO_PREFIX to an install prefix of libdepo (the wall-function stage links it)}"
    DEPO_PREFIX="$(cd "$DEPO_PREFIX" && pwd)" ;;
esac
# Code_Saturne 6.0 reads USER to find its scratch settings.
export USER="${USER:-$(id -un)}"
command -v code_saturne >/dev/null || { echo "code_saturne not found (apt-get install code-saturne code-saturne-include)" >&2; exit 2; }

rm -rf "$work"
mkdir -p "$work"
work="$(cd "$work" && pwd)"
cd "$work"
code_saturne create -s study -c flow >/dev/null
for stage in $stages; do (cd study && code_saturne create -c "$stage" >/dev/null); done
python3 "$here/box_mesh.py" study/MESH/box.msh $(cat "$here/channel_case/mesh_args")

for stage in flow $stages; do
  cp "$here"/channel_case/SRC/* "study/$stage/SRC/"
  cp "$here"/channel_case/DATA/* "study/$stage/DATA/"
  prefix=""
  n="$particles"
  if [ "$stage" = wall-function ]; then
    n="$wf_particles"
    cp "$here/depo_code_saturne.c" "$here/depo_code_saturne.h" "study/$stage/SRC/"
    printf 'floor wall-function wood\nceiling wall-function wood\n' > "study/$stage/DATA/depo_zones"
    prefix="$DEPO_PREFIX"
  fi
  {
    echo "stage $stage"
    echo "flow_steps $flow_steps"
    echo "particles $n"
    echo "particle_steps $particle_steps"
    echo "particle_dt $particle_dt"
    [ -z "$classes" ] || echo "classes $classes"
  } > "study/$stage/DATA/channel_run"
  restart=""
  [ "$stage" = flow ] || restart="$work/study/flow/RESU/run/checkpoint"
  start=$(date +%s)
  (cd "study/$stage/DATA" && CHANNEL_RESTART="$restart" CHANNEL_DEPO_PREFIX="$prefix" code_saturne run --id run --nprocs 1) > "$stage.log" 2>&1 ||
    { echo "the $stage run failed: see $work/$stage.log and $work/study/$stage/RESU/run" >&2; exit 1; }
  echo "$stage: $(( $(date +%s) - start )) s"
done
runs=()
for stage in $stages; do runs+=("study/$stage/RESU/run"); done
python3 "$here/channel_report.py" study/flow/RESU/run "$work/channel_peer.csv" "$transient" "${runs[@]}"
