#!/usr/bin/env bash
# The speed bench (docs/performance.md): configs/bench_speed.yaml run --repeat times (each run a process
# of its own, --jobs 1, --threads per run), then the best of the repeats per dataset and pipeline as a
# Markdown table (results/bench/speed.md), one JSON line per run (results/bench/speed.jsonl) and a
# log-log plot of time against points (docs/figures/speed.png). Repeats already done are kept (the
# runner skips finished runs), so an interrupted bench goes on where it stopped. Run it on an
# otherwise idle machine; iPSR first: bash ../shared/yardsticks/build.sh
#   bench/speed.sh [--repeat 3] [--run-id reference] [--threads 2] [--set KEY=VALUE ...]
set -euo pipefail
cd "$(dirname "$0")/.."
repeat=3 id=reference threads=2 sets=()
while [ $# -gt 0 ]; do
  case "$1" in
    --repeat) repeat=$2; shift 2 ;;
    --run-id) id=$2; shift 2 ;;
    --threads) threads=$2; shift 2 ;;
    --set) sets+=(--set "$2"); shift 2 ;;
    *) echo "usage: bench/speed.sh [--repeat N] [--run-id ID] [--threads N] [--set KEY=VALUE ...]" >&2; exit 2 ;;
  esac
done
dtsl=build/experiments/dtsl
[ -x "$dtsl" ] || { echo "bench/speed.sh: $dtsl not built (scripts/setup.sh)" >&2; exit 1; }
[ -x /tmp/dtsl-yardsticks/ipsr ] || echo "bench/speed.sh: iPSR not built; its runs will say skipped (bash ../shared/yardsticks/build.sh)" >&2
dirs=()
for k in $(seq 1 "$repeat"); do
  "$dtsl" run configs/bench_speed.yaml --jobs 1 --threads "$threads" --run-id "${id}_r$k" ${sets[@]+"${sets[@]}"}
  dirs+=("results/bench_speed/${id}_r$k")
done
mkdir -p results/bench docs/figures
/usr/bin/python3 bench/speed_table.py "${dirs[@]}" --plot docs/figures/speed.png --json results/bench/speed.jsonl \
  > results/bench/speed.md
cat results/bench/speed.md
