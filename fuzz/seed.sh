#!/usr/bin/env bash
# Seeds fuzz/corpus/<target>/ from examples/mechanisms/*.ron (existing corpus files stay).
# parse and generate: each example file as it is. solve: each example file, a NUL byte, and
# a few state tails (the first tail byte picks the number encoding, see
# fuzz_targets/solve.rs): none (all zeros), small i16/1000 values, wide-range values, and
# raw f64 bit patterns.
set -euo pipefail
cd "$(dirname "$0")"
examples=(../examples/mechanisms/*.ron)
mkdir -p corpus/parse corpus/solve corpus/generate
for f in "${examples[@]}"; do
    name=$(basename "$f" .ron)
    cp "$f" "corpus/parse/$name.ron"
    cp "$f" "corpus/generate/$name.ron"
    # Text only: the solver at rest.
    cp "$f" "corpus/solve/$name.ron"
    # Mode 1 (i16 / 1000): 0.1, 0.5, 0.3, -0.2, 1.0, ... repeated.
    { cat "$f"; printf '\0\001'; for _ in 1 2 3 4 5 6; do printf '\144\000\364\001\054\001\070\377\350\003'; done; } \
        > "corpus/solve/$name.small"
    # Mode 2 (i16 / 32768 · 10^(e − 32)): values from 1e-3 to 1e3.
    { cat "$f"; printf '\0\002'; for _ in 1 2 3 4 5 6; do printf '\000\100\035\000\300\041\377\177\043'; done; } \
        > "corpus/solve/$name.wide"
    # Mode 0 (raw f64): 1.0, -2.5, 1e300, 0.25, ...
    { cat "$f"; printf '\0\000'; python3 -c 'import struct,sys; sys.stdout.buffer.write(struct.pack("<12d", *([1.0, -2.5, 1e300, 0.25] * 3)))'; } \
        > "corpus/solve/$name.raw"
done
echo "seeded: $(ls corpus/parse | wc -l) parse, $(ls corpus/solve | wc -l) solve, $(ls corpus/generate | wc -l) generate"
