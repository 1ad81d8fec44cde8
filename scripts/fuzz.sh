#!/bin/bash
# Fuzzes every input reader with libFuzzer (clang, libclang-rt-14-dev), ASan and UBSan:
# scripts/fuzz.sh [SECONDS_PER_TARGET (default 60)] [TARGET...]
# Targets: off obj ply gltf points scene (all by default). Builds in build/fuzz with its own
# clang command lines (the readers and their small dependencies only), seeds each corpus from
# the fixtures of its format and tests/fuzz/seeds/TARGET, runs each target for the time given
# and exits non-zero
# when any target found a crash, a sanitizer report, a timeout or an out-of-memory input
# (the reproducer is left in build/fuzz/ as crash-*, timeout-*, oom-*).
# Not part of `make test` (too slow); see README.md.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=${1:-60}
shift || true
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(off obj ply gltf points scene)

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
  mesh_readers=(src/io/off_file.cpp src/io/obj_file.cpp src/io/ply_file.cpp src/io/gltf_file.cpp
                src/io/gltf_file_access.cpp src/io/mesh_file.cpp src/io/atomic_file.cpp)
  case $t in
    off)  sources=(src/io/off_file.cpp);  libs=() ;;
    obj)  sources=(src/io/obj_file.cpp);  libs=(-ltinyobjloader_double) ;;
    ply)  sources=(src/io/ply_file.cpp);  libs=() ;;
    gltf) sources=(src/io/gltf_file.cpp src/io/gltf_file_access.cpp); libs=(-ltinygltf) ;;
    points) sources=(src/io/point_file.cpp "${mesh_readers[@]}" src/core/points/*.cpp src/core/base/format_number.cpp
                     src/core/base/threading.cpp)
            libs=(-ltinyobjloader_double -ltinygltf -lopenblas -fopenmp) ;;
    # The scene reader is instrumented; what its key tables call (presets, kernels, the patch and
    # hole-fill documents) is linked from a release build: run `make build` first.
    scene) sources=(src/scene/scene_file.cpp src/scene/scene_reader.cpp src/scene/scene_*_keys.cpp)
           release=build/release
           libs=(-Wl,--start-group "$release"/libhermite_scene.a "$release"/libhermite_io.a
                 "$release"/libhermite_core_*.a -Wl,--end-group -ltinyobjloader_double -ltinygltf
                 -llapacke -lopenblas -fopenmp) ;;
    *) echo "fuzz: unknown target '$t' (off obj ply gltf points scene)" >&2; exit 2 ;;
  esac
  exe=$out/fuzz_$t
  echo "fuzz: building $exe"
  "$CXX" "${flags[@]}" -o "$exe" "tests/fuzz/fuzz_$t.cpp" "${sources[@]}" src/io/mesh_format_common.cpp \
    src/io/input_file.cpp src/io/quoted_token.cpp "${libs[@]}"

  # Seeds: the fixtures of this format (glTF: both .gltf and .glb; points: the point fixtures;
  # scene: the fixture and teaching scenes) and tests/fuzz/seeds/TARGET, copied into a working
  # corpus that libFuzzer grows between runs.
  corpus=$out/corpus_$t
  mkdir -p "$corpus"
  case $t in
    points) seed_dirs=(tests/fixtures/points); exts=(xyz xyzn pwn xyn txt) ;;
    scene)  seed_dirs=(tests/fixtures/scenes assets/scenes); exts=(json) ;;
    gltf)   seed_dirs=(tests/fixtures/meshes tests/fixtures/malformed); exts=(gltf glb) ;;
    *)      seed_dirs=(tests/fixtures/meshes tests/fixtures/malformed); exts=("$t") ;;
  esac
  for e in "${exts[@]}"; do
    find "${seed_dirs[@]}" -maxdepth 1 -type f -name "*.$e" -exec cp -n {} "$corpus/" \;
  done
  [ -d "tests/fuzz/seeds/$t" ] && find "tests/fuzz/seeds/$t" -type f -exec cp -n {} "$corpus/" \;

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
    # Coverage: libFuzzer's last status line (cov: edges, ft: features, corp: corpus size).
    grep -E "^#[0-9]+.*cov: " "$out/fuzz_$t.log" | tail -n 1 | sed "s/^/fuzz: $t /" || true
  fi
done
exit $status
