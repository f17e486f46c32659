#!/bin/sh
# Frames in flight change when the CPU records, never what is rendered: the
# thesis graph along walk.path renders the same PNG files (every frame of
# --sequence, written by render's writer thread, and the final one) with
# frames_in_flight = 1 as with the default 2 and with 4.
# Usage: test_frames_in_flight.sh VOXRG SOURCE_DIR OUT_DIR
voxrg=$1 src=$2 out=$3
rm -rf "$out" && mkdir -p "$out" || exit 1
fail=0
render() { # N: a copy of thesis.ini with frames_in_flight = N (none: the default)
    dir="$out/fif$1"
    mkdir -p "$dir"
    if [ "$1" = default ]; then
        graph="$src/graphs/thesis.ini"
    else
        graph="$dir/thesis.ini"
        sed "s/^\[graph\]\$/[graph]\nframes_in_flight = $1/" "$src/graphs/thesis.ini" >"$graph"
        grep -q "^frames_in_flight = $1\$" "$graph" || { echo "FAIL: no frames_in_flight in $graph"; exit 1; }
    fi
    "$voxrg" render "$graph" --validate --frames 4 --size 160x90 --camera "$src/graphs/paths/walk.path" --sequence --out "$dir/png" \
        2>"$dir/stderr" || { echo "FAIL: render with frames_in_flight $1"; cat "$dir/stderr"; fail=1; }
}
render 1
render default
render 4
for n in default 4; do
    for f in ldr.png ldr-00000.png ldr-00001.png ldr-00002.png ldr-00003.png; do
        if cmp -s "$out/fif1/png/$f" "$out/fif$n/png/$f"; then
            echo "ok: $f with frames_in_flight $n"
        else
            echo "FAIL: $f differs between frames_in_flight 1 and $n"
            fail=1
        fi
    done
done
exit $fail
