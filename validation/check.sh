#!/usr/bin/env bash
# Regenerates, in place, every result in validation/ that flexrock computes, then fails if any
# file differs from the committed one, naming the file and its first differing line.
#
#   validation/check.sh          (from anywhere; builds the release binary unless FLEXROCK_BIN is set)
#
# What it reruns (validation/README.md, "What CI checks"):
#   1. validation/regenerate.sh: results/, figures/*.svg, REPORT.md;
#   2. validation/fem.sh: FEM.md and figures/fem/ (every case: a few seconds);
#   3. validation/self-weight/compare.py: self-weight/results/ except timings.json (needs numpy
#      and matplotlib, the versions of validation/requirements.txt: its SVGs are byte-compared);
#   4. flexrock's side of validation/sweep/: the sweeps of sweep/flexrock/commands.txt, against
#      the sweep.csv files sweep/compare.py compared with the reference;
#   5. then, when every file is the same: tests/report.rs (the committed results give the
#      committed REPORT.md).
# Not rerun: the OpenSees and scipy reference sides (validation/opensees/, the reference columns
# of validation/sweep/*_comparison.csv, tests/data/cases/ of validation/independent/); their
# outputs are committed with the commands and versions that made them, and flexrock's side of
# each comparison is checked here (3, 4) or by the test suite (core/tests/independent.rs).
#
# Wall times are not compared: every command runs with --timings-apart, so they go to the
# timings.json of each result directory, committed as measured when the evidence was made and put
# back as committed after the run.
# The check refuses to start when validation/ has uncommitted changes (they would be mixed with
# the regenerated files). Exit status: 0 same, 1 some file differs, 2 could not check.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD

if [ -n "$(git status --porcelain -- validation)" ]; then
    echo "validation/check.sh: validation/ has uncommitted changes; commit or stash them first:" >&2
    git status --short -- validation >&2
    exit 2
fi

started=$(date +%s)
if [ -z "${FLEXROCK_BIN:-}" ]; then
    cargo build --release --quiet
    FLEXROCK_BIN="${CARGO_TARGET_DIR:-$root/target}/release/flexrock"
fi
export FLEXROCK_BIN
step() { echo "== validation/check.sh: $1 ($(($(date +%s) - started)) s)"; }

step "regenerate.sh"
bash validation/regenerate.sh > /dev/null

step "fem.sh"
bash validation/fem.sh > /dev/null

step "self-weight/compare.py"
python="${PYTHON:-python3}"
if ! "$python" -c 'import numpy, matplotlib' 2> /dev/null; then
    echo "validation/check.sh: $python has no numpy or matplotlib (pip install -r validation/requirements.txt)" >&2
    exit 2
fi
"$python" validation/self-weight/compare.py > /dev/null

step "sweep/flexrock (flexrock's side of sweep/compare.py)"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
while read -r flexrock args; do
    [ "$flexrock" = flexrock ] || continue
    # shellcheck disable=SC2086 # the arguments are words without quotes or globs
    set -- ${args//OUT\//$tmp/}
    "$FLEXROCK_BIN" "$@" > /dev/null
    out=
    while [ $# -gt 0 ]; do
        if [ "$1" = --out ]; then out=$2; fi
        shift
    done
    cp "$out/sweep.csv" "validation/sweep/flexrock/$(basename "$out").csv"
done < validation/sweep/flexrock/commands.txt

step "comparing with the committed files"
# Wall times: kept as committed, never compared.
git ls-files -z -- 'validation/*timings.json' | xargs -0 -r git checkout --
changed=$(git status --porcelain --untracked-files=all -- validation)
if [ -z "$changed" ]; then
    echo "validation/check.sh: every regenerated file is byte for byte the committed one ($(($(date +%s) - started)) s)"
    step "tests/report.rs (the committed results give the committed REPORT.md)"
    cargo test --release --quiet --test integration report:: > "$tmp/report-test.log" 2>&1 || {
        cat "$tmp/report-test.log" >&2
        echo "validation/check.sh: tests/report.rs failed (REPORT.md does not follow from validation/results/)" >&2
        exit 1
    }
    echo "validation/check.sh: passed ($(($(date +%s) - started)) s)"
    exit 0
fi
echo "validation/check.sh: the regenerated evidence differs from the committed evidence:" >&2
while read -r status file; do
    case "$status" in
    '??') echo "  $file: new file, not committed" >&2 ;;
    D) echo "  $file: committed, no longer produced" >&2 ;;
    *)
        # The first hunk's first removed (committed) and added (regenerated) lines.
        git diff --no-color --unified=0 -- "$file" | awk -v file="$file" '
            /^@@/ && !hunk { hunk = 1; split($2, a, ","); line = substr(a[1], 2); next }
            hunk && /^-/ && !old { old = substr($0, 2); next }
            hunk && /^\+/ && !new { new = substr($0, 2) }
            hunk && /^@@/ { exit }
            END {
                printf "  %s: first difference at line %s\n", file, line
                printf "    committed:   %s\n", substr(old, 1, 200)
                printf "    regenerated: %s\n", substr(new, 1, 200)
            }' >&2
        ;;
    esac
done <<< "$changed"
echo "If the change is intended, commit the regenerated files (validation/README.md, 'Regenerating')." >&2
exit 1
