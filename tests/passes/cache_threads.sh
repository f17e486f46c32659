#!/bin/sh
# The surface cache's image does not depend on how many threads lavapipe
# runs: its sums are integer atomics, whatever order the pixels come in.
# usage: cache_threads.sh VOXRG GRAPH PATH OUT
set -e
voxrg=$1 graph=$2 path=$3 out=$4
for n in 1 2 3; do
    LP_NUM_THREADS=$n "$voxrg" render "$graph" --validate --frames 4 --size 96x54 --camera "$path" --out "$out/t$n" >/dev/null
done
for n in 2 3; do
    cmp -s "$out/t1/ldr.png" "$out/t$n/ldr.png" || { echo "FAIL: the image with $n lavapipe threads differs from 1 thread's"; exit 1; }
done
echo "the same image on 1, 2 and 3 threads"
