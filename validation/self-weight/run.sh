#!/usr/bin/env bash
# Regenerates validation/self-weight/results/ from scratch: builds the release binary (unless
# FLEXROCK_BIN names one) and runs compare.py, which runs every flexrock command it needs
# (listed afterwards in results/commands.txt) and deletes results/ first.
# Needs Python 3 with numpy and matplotlib (pip install matplotlib). About 20 s after the build.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
if [ -z "${FLEXROCK_BIN:-}" ]; then
    (cd "$root" && cargo build --release)
    export FLEXROCK_BIN="${CARGO_TARGET_DIR:-$root/target}/release/flexrock"
fi
"${PYTHON:-python3}" "$here/compare.py"
