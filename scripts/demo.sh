#!/usr/bin/env bash
# Sets up pushout (scripts/setup.sh) and runs the default scene,
# demo/pushout_friction.toml, into results/pushout_friction/.
set -euo pipefail
cd "$(dirname "$0")/.."
for a in "$@"; do
  case "$a" in -h | --help)
    echo "usage: scripts/demo.sh [pushout run's options: --set key=value, --quiet, ...]"
    exit 0
    ;;
  esac
done
scripts/setup.sh pushout # the program alone: the unit tests are scripts/test.sh's
out=results/pushout_friction
build/pushout run demo/pushout_friction.toml --out "$out" "$@"
echo "curve: $out/curve.csv  plot: $out/curve.png  summary: $out/summary.json"
