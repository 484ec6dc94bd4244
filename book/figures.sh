#!/usr/bin/env bash
# Draws the figures the book shows (book/src/figures/) by running the commands of the pages that
# show them, as the test suite does (tests/quoted_outputs.rs), and writes each into place. Run it
# from anywhere in a clone after a change that alters a figure, look at the figures, and commit
# them: the test fails while a committed figure differs from what its page's commands draw.
set -euo pipefail
cd "$(dirname "$0")/.."
mkdir -p book/src/figures
FLEXROCK_WRITE_FIGURES=1 cargo test --release --test integration -- --exact \
    quoted_outputs::the_documents_quote_what_the_program_prints
