#!/bin/bash
# Whole-process fit times in "units" of the yardstick (a 1000 × 1000 Eigen LU, scripts/yardstick.cpp),
# measured in the same run: the table of docs/performance.md, "Fit speed as users meet it".
#   [FIT_SPEED_BUSY=1] [FIT_SPEED_SOLVERS="lu ldlt"] scripts/fit_speed.sh [BUILD_DIR] [REPEATS]
# Needs the build's hermite-lab and yardstick targets. Prints one line per case: the median wall
# time of REPEATS whole processes (default 7), the median fit_ms they report, and both in units.
# Then, per case, the warm fit (the median of `hermite-lab bench`, refits in one process), the
# cold fit_ms over it, and what a whole process takes beyond the warm fit.
set -euo pipefail
BUILD=${1:-build/release}
REPEATS=${2:-7}
HL=$BUILD/hermite-lab
MIN=tests/fixtures/scenes/minimal.json
[ -x "$HL" ] && [ -x "$BUILD/yardstick" ] || { echo "fit_speed: build $BUILD first (targets hermite-lab yardstick)" >&2; exit 2; }

median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
# FIT_SPEED_BUSY=1: one competing busy process (a shell loop) for the whole run.
if [ "${FIT_SPEED_BUSY:-0}" = 1 ]; then
  sh -c 'while :; do :; done' &
  busy=$!
  trap 'kill $busy' EXIT
  echo "with one busy process competing (pid $busy)"
fi
unit=$(for _ in 1 2 3; do "$BUILD/yardstick"; done | median)
echo "unit (1000 x 1000 Eigen LU, -O2, 1 thread): $unit ms; load average $(cut -d' ' -f1 /proc/loadavg)"
printf '%-44s %10s %8s %10s %8s %s\n' case process_ms units fit_ms units solver

declare -A WALL FIT  # case key → medians, for the cold-versus-warm table
run_case() {  # name, key, then the fit arguments
  local name=$1 key=$2; shift 2
  local walls=() fits=() solver=
  for _ in $(seq "$REPEATS"); do
    local t0 t1 out
    t0=$(date +%s%N)
    out=$("$HL" fit "$MIN" "$@" --json)
    t1=$(date +%s%N)
    walls+=("$(( (t1 - t0) / 1000 ))")
    local fit
    read -r fit solver < <(python3 -c 'import json,sys; d = json.load(sys.stdin); print(d["fit_ms"], d["solver"])' <<<"$out")
    fits+=("$fit")
  done
  local wall fit
  wall=$(printf '%s\n' "${walls[@]}" | median)
  fit=$(printf '%s\n' "${fits[@]}" | median)
  WALL[$key]=$(awk -v w="$wall" 'BEGIN {print w / 1000}')
  FIT[$key]=$fit
  awk -v n="$name" -v w="$wall" -v f="$fit" -v u="$unit" -v s="$solver" \
    'BEGIN {printf "%-44s %10.1f %8.2f %10.1f %8.2f %s\n", n, w / 1000, w / 1000 / u, f, f / u, s}'
}

run_case "cubic + linear, N = 250" cubic-linear/N=250 --set data.preset=sphere --set data.count=250
run_case "cubic + linear, N = 500" cubic-linear/N=500 --set data.preset=sphere --set data.count=500
run_case "cubic + linear, N = 1000" cubic-linear/N=1000 --set data.preset=sphere --set data.count=1000
run_case "cubic, no polynomial, N = 1000 (auto)" cubic-none/N=1000 --set data.preset=sphere --set data.count=1000 --set fit.polynomial=none
for solver in ${FIT_SPEED_SOLVERS:-}; do
  run_case "cubic, no polynomial, N = 1000 ($solver)" "none-$solver" --set data.preset=sphere --set data.count=1000 \
    --set fit.polynomial=none --set fit.solver="$solver"
done

# The same cases warm: the bench's median fit over refits in one process (same sphere points).
printf '\n%-44s %10s %10s %12s %14s\n' case warm_ms cold_ms cold/warm process-warm
for key in cubic-linear/N=250 cubic-linear/N=500 cubic-linear/N=1000 cubic-none/N=1000; do
  warm=$("$HL" bench --only "fit3d/$key" --json | python3 -c 'import json,sys; print(json.load(sys.stdin)["results"][0]["median"])')
  awk -v k="$key" -v w="$warm" -v c="${FIT[$key]}" -v p="${WALL[$key]}" \
    'BEGIN {printf "%-44s %10.1f %10.1f %12.3f %14.1f\n", k, w, c, c / w, p - w}'
done
