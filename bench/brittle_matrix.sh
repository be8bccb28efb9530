#!/bin/bash
# Brittle adhesion under each push control (issue 16): the friction +
# adhesion demo (paper mesh, quarter model, condensed) with
#   interface.1.c in {100, 400, 2000} 1/mm x f_t in {3, 6} MPa
#   x k in {1e3, 1e5} N/mm^3 (both layers), 0.5 mm in 10 steps, dT -25 degC,
# one line per case: exit code, Newton iterations, steps controlled by
# energy, steps, cuts, wall time. Usage (from the repository root):
#   bench/brittle_matrix.sh CONTROL > bench/results/brittle_matrix_CONTROL.txt
ctl=${1:-dissipation}
for c in 100 400 2000; do for ft in 3 6; do for k in 1e3 1e5; do
  out=/tmp/brittle_matrix/${ctl}_${c}_${ft}_${k}
  s=$(date +%s.%N)
  timeout 600 build/pushout run demo/pushout_friction_adhesion.toml --out "$out" --force --quiet \
    --set interface.1.c=$c --set interface.1.f_t=$ft --set interface.0.k=$k --set interface.1.k=$k \
    --set loading.push_displacement=0.5 --set loading.steps=10 --set loading.control="$ctl" \
    --set output.plot=false > "$out.log" 2>&1
  rc=$?
  e=$(date +%s.%N)
  its=$(/usr/bin/python3 -c "import json; d = json.load(open('$out/summary.json')); print(d['newton_iterations'], d.get('dissipation_steps'), d['steps'], d['cuts'])" 2>/dev/null)
  printf "%s c=%s f_t=%s k=%s exit=%s iterations/energy_steps/steps/cuts=%s wall=%.1f s\n" \
    "$ctl" $c $ft $k $rc "$its" "$(echo "$e - $s" | bc)"
done; done; done
