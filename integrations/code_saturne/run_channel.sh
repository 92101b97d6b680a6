#!/usr/bin/env bash
# The channel case: Code_Saturne's deposition velocity against tau+, with its deposition
# model (Guingo & Minier 2008) and without it, beside Wood (1981); see README.md.
#
#   run_channel.sh WORK_DIR
#
# Three serial Code_Saturne runs in one study under WORK_DIR: the flow developed from a plug
# flow (stage "flow"), then two restarts from it with particles, the model on ("model") and
# off ("no-model"); then channel_report.py writes WORK_DIR/channel_peer.csv. Does not use
# libdepo. The run's size can be changed through the environment:
#   CHANNEL_PARTICLES       particles per class (default 15000)
#   CHANNEL_PARTICLE_STEPS  steps of each particle stage (default 2500: 0.5 s at 0.2 ms)
#   CHANNEL_PARTICLE_DT     time step of the particle stages, s (default 2e-4)
#   CHANNEL_TRANSIENT       seconds after the injection left out of the count (default 0.2)
#   CHANNEL_FLOW_STEPS      steps of 2 ms of the flow stage (default 3000: 6 s)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
work="$1"
particles="${CHANNEL_PARTICLES:-15000}"
particle_steps="${CHANNEL_PARTICLE_STEPS:-2500}"
particle_dt="${CHANNEL_PARTICLE_DT:-2e-4}"
transient="${CHANNEL_TRANSIENT:-0.2}"
flow_steps="${CHANNEL_FLOW_STEPS:-3000}"
# Code_Saturne 6.0 reads USER to find its scratch settings.
export USER="${USER:-$(id -un)}"
command -v code_saturne >/dev/null || { echo "code_saturne not found (apt-get install code-saturne code-saturne-include)" >&2; exit 2; }

rm -rf "$work"
mkdir -p "$work"
work="$(cd "$work" && pwd)"
cd "$work"
code_saturne create -s study -c flow >/dev/null
(cd study && code_saturne create -c model >/dev/null && code_saturne create -c no-model >/dev/null)
python3 "$here/box_mesh.py" study/MESH/box.msh $(cat "$here/channel_case/mesh_args")

for stage in flow model no-model; do
  cp "$here"/channel_case/SRC/* "study/$stage/SRC/"
  cp "$here"/channel_case/DATA/* "study/$stage/DATA/"
  {
    echo "stage $stage"
    echo "flow_steps $flow_steps"
    echo "particles $particles"
    echo "particle_steps $particle_steps"
    echo "particle_dt $particle_dt"
  } > "study/$stage/DATA/channel_run"
  restart=""
  [ "$stage" = flow ] || restart="$work/study/flow/RESU/run/checkpoint"
  start=$(date +%s)
  (cd "study/$stage/DATA" && CHANNEL_RESTART="$restart" code_saturne run --id run --nprocs 1) > "$stage.log" 2>&1 ||
    { echo "the $stage run failed: see $work/$stage.log and $work/study/$stage/RESU/run" >&2; exit 1; }
  echo "$stage: $(( $(date +%s) - start )) s"
done
python3 "$here/channel_report.py" study/flow/RESU/run study/model/RESU/run study/no-model/RESU/run \
  "$work/channel_peer.csv" "$transient"
