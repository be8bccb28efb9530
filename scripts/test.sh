#!/usr/bin/env bash
# Sets up pushout (scripts/setup.sh) and runs the whole test suite (ctest).
set -euo pipefail
cd "$(dirname "$0")/.."
for a in "$@"; do
  case "$a" in -h | --help)
    echo "usage: scripts/test.sh [ctest's options: -R REGEX, -E REGEX, -j N, ...]"
    echo "sets up pushout (scripts/setup.sh: packages, build) and runs every test (ctest)"
    exit 0
    ;;
  esac
done
scripts/setup.sh
cd build
ctest --output-on-failure -j"$(nproc)" "$@"
