#!/usr/bin/env bash
# Regenerates every file in validation/opensees/results/ from scratch.
# Usage (from anywhere):  validation/opensees/run_all.sh
# Needs a Python with openseespy, numpy and scipy; set PYTHON to choose it (default: the venv
# /work/venv-ops if present, else python3). OpenSeesPy needs Debian's libblas3 and liblapack3.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
if [[ -z "${PYTHON:-}" ]]; then
    if [[ -x /work/venv-ops/bin/python ]]; then PYTHON=/work/venv-ops/bin/python; else PYTHON=python3; fi
fi
rm -rf "$here/results"
mkdir -p "$here/results"
cd "$here"
# 1. pushovers (E and 10 E, with and without P-Delta) and fixed-base periods after gravity
"$PYTHON" beam_column.py pushover --out results 2>results/pushover.stderr | tee results/pushover.log
# 2. transient analyses: the paper's wave and the five shipped records (scale 1.0), each with
#    P-Delta at dt and dt/2 (convergence) and without P-Delta (Linear transf) at dt
"$PYTHON" beam_column.py dynamic --out results 2>results/dynamic.stderr | tee results/dynamic.log
# 3. sensitivity of the paper's-wave run to the toe stiffness, mesh, integrator, rotary inertia, dt
"$PYTHON" beam_column.py sensitivity --out results 2>results/sensitivity.stderr | tee results/sensitivity.log
# 4. the continuum boundary-value check of the pushover (scipy)
"$PYTHON" continuum_bvp.py --out results | tee results/continuum.log
# OpenSees prints its warnings on stderr; keep only a count (the files are large otherwise)
for f in results/*.stderr; do
    echo "$(grep -c -i warning "$f" || true) warning lines in $(basename "$f")" >> results/stderr-summary.txt
    rm "$f"
done
