#!/bin/bash
# Fuzzes every mesh / point-set reader with libFuzzer (clang, libclang-rt-14-dev), ASan and
# UBSan: scripts/fuzz.sh [SECONDS_PER_TARGET (default 60)] [TARGET...]
# Targets: off obj ply gltf (all by default). Builds in build/fuzz with its own clang command
# lines (the readers and their small dependencies only), seeds each corpus from the mesh
# fixtures and the malformed corpus, runs each target for the time given and exits non-zero
# when any target found a crash, a sanitizer report, a timeout or an out-of-memory input
# (the reproducer is left in build/fuzz/ as crash-*, timeout-*, oom-*).
# Not part of `make test` (too slow); see README.md.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=${1:-60}
shift || true
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(off obj ply gltf)

CXX=${CXX:-clang++}
if ! command -v "$CXX" >/dev/null 2>&1; then
  echo "fuzz: $CXX not found; run scripts/install-deps.sh (clang, libclang-rt-14-dev)" >&2
  exit 4
fi
out=build/fuzz
mkdir -p "$out"
flags=(-std=c++20 -O1 -g -fno-omit-frame-pointer -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all
       -Isrc -Itests/fuzz -I/usr/include/eigen3 -Wall -Wextra)

status=0
for t in "${targets[@]}"; do
  case $t in
    off)  sources=(src/io/off_file.cpp);  libs=() ;;
    obj)  sources=(src/io/obj_file.cpp);  libs=(-ltinyobjloader_double) ;;
    ply)  sources=(src/io/ply_file.cpp);  libs=() ;;
    gltf) sources=(src/io/gltf_file.cpp); libs=(-ltinygltf) ;;
    *) echo "fuzz: unknown target '$t' (off obj ply gltf)" >&2; exit 2 ;;
  esac
  exe=$out/fuzz_$t
  echo "fuzz: building $exe"
  "$CXX" "${flags[@]}" -o "$exe" "tests/fuzz/fuzz_$t.cpp" "${sources[@]}" src/io/mesh_format_common.cpp "${libs[@]}"

  # Seeds: the fixtures of this format (glTF: both .gltf and .glb), copied into a working corpus
  # that libFuzzer grows between runs.
  corpus=$out/corpus_$t
  mkdir -p "$corpus"
  exts=("$t"); [ "$t" = gltf ] && exts=(gltf glb)
  for e in "${exts[@]}"; do
    find tests/fixtures/meshes tests/fixtures/malformed -maxdepth 1 -type f -name "*.$e" -exec cp -n {} "$corpus/" \;
  done

  echo "fuzz: running fuzz_$t for ${seconds}s on $(ls "$corpus" | wc -l) seeds"
  # -timeout: one input taking over 10 s is a hang; -rss_limit_mb: an allocation the header
  # asked for instead of the data is a bug too.
  if ! (cd "$out" && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
        "./fuzz_$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
        -print_final_stats=1 "corpus_$t" > "fuzz_$t.log" 2>&1); then
    echo "fuzz: fuzz_$t FAILED — see $out/fuzz_$t.log and the crash-*/timeout-*/oom-* file there" >&2
    tail -n 40 "$out/fuzz_$t.log" >&2
    status=1
  else
    grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "$out/fuzz_$t.log" | sed "s/^/fuzz: $t /" || true
  fi
done
exit $status
