#!/usr/bin/env bash
# Exact multiprecision references for every case, and the current adaptive solvers against them.
#
#   validation/exact/run.sh [FLEXROCK]        (from the repository root; FLEXROCK defaults to
#                                              target/release/flexrock)
#
# Writes validation/exact/reference/<case>/{events.csv,peaks.json} (the committed references) and
# compares `flexrock run` with the exact method, and with bdf and tsit45 at rtol = 1e-12,
# atol = 1e-14, against them
# (validation/exact/results/<case>-<method>.json and the table printed at the end).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
flexrock="${1:-target/release/flexrock}"
py="${PYTHON:-python3}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$here/results"
for model in "$here"/cases/*.toml; do
  case="$(basename "$model" .toml)"
  if [ -z "${SKIP_MP:-}" ]; then
    "$py" "$here/mp_exact.py" "$model" --out "$here/reference/$case"
  fi
  for method in exact bdf tsit45; do
    if [ "$method" = exact ]; then tolerances=(); else tolerances=(--rtol 1e-12 --atol 1e-14); fi
    "$flexrock" run "$model" --out "$tmp/$case-$method" --method "$method" "${tolerances[@]}" \
      --timings-apart >/dev/null 2>&1 || { echo "$case $method: flexrock run failed"; continue; }
    "$py" "$here/compare.py" "$tmp/$case-$method" "$here/reference/$case" --quiet \
      --json "$here/results/$case-$method.json" | sed "s/^/$case $method: /" || true
  done
done
