#!/usr/bin/env bash
# The second CI build: clang with AddressSanitizer and UndefinedBehaviorSanitizer
# (-fno-sanitize-recover=all), then each libFuzzer target for SECONDS seconds (default 60) from
# the seed corpora. Run from the project root after README command 2 (which installs the
# dependencies, fills build/npm and has run the whole suite on the Release build):
#
#   tests/fuzz/run.sh [SECONDS] [all]
#
# By default (CI) the pass builds what its own tests run, the tools and the fuzz targets, and
# runs the suites made for hostile input under the sanitizers: hostile/ (every tool on the hostile
# files, full disks, neighbours) and lsp.protocol (bodyls driven by a client), then the fuzz
# smokes. The unit tests, the dynamics test binaries and the corpus suites run in the first
# build only: a second full build and the whole suite again took 40 minutes here, and the first
# build already took 62 of CI's 90. `all` builds every target and runs the whole suite sanitized
# (by hand).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
seconds=${1:-60}
scope=${2:-focused}
build=build-sanitize
if [ "$(id -u)" -eq 0 ]; then S=; else S=sudo; fi
command -v clang++ >/dev/null && [ -n "$(find /usr/lib/llvm-14/lib/clang -name 'libclang_rt.fuzzer-x86_64.a' 2>/dev/null)" ] ||
  $S env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends clang libclang-rt-14-dev
# Line tables are all a sanitizer's stack trace needs; full debug info made each compile a sixth
# slower (61 s against 51 s for dynamics' generic_checks.cpp).
CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBODYFMT_FUZZ=ON \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -gline-tables-only -DNDEBUG" \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O2 -gline-tables-only -DNDEBUG" -DBODYFMT_NPM_PREFIX="$PWD/build/npm"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export LSAN_OPTIONS=suppressions=$PWD/tests/fuzz/lsan.supp
export BODYFMT_TIME_SCALE=6  # sanitized tools are several times slower (tests/hostile/run_case.py)
if [ "$scope" = all ]; then
  cmake --build "$build"
  # The package test links an outside project against the installed library, which would need
  # the sanitizer runtime flags too; the first build runs it, and the style checks (label
  # sources_only), which run none of the project's code, and the 100,000-link scale cases (label
  # release_only), which measure time and memory.
  ctest --test-dir "$build" --output-on-failure -j2 -E '^package\.find_package$' -LE '^(sources_only|release_only)$'
else
  # bodysim and fuzz_scenario exist only with Simbody.
  targets=()
  listed=$(ninja -C "$build" -t targets all)
  for t in bodyinfo bodycheck body2urdf body2mjcf body2gltf urdf2body bodydiff bodyview bodysim bodyls \
           fuzz_yaml fuzz_load fuzz_urdf fuzz_mjcf fuzz_gltf fuzz_urdf_import fuzz_text_outputs fuzz_fix \
           fuzz_scenario fuzz_lsp; do
    grep -qE "^$t: " <<<"$listed" && targets+=("$t")
  done
  cmake --build "$build" --target "${targets[@]}"
  ctest --test-dir "$build" --output-on-failure -j2 -R '^(hostile/|lsp\.protocol\.)' -LE '^(sources_only|release_only)$'
fi

# Seeds: every body and YAML file we have, and the small multi-file folders in tests/fuzz/seeds.
seeds=$build/fuzz-seeds
rm -rf "$seeds" && mkdir -p "$seeds/yaml" "$seeds/load"
n=0
while IFS= read -r -d '' f; do
  n=$((n + 1))
  cp "$f" "$seeds/yaml/$n"
  case "$f" in *.body) cp "$f" "$seeds/load/$n" ;; esac
done < <(find examples tests/data ../shared/corpus/choreonoid -type f \( -name '*.body' -o -name '*.yaml' \) -size -64k -print0 | sort -z)
cp tests/fuzz/seeds/* "$seeds/load/"
# bodysim scenarios: the examples' and the tests'.
mkdir -p "$seeds/scenario"
for f in examples/*.scenario.yaml tests/data/dynamics/*.scenario.yaml; do cp "$f" "$seeds/scenario/"; done
# URDFs for the importer: the tests', the corpus', and body2urdf's exports of the examples.
mkdir -p "$seeds/urdf_import"
while IFS= read -r -d '' f; do
  n=$((n + 1))
  cp "$f" "$seeds/urdf_import/$n"
done < <(find examples tests/data ../shared/corpus -type f -name '*.urdf' -size -64k -print0 | sort -z)
for f in examples/*.body; do
  "$build/body2urdf" "$f" -o "$seeds/urdf_import/$(basename "$f" .body).urdf" --devices-as-frames >/dev/null 2>&1 || true
done
# bodyls's sessions pick their models from the examples and the corpus themselves (no seeds).
mkdir -p "$seeds/lsp"
for target in yaml load urdf urdf_import mjcf gltf text_outputs fix scenario lsp; do
  [ -x "$build/tests/fuzz/fuzz_$target" ] || continue  # fuzz_scenario needs Simbody
  corpus=$build/fuzz-corpus/$target
  mkdir -p "$corpus"
  seed_dir=$seeds/load
  [ "$target" = yaml ] && seed_dir=$seeds/yaml
  [ "$target" = scenario ] && seed_dir=$seeds/scenario
  extra=()
  timeout=20
  # A session's edits come from its input: full-length inputs from the start (libFuzzer's
  # default grows them from 4 bytes, a session of one edit). A session checks its model after
  # many of its edits, so one input may take longer than one load.
  [ "$target" = lsp ] && seed_dir=$seeds/lsp && extra=(-len_control=0) && timeout=120
  dict=tests/fuzz/body.dict
  [ "$target" = urdf_import ] && seed_dir=$seeds/urdf_import && dict=tests/fuzz/urdf.dict
  echo "fuzz_$target: ${seconds} s"
  "$build/tests/fuzz/fuzz_$target" -max_total_time="$seconds" -rss_limit_mb=4096 -timeout="$timeout" -max_len=65536 \
    -dict="$dict" -print_final_stats=1 "${extra[@]}" "$corpus" "$seed_dir" 2>&1 | tail -n 12
done
