#!/usr/bin/env bash
# dtsl on a shared machine (docs/performance.md): `dtsl reconstruct` with its default thread count and
# with --threads 1, alternately, on an idle machine and then with one core kept busy by another process
# (a shell loop), best and median of --repeat runs each. The default must never be slower than one
# thread when a core is taken (the default takes the cores free at start and waits passively then:
# experiments/main.cpp).
#   bench/busy_core.sh [--repeat 3] [POINT_FILE ...]     # default: the rocker arm and fandisk's vertices
set -euo pipefail
cd "$(dirname "$0")/.."
repeat=3
files=()
while [ $# -gt 0 ]; do
  case "$1" in
    --repeat) repeat=$2; shift 2 ;;
    -*) echo "usage: bench/busy_core.sh [--repeat N] [POINT_FILE ...]" >&2; exit 2 ;;
    *) files+=("$1"); shift ;;
  esac
done
if [ ${#files[@]} -eq 0 ]; then
  files=(../shared/data/rocker-arm.obj "${DTSL_DATA_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/dtsl}/cgal-demo/data/meshes/fandisk.off")
fi
dtsl=build/experiments/dtsl
[ -x "$dtsl" ] || { echo "bench/busy_core.sh: $dtsl not built (scripts/setup.sh)" >&2; exit 1; }
out=$(mktemp -d)
spinner=""
trap '[ -n "$spinner" ] && kill "$spinner" 2>/dev/null; rm -rf "$out"' EXIT

seconds() {  # the wall time of one reconstruction, in seconds
  local start end
  start=$(date +%s.%N)
  "$dtsl" reconstruct "$@" --quiet >/dev/null
  end=$(date +%s.%N)
  awk -v a="$start" -v b="$end" 'BEGIN { printf "%.3f\n", b - a }'
}
summary() {  # best and median of the numbers on stdin
  sort -g | awk '{v[NR] = $1} END {m = (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2; printf "%.2f | %.2f", v[1], m}'
}

echo "| input | machine | default threads: best / median (s) | --threads 1: best / median (s) | default / one thread (medians) |"
echo "| --- | --- | ---: | ---: | ---: |"
for load in idle busy; do
  if [ "$load" = busy ]; then
    sh -c 'while :; do :; done' &
    spinner=$!
    sleep 1
  fi
  for f in "${files[@]}"; do
    [ -f "$f" ] || { echo "bench/busy_core.sh: no file $f" >&2; exit 1; }
    : >"$out/default"; : >"$out/one"
    for _ in $(seq 1 "$repeat"); do
      seconds "$f" "$out/m.ply" >>"$out/default"
      seconds "$f" "$out/m.ply" --threads 1 >>"$out/one"
    done
    d=$(summary <"$out/default"); o=$(summary <"$out/one")
    ratio=$(awk -v a="${d##*| }" -v b="${o##*| }" 'BEGIN { print a / b }')
    printf '| %s | %s | %s | %s | %.2f |\n' "$(basename "$f")" "$load" "${d/ | / \/ }" "${o/ | / \/ }" "$ratio"
  done
done
