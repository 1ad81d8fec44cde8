#!/bin/bash
# Where a cold `fit` process takes its page faults: every anonymous writable mapping of 1 MiB or
# more (strace), the range advised MADV_HUGEPAGE (the kernel matrix), and the faults of one run
# (perf, one sample per fault with its address) bucketed by them. docs/performance.md, "What a
# cold fit allocates and touches".
#   scripts/fit_faults.sh [BUILD_DIR] [fit arguments...]
#   e.g. scripts/fit_faults.sh build/release --set data.preset=sphere --set data.count=1000
# Needs strace and perf (root, or perf_event_paranoid ≤ 1). Timings under perf and strace are
# not representative; the counts are.
set -euo pipefail
BUILD=${1:-build/release}
shift || true
MIN=tests/fixtures/scenes/minimal.json
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
# The program as the launcher runs it (src/launcher/launcher.c), without the launcher's exec.
HERMITE_REEXECUTED=1 OMP_WAIT_POLICY=PASSIVE OPENBLAS_THREAD_TIMEOUT=16 \
  perf record -q -e page-faults -c 1 -d -o "$TMP/pf.data" -- \
  strace -f -e trace=mmap,madvise -o "$TMP/mmap.txt" "$BUILD/hermite-lab-cli" fit "$MIN" "$@" --json >"$TMP/fit.json"
perf script -i "$TMP/pf.data" -F addr 2>/dev/null >"$TMP/faults.txt"
python3 - "$TMP" <<'PY'
import collections, json, re, sys
tmp = sys.argv[1]
regions = []  # (start, bytes, name)
for line in open(f"{tmp}/mmap.txt"):
    m = re.match(r"(\d+)\s+mmap\(NULL, (\d+), (\S+), (\S+),.*= (0x[0-9a-f]+)", line)
    if m and int(m.group(2)) >= 1 << 20 and "WRITE" in m.group(3):
        regions.append((int(m.group(5), 16), int(m.group(2)), f"mapping of {int(m.group(2)) / 2**20:.0f} MiB, thread {m.group(1)}"))
    m = re.match(r"(\d+)\s+madvise\((0x[0-9a-f]+), (\d+), MADV_HUGEPAGE", line)
    if m:  # the advised range plus the unaligned ends around it (at most 2 MB each)
        regions.append((int(m.group(2), 16) - (2 << 20), int(m.group(3)) + (4 << 20), f"advised MADV_HUGEPAGE ({int(m.group(3)) / 2**20:.0f} MiB) and its ends"))
counts = collections.Counter()
for line in open(f"{tmp}/faults.txt"):
    try:
        addr = int(line.split()[0], 16)
    except (ValueError, IndexError):
        continue
    counts[next((n for a, s, n in regions if a <= addr < a + s), "everything else (libraries, stacks, small blocks)")] += 1
fit = json.load(open(f"{tmp}/fit.json"))
print(f"solver {fit['solver']}, {sum(counts.values())} page faults")
for name, c in counts.most_common():
    print(f"{c:8d}  {name}")
PY
