#!/bin/sh
# Every shipped pass a shipped graph uses lists its dispatches
# (vrg_plugin_desc.dispatches), so `voxrg check` compiles and reflects its
# shaders before any frame: no "lists no dispatches" line names a plugin of
# passes/. Plugins of other folders (scenes) are not held to it here.
# A graph of the vox scene reads its model from VOX_DIR (VRG_VOX_DIR); where
# that file is missing the graph is skipped, saying so (its passes are in
# the other graphs too).
# GRAPH...: more graphs to check (a test graph that keeps a pass no
# shipped graph uses any more).
# usage: check_listed_dispatches.sh VOXRG PASSES_DIR GRAPHS_DIR VOX_DIR [GRAPH...]
voxrg=$1 passes=$2 graphs=$3 voxdir=$4
shift 4
fail=0 count=0
out=$(mktemp) || exit 1
trap 'rm -f "$out"' EXIT
for graph in "$graphs"/*.ini "$@"; do
    count=$((count + 1))
    vox=$(sed -n 's#^file *= *.*/\([^/]*\.vox\) *$#\1#p' "$graph")
    set --
    if [ -n "$vox" ]; then
        if [ ! -f "$voxdir/$vox" ]; then
            echo "skipped $graph: $voxdir/$vox is missing (VRG_VOX_DIR)"
            count=$((count - 1))
            continue
        fi
        set -- --set "scene.file=$voxdir/$vox"
    fi
    if ! "$voxrg" check "$graph" --no-device "$@" >"$out" 2>&1; then
        echo "FAIL $graph: voxrg check --no-device failed"
        cat "$out"
        fail=1
        continue
    fi
    # "  PASS  PLUGIN  lists no dispatches ..."
    for plugin in $(awk '/ lists no dispatches / {print $2}' "$out"); do
        if [ -d "$passes/$plugin" ]; then
            echo "FAIL $graph: pass plugin $plugin lists no dispatches (passes/$plugin/$plugin.c: vrg_plugin_desc.dispatches)"
            fail=1
        fi
    done
done
[ "$count" -gt 0 ] || { echo "FAIL no graphs in $graphs"; exit 1; }
[ "$fail" -eq 0 ] && echo "check_listed_dispatches: $count graphs, every pass they use lists its dispatches"
exit $fail
