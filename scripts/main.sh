#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine, builds voxrg and renders the default graph
# (graphs/thesis.ini) headless to out/. `./build/voxrg run` then opens a
# window on graphs/interactive.ini (README.md, "Using it").
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build -j"$(nproc)"
./build/voxrg render graphs/thesis.ini --frames 16 --out out --json out/timings.json "$@"
echo "main: wrote out/$(sed -n 's/^output *= *\([A-Za-z0-9_.-]*\).*/\1/p' graphs/thesis.ini | head -1).png"
