#!/usr/bin/env bash
# Regenerates validation/criteria/results/ (the overturning criteria study of the book chapter
# "Overturning criteria of elastic bodies", which links its figures there).
# Everything it writes is byte-stable from run to run except results/timings.json. About four
# minutes on two cores.
set -euo pipefail
cd "$(dirname "$0")/../.."
cargo build --release --quiet
FLEXROCK="${CARGO_TARGET_DIR:-target}/release/flexrock"
rm -rf validation/criteria/results
"$FLEXROCK" criteria models/pulse-map.toml --out validation/criteria/results \
    --slenderness 0.1 --slenderness 0.25 \
    --record validation/records/elCentro.AT2 \
    --check-record validation/records/A-ELC180.AT2 \
    --check-record validation/records/HEN-E.AT2
