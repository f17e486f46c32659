#!/bin/sh
# The surface cache's image does not depend on how many threads lavapipe
# runs, nor on where in its hash table a cell lands: its sums are integer
# atomics, whatever order the pixels come in, and a cell expires a fixed
# number of frames after its last samples, whenever the evict pass reaches
# its slot. 12 frames with cells expiring after 2 frames, on 1, 2 and 3
# threads, and with tables of other sizes (other slots for every cell).
# GRAPH: surface-cache-4ray.ini, its indirect cache with two coarse levels
# and its sun read at each point's own cell (the other gather), or
# tests/graphs/cache_fallback.ini (a sun cache with a fallback).
# usage: cache_threads.sh VOXRG GRAPH PATH OUT
set -e
voxrg=$1 graph=$2 path=$3 out=$4
render() {
    name=$1; shift
    "$voxrg" render "$graph" --validate --frames 12 --size 96x54 --camera "$path" --set sun_cache.evict_frames=2 \
        --set indirect_cache.evict_frames=2 --set indirect_cache.coarse_levels=2 --set sun_cache.bilinear=0 "$@" --out "$out/$name" >/dev/null
}
for n in 1 2 3; do
    LP_NUM_THREADS=$n render t$n
done
render small --set sun_cache.cells=65536 --set indirect_cache.cells=32768
render other --set sun_cache.cells=262144
for name in t2 t3 small other; do
    cmp -s "$out/t1/ldr.png" "$out/$name/ldr.png" || { echo "FAIL: the image of run $name differs from 1 thread's"; exit 1; }
done
echo "the same image on 1, 2 and 3 threads and with three table sizes"
