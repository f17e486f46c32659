#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine, builds voxrg twice (release, and clang
# with AddressSanitizer + UndefinedBehaviorSanitizer + the libFuzzer target)
# and runs the whole ctest suite in both. Every test runs under the Khronos
# validation layer with synchronization validation.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
jobs=$(nproc)

cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build -j"$jobs"
(cd build && ctest --output-on-failure -j"$jobs")

CC=clang CXX=clang++ cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DVOXRG_SANITIZE=ON -DVOXRG_FUZZ=ON >/dev/null
cmake --build build-asan -j"$jobs"
(cd build-asan && ctest --output-on-failure -j"$jobs")
