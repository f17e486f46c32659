#!/bin/sh
# The surface cache's image does not depend on where in its hash table a
# cell lands, nor on how many threads lavapipe runs: its sums are integer
# atomics, whatever order the pixels come in, and a cell expires a fixed
# number of frames after its last samples, whenever the evict pass reaches
# its slot. 12 frames with cells expiring after 2 frames, with tables of
# other sizes (other slots for every cell), then on 1, 2 and 3 threads.
# Threads are varied through LP_NUM_THREADS, which only lavapipe reads: on
# another device the three runs would be one, so the thread part is skipped
# there (exit 77, after the table sizes are checked).
# GRAPH: surface-cache-4ray.ini, its indirect cache with two coarse levels
# and its sun read at each point's own cell (the other gather), or
# tests/graphs/cache_fallback.ini (a sun cache with a fallback), or
# interactive.ini (half-size samples inserted by texel, signal_position).
# SETS: PASS.PARAM=VALUE words for every run (its caches' evict_frames,
# scene.edits=none: no edit journal beside the graph is read); SMALL and
# OTHER: the two runs' other table sizes.
# usage: cache_threads.sh VOXRG GRAPH PATH OUT SETS SMALL OTHER
set -e
# the settings are split into words, never expanded as file names
set -f
[ $# -eq 7 ] && [ -n "$6" ] && [ -n "$7" ] || { echo "usage: cache_threads.sh VOXRG GRAPH PATH OUT SETS SMALL OTHER (SMALL, OTHER: not empty)"; exit 2; }
voxrg=$1 graph=$2 path=$3 out=$4 sets=$5 small=$6 other=$7
mkdir -p "$out"
render() {
    name=$1; shift
    args=""
    for s in $sets "$@"; do args="$args --set $s"; done
    # $args unquoted: one word per --set and its value
    "$voxrg" render "$graph" --validate --frames 12 --size 96x54 --camera "$path" $args --out "$out/$name" >"$out/$name.log" 2>&1 ||
        { cat "$out/$name.log"; echo "FAIL: run $name"; exit 1; }
}
same() { # run: its image is run t1's
    cmp -s "$out/t1/ldr.png" "$out/$1/ldr.png" || { echo "FAIL: the image of run $1 differs from run t1's"; exit 1; }
}
LP_NUM_THREADS=1 render t1
# unquoted: one word per setting
render small $small
render other $other
same small
same other
echo "the same image with three table sizes"
# "voxrg: device NAME (...)": lavapipe's device is llvmpipe
device=$(sed -n 's/^voxrg: device \(.*\) (ray query.*/\1/p' "$out/t1.log")
[ -n "$device" ] || { cat "$out/t1.log"; echo "FAIL: run t1 names no device"; exit 1; }
case $device in
llvmpipe*) ;;
*) echo "skipped: threads not varied: the device is '$device', not lavapipe (LP_NUM_THREADS is lavapipe's)"; exit 77 ;;
esac
for n in 2 3; do
    LP_NUM_THREADS=$n render t$n
    same t$n
done
echo "the same image on 1, 2 and 3 threads"
