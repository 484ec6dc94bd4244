#!/usr/bin/env bash
# Regenerates every file in validation/opensees/row_results/ from scratch: the OpenSees pair of
# pounding columns (row_pair.py), the same rows run by flexrock, the comparison tables, the
# figures and the contact-stiffness sweep.
# Usage (from anywhere):  validation/opensees/run_row.sh
# Needs a Python with openseespy, numpy and scipy (PYTHON; default the venv /work/venv-ops if
# present, else python3), rsvg-convert, and flexrock (FLEXROCK; default: built here with
# cargo build --release into $CARGO_TARGET_DIR or target/).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
if [[ -z "${PYTHON:-}" ]]; then
    if [[ -x /work/venv-ops/bin/python ]]; then PYTHON=/work/venv-ops/bin/python; else PYTHON=python3; fi
fi
if [[ -z "${FLEXROCK:-}" ]]; then
    (cd "$repo" && cargo build --release --quiet)
    FLEXROCK="${CARGO_TARGET_DIR:-$repo/target}/release/flexrock"
fi
rm -rf "$here/row_results"
mkdir -p "$here/row_results"
cd "$here"
"$PYTHON" row_pair.py run --out row_results --flexrock "$FLEXROCK" 2>row_results/row.stderr | tee row_results/row.log
# OpenSees prints its warnings on stderr; keep only a count
# (and the steps that failed to converge, whole)
echo "$(grep -c -i warning row_results/row.stderr || true) warning lines in row.stderr" > row_results/stderr-summary.txt
grep -i "no convergence" row_results/row.stderr >> row_results/stderr-summary.txt || true
rm row_results/row.stderr
