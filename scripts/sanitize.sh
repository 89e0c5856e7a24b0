#!/usr/bin/env bash
# The test suite under AddressSanitizer + UndefinedBehaviorSanitizer (clang, build-asan/), and the
# libFuzzer targets briefly, seeded from fuzz/seeds and the robustness corpus (fuzz/README.md).
#
#   scripts/sanitize.sh          the fast subset CI runs: the framework's and the T-spline's tests, the
#                                robustness corpus through `dtsl reconstruct
#                                --pipeline pcl_poisson` and `dtsl run` (every reader and the config
#                                loader on every bad file), crash safety, and each fuzz target for 10 s
#   scripts/sanitize.sh --full   every test executable and the corpus through the method too (about an
#                                hour on 2 cores: the evolution's and the method's tests run 10-25x
#                                slower under the sanitizers, the method's corpus 15 minutes)
#
# Needs the packages of scripts/setup.sh (clang, libclang-rt-14-dev). Prints the time of each part.
set -euo pipefail
cd "$(dirname "$0")/.."
full=0
for arg in "$@"; do
  case "$arg" in
    --full) full=1 ;;
    -h | --help) sed -n '2,13p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "sanitize.sh: unknown argument '$arg' (usage: scripts/sanitize.sh [--full])" >&2; exit 2 ;;
  esac
done
t0=$SECONDS
step() { echo "== [$((SECONDS - t0)) s] $*"; }

# The fast subset: every library is built (`dtsl` and the experiment fuzzer link them all), but only
# these test executables; the others (the method's stages, the command line's runs of the method, the
# baselines, rendering, Python) run in the Release suite and under --full.
quick_tests=(test_core test_io test_datasets test_metrics test_tspline test_robustness)

step "sanitizer build (clang, -fsanitize=address,undefined, libFuzzer targets)"
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1 -gline-tables-only" "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -gline-tables-only" \
  -DDTSL_SANITIZE=address,undefined -DDTSL_FUZZ=ON -DDTSL_BUILD_BENCH=OFF >/dev/null
if [ $full -eq 1 ]; then
  cmake --build build-asan -j2
else
  cmake --build build-asan -j2 --target dtsl dtsl_fuzzers "${quick_tests[@]}"
fi

step "test suite under ASan + UBSan"
# Suppressions: .ci/lsan.supp and .ci/ubsan.supp, each entry with the evidence that it is a library issue.
# alloc_dealloc_mismatch=0: Debian's PCL is compiled as C++14, where EIGEN_MAKE_ALIGNED_OPERATOR_NEW
# gives pcl::PointCloud a class operator new calling Eigen::internal::aligned_malloc (malloc); compiled
# as C++17 (dtsl), the same macro is empty, so a cloud PCL allocates inside libpcl_io and releases
# through a shared_ptr instantiated in our code (e.g. ~GridProjection) is freed with the global operator
# delete. ASan reports "malloc vs operator delete" inside PCL's own objects; both end in free(). This
# check cannot be suppressed per library, so it is off.
export ASAN_OPTIONS="detect_leaks=1:check_initialization_order=1:alloc_dealloc_mismatch=0"
export LSAN_OPTIONS="suppressions=$PWD/.ci/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:suppressions=$PWD/.ci/ubsan.supp"
export DTSL_ROBUSTNESS_TIMEOUT=600
if [ $full -eq 1 ]; then
  ctest --test-dir build-asan --output-on-failure -j2 --timeout 2400
else
  # The method's corpus and the determinism test (the method on every bad file; the method twice at two
  # thread counts) run in the Release suite, and here under --full.
  pattern="^($(IFS='|'; echo "${quick_tests[*]}")|test_robustness_corpus_baseline|test_robustness_crash)$"
  ctest --test-dir build-asan --output-on-failure -j2 --timeout 2400 -R "$pattern"
fi

step "fuzz targets, 10 s each"
unset ASAN_OPTIONS LSAN_OPTIONS UBSAN_OPTIONS
# fuzz_pcd is left out until PCD bodies are decoded without PCL's reader: fuzz/open_findings/ holds an
# input that still crashes pcl::PCDReader::read behind our validation (fuzz/README.md).
ARTIFACTS="$PWD/build-asan/fuzz-artifacts" fuzz/run.sh build-asan 10 ply ply_binary obj off xyz experiment

step "done"
