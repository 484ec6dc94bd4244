#!/usr/bin/env bash
# Regenerates validation/REPORT.md and validation/figures/*.svg from the flexrock command line.
# Usage (from anywhere): validation/regenerate.sh   (FLEXROCK_BIN names a binary to use instead
# of building one); validation/check.sh runs it and compares the result with the committed files.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/.." && pwd)"
cd "$root"

if [ -n "${FLEXROCK_BIN:-}" ]; then
    flexrock=$FLEXROCK_BIN
else
    cargo build --release --quiet
    flexrock="${CARGO_TARGET_DIR:-$root/target}/release/flexrock"
fi

results="validation/results"
figures="validation/figures"
mkdir -p "$results" "$figures"

model="models/ichinose1986.toml"

# 1. The paper's example: reference vs Newmark dt = 0.02 s, both event treatments.
# Wall times go to timings.json in each directory (--timings-apart): every other file is the
# same from run to run, which validation/check.sh relies on.
"$flexrock" compare "$model" --dt 0.02 --variant compensate --timings-apart --out "$results/compare-compensate"
"$flexrock" compare "$model" --dt 0.02 --variant substep --timings-apart --out "$results/compare-substep"

# 2. The convergence study (default lists of dt and rtol).
"$flexrock" converge "$model" --timings-apart --out "$results/converge"

# 3. The rigid limit against Housner.
"$flexrock" run validation/models/rigid-free-rocking.toml --timings-apart --out "$results/rigid"

# Figures, under names the report links.
cp "$results/compare-compensate/compare.svg" "$figures/compare-compensate.svg"
cp "$results/compare-substep/compare.svg" "$figures/compare-substep.svg"
cp "$results/compare-compensate/compare_relations.svg" "$figures/relations-compensate.svg"
cp "$results/compare-substep/compare_relations.svg" "$figures/relations-substep.svg"
cp "$results/converge/convergence_dt.svg" "$figures/convergence-dt.svg"
cp "$results/converge/convergence_work.svg" "$figures/convergence-work.svg"

# 4. The report, assembled from the files above.
"$flexrock" report \
    --compare-compensate "$results/compare-compensate" \
    --compare-substep "$results/compare-substep" \
    --converge "$results/converge" \
    --rigid "$results/rigid" \
    --figures figures \
    --command "validation/regenerate.sh" \
    --out validation/REPORT.md
