#!/usr/bin/env bash
# Runs the fuzz targets of a DTSL_FUZZ=ON build, each for SECONDS, one after the other, seeded from
# fuzz/seeds/, the robustness corpus (tests/robustness/corpus) and, for the experiment loader,
# configs/. New inputs go to a scratch corpus; a crash, leak, timeout or violated property is saved in
# ARTIFACTS (default: fuzz-artifacts/) and makes the script exit non-zero after all targets ran.
#   fuzz/run.sh BUILD_DIR SECONDS [TARGET ...]      (targets: ply ply_binary obj off xyz pcd experiment)
set -uo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
build="$1"
seconds="$2"
shift 2
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(ply ply_binary obj off xyz pcd experiment)
artifacts="${ARTIFACTS:-$PWD/fuzz-artifacts}"
mkdir -p "$artifacts"
corpus="$root/tests/robustness/corpus"
failed=0
for t in "${targets[@]}"; do
  case "$t" in
    ply | ply_binary) seeds=("$here/seeds/ply" "$corpus/points") ;;
    experiment) seeds=("$here/seeds/experiment" "$root/configs" "$corpus/configs") ;;
    *) seeds=("$here/seeds/$t" "$corpus/points") ;;
  esac
  work="$(mktemp -d)"
  echo "== fuzz_$t for ${seconds}s"
  if ! "$build/fuzz/fuzz_$t" "$work" "${seeds[@]}" -max_total_time="$seconds" -timeout=20 -rss_limit_mb=2560 \
      -max_len=65536 -print_final_stats=1 -artifact_prefix="$artifacts/${t}-" 2>"$artifacts/fuzz_$t.log"; then
    echo "fuzz_$t FAILED: see $artifacts/fuzz_$t.log"
    tail -40 "$artifacts/fuzz_$t.log"
    failed=1
  else
    grep -E "stat::number_of_executed_units|stat::new_units_added" "$artifacts/fuzz_$t.log" | tr '\n' ' '
    echo
  fi
  rm -rf "$work"
done
exit $failed
