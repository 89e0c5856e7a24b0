#!/bin/bash
# A/B timing of two dtsl builds (docs/performance.md): `dtsl reconstruct` of the same point files with each binary,
# alternating OLD and NEW so that the machine's drift hits both, REPEAT times; prints every wall time,
# each binary's mean per file, and whether the two wrote byte-identical meshes (a speed-up that should
# not change results must say "identical").
#
#   bench/compare_builds.sh OLD_DTSL NEW_DTSL REPEAT POINTS.ply...
#
# e.g. (the old build from a git worktree of the commit to compare against):
#   git worktree add /tmp/old <commit> && cmake -S /tmp/old -B /tmp/old/build -G Ninja -DCMAKE_BUILD_TYPE=Release
#   ninja -C /tmp/old/build experiments/dtsl
#   bench/compare_builds.sh /tmp/old/build/experiments/dtsl build/experiments/dtsl 3 \
#     results/paper_table1/reference/datasets/{fandisk_cut,armadillo_25k}/points.ply
set -euo pipefail
if [ $# -lt 4 ]; then
  echo "usage: compare_builds.sh OLD_DTSL NEW_DTSL REPEAT POINTS..." >&2
  exit 2
fi
old=$1 new=$2 repeat=$3
shift 3
for b in "$old" "$new"; do [ -x "$b" ] || { echo "compare_builds.sh: $b is not an executable" >&2; exit 2; }; done
case $repeat in '' | *[!0-9]*) echo "compare_builds.sh: REPEAT must be a whole number, got '$repeat'" >&2; exit 2 ;; esac
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for points in "$@"; do
  [ -f "$points" ] || { echo "compare_builds.sh: no file $points" >&2; exit 2; }
  name=$(basename "$(dirname "$points")")/$(basename "$points")
  sum_old=0 sum_new=0 same=identical
  for ((r = 1; r <= repeat; ++r)); do
    for side in old new; do
      bin=$old
      [ $side = new ] && bin=$new
      start=${EPOCHREALTIME/./}  # microseconds (bash 5), no external tools
      "$bin" reconstruct "$points" "$work/$side.ply" > "$work/$side.log" 2>&1 || { cat "$work/$side.log" >&2; exit 1; }
      t=$((${EPOCHREALTIME/./} - start))
      printf '%s %s run %d: %d.%03d s\n' "$name" $side "$r" $((t / 1000000)) $((t / 1000 % 1000))
      if [ $side = old ]; then sum_old=$((sum_old + t)); else sum_new=$((sum_new + t)); fi
    done
    cmp -s "$work/old.ply" "$work/new.ply" || same=DIFFERENT
  done
  mean_old=$((sum_old / repeat / 1000)) mean_new=$((sum_new / repeat / 1000))  # milliseconds
  printf '%s: old %d.%03d s, new %d.%03d s (means of %d), meshes %s\n' "$name" $((mean_old / 1000)) \
    $((mean_old % 1000)) $((mean_new / 1000)) $((mean_new % 1000)) "$repeat" "$same"
done
