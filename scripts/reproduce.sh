#!/usr/bin/env bash
# The main job from a fresh Debian 12 machine: install what is missing, build, and run
# `nocdyn reproduce` (results in ./results unless an output folder is given).
# Every option is set here, so that a cache left by scripts/test.sh in build/ does not matter.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DNOCDYN_BUILD_TESTS=OFF -DNOCDYN_BUILD_BENCHMARKS=OFF \
  -DNOCDYN_BUILD_VALIDATION=ON -DNOCDYN_SANITIZE=OFF -DNOCDYN_FUZZ=OFF -DNOCDYN_BUILD_PYTHON=ON -DNOCDYN_CPU_DISPATCH=ON
cmake --build build -j"$(nproc)" --target nocdyn_cli nocdyn_python
./build/nocdyn reproduce --out-dir "${1:-results}"
