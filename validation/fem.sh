#!/usr/bin/env bash
# Regenerates validation/FEM.md: the plane-stress finite element check of the paper's Section 3
# against the SDOF model, with the tables of this run of the code.
#
#   bash validation/fem.sh            (from the repository root; builds in release mode)
#
# Runs in a few seconds after the build (FLEXROCK_BIN names a binary to use instead of building
# one). Wall times stay in the result directories' timings.json (--timings-apart), not in FEM.md,
# so that FEM.md is the same from run to run; validation/check.sh compares it with the committed one. Result files go to validation/out/fem/<case>/.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ -n "${FLEXROCK_BIN:-}" ]; then
    bin=$FLEXROCK_BIN
else
    cargo build --release --quiet
    bin="${CARGO_TARGET_DIR:-target}/release/flexrock"
fi
model=models/ichinose1986.toml
out=validation/out/fem
rm -rf "$out"
mkdir -p "$out"

# A copy of the reference model with extra [fem] keys.
variant() { # name, [fem] lines
    { cat "$model"; printf '\n[fem]\n%s\n' "$2"; } > "$out/$1.toml"
    echo "$out/$1.toml"
}

run_case() { # case name, model file, extra flags...
    local name=$1 file=$2
    shift 2
    "$bin" fem "$file" --out "$out/$name" --compare --timings-apart "$@" > "$out/$name.txt" 2> "$out/$name.stderr"
}

run_case paper "$model"
run_case paper-average "$model" --scheme average-acceleration
run_case paper-wilson "$model" --scheme wilson-theta
run_case paper-dt0.0064 "$model" --dt 0.0064
run_case no-p-delta "$(variant no-p-delta 'p_delta = false')" --scheme average-acceleration
run_case fine-8x40 "$model" --nx 8 --ny 40 --scheme average-acceleration
plate=$(variant rigid-plate 'base = "rigid-plate"')
run_case plate "$plate" --scheme average-acceleration
run_case plate-8x40 "$plate" --nx 8 --ny 40 --scheme average-acceleration
"$bin" fem "$model" --pushover --nx 8 --ny 40 --timings-apart --out "$out/pushover" > "$out/pushover.txt"
"$bin" fem "$out/no-p-delta.toml" --pushover --nx 8 --ny 40 --timings-apart --out "$out/pushover-no-p-delta" \
    > "$out/pushover-no-p-delta.txt"
for mesh in "2 5" "4 20" "8 40"; do
    set -- $mesh
    "$bin" fem "$model" --modes --nx "$1" --ny "$2" > "$out/modes-$1x$2.txt"
done

# The figures the report shows: the paper's settings, and the stable scheme against the SDOF model.
figures=validation/figures/fem
rm -rf "$figures"
mkdir -p "$figures"
for f in "$out"/paper/fem_*.svg; do cp "$f" "$figures/paper-$(basename "$f")"; done
for f in "$out"/paper-average/compare_*.svg; do cp "$f" "$figures/average-$(basename "$f")"; done
for f in "$out"/plate/compare_*.svg; do cp "$f" "$figures/plate-$(basename "$f")"; done
cp "$out/pushover/pushover.svg" "$figures/pushover.svg"
cp "$out/pushover-no-p-delta/pushover.svg" "$figures/pushover-no-p-delta.svg"

figure() { # caption, file under validation/figures/fem
    printf '
%s

![%s](figures/fem/%s)
' "$1" "$1" "$2"
}

section() { # title, file: the command's output in a code block
    printf '\n#### %s\n\n```text\n' "$1"
    grep -v '^  wrote ' "$2"
    printf '```\n'
}
stderr_of() { if [ -s "$1" ]; then printf '\nOn stderr:\n\n```text\n'; cat "$1"; printf '```\n'; fi; }

{
    cat validation/fem-discussion.md
    printf '\n## Figures of this run\n\nStatic pushovers of the reference body (8 x 40), on the flexible base and on a rigid base plate, against the SDOF F(q):\n'
    figure "pushover with P-Delta" pushover.svg
    figure "pushover without P-Delta" pushover-no-p-delta.svg
    printf '\nThe paper'"'"'s settings (2 x 5 mesh, linear acceleration, dt = 0.0071 s, P-Delta on):\n'
    figure "Fig. 9: deformed shapes (x5) from 0.9 to 1.4 s" paper-fem_deformed_shapes.svg
    figure "Figs. 10-11: top displacement q and its flexural, rocking, slipping and shearing parts" paper-fem_components.svg
    figure "Fig. 12: q against r" paper-fem_q_vs_r.svg
    figure "Fig. 13: s against r" paper-fem_s_vs_r.svg
    figure "Fig. 14: top velocity" paper-fem_top_velocity.svg
    figure "Fig. 15: angular momentum about the left and right toes" paper-fem_angular_momentum.svg
    printf '\nThe FEM with average acceleration (no chatter) overlaid on the SDOF model:\n'
    figure "top displacement q, FEM and SDOF" average-compare_q.svg
    figure "flexural part s, FEM and SDOF" average-compare_flexural.svg
    figure "top velocity, FEM and SDOF" average-compare_top_velocity.svg
    figure "q against r, FEM and SDOF" average-compare_q_vs_r.svg
    figure "s against r, FEM and SDOF" average-compare_s_vs_r.svg
    printf '\nThe FEM on a rigid base plate (2 x 5, average acceleration) overlaid on the SDOF model:\n'
    figure "top displacement q, FEM on a rigid plate and SDOF" plate-compare_q.svg
    figure "flexural part s, FEM on a rigid plate and SDOF" plate-compare_flexural.svg
    figure "top velocity, FEM on a rigid plate and SDOF" plate-compare_top_velocity.svg
    figure "q against r, FEM on a rigid plate and SDOF" plate-compare_q_vs_r.svg
    figure "s against r, FEM on a rigid plate and SDOF" plate-compare_s_vs_r.svg
    printf '\n## Tables of this run\n\nGenerated by `bash validation/fem.sh` with flexrock %s.\n' \
        "$("$bin" --version | cut -d' ' -f2)"
    printf '\n### Static pushover (`flexrock fem --pushover`)\n'
    section "8 x 40, with P-Delta" "$out/pushover.txt"
    section "8 x 40, without P-Delta" "$out/pushover-no-p-delta.txt"
    printf '\n### Fixed-base periods (`flexrock fem --modes`)\n'
    for mesh in 2x5 4x20 8x40; do section "$mesh mesh" "$out/modes-$mesh.txt"; done
    printf '\n### FEM against SDOF (`flexrock fem --compare`)\n'
    section "paper's settings: 2 x 5, linear acceleration, dt = 0.0071 s" "$out/paper.txt"
    stderr_of "$out/paper.stderr"
    section "2 x 5, average acceleration, dt = 0.0071 s" "$out/paper-average.txt"
    section "2 x 5, Wilson theta = 1.4, dt = 0.0071 s" "$out/paper-wilson.txt"
    section "2 x 5, linear acceleration, dt = 0.0064 s (inside the limit)" "$out/paper-dt0.0064.txt"
    section "2 x 5, average acceleration, without P-Delta" "$out/no-p-delta.txt"
    section "8 x 40, average acceleration, dt = 0.0071 s" "$out/fine-8x40.txt"
    section "rigid base plate, 2 x 5, average acceleration, dt = 0.0071 s" "$out/plate.txt"
    section "rigid base plate, 8 x 40, average acceleration, dt = 0.0071 s" "$out/plate-8x40.txt"
} > validation/FEM.md
echo "wrote validation/FEM.md (result files in $out)"
