#!/bin/bash
# Submits a sweep as a job array of N tasks and its merge, to run when every task has succeeded.
#
#   MODEL=models/pulse-map.toml OUT=out/pulse-map validation/slurm/submit.sh 8 \
#       --vary excitation.period=lin:0.2:3:100 --vary excitation.amplitude=lin:0.5:15:100
#
# MODEL, OUT and FLEXROCK (default: flexrock on PATH) go to both jobs through the environment;
# extra sbatch options (partition, account, ...) can be given in SBATCH_* variables, e.g.
# SBATCH_PARTITION=short.
set -euo pipefail

if [ $# -lt 1 ] || ! [[ $1 =~ ^[1-9][0-9]*$ ]]; then
    echo "usage: MODEL=... OUT=... $0 N [sweep flags...]" >&2
    exit 2
fi
tasks=$1
shift
: "${MODEL:?set MODEL}" "${OUT:?set OUT}"
export MODEL OUT
here=$(dirname "$0")

array=$(sbatch --parsable --array="0-$((tasks - 1))" "$here/sweep.sbatch" "$@")
array=${array%%;*} # --parsable prints "jobid" or "jobid;cluster"
merge=$(sbatch --parsable --dependency="afterok:$array" "$here/merge.sbatch")
echo "array job ${array} (${tasks} tasks), merge job ${merge%%;*}: results in ${OUT}"
