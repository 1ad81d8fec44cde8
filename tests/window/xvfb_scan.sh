#!/bin/bash
# Issue 18's "Done when" on a raw scan, in the real window under Xvfb + xdotool:
#   - a raw 5 000-point scan (positions only, no normals) opens from the command line: its fit and
#     settled view arrive, and the window title names the file;
#   - F1 is taken by a frame within 0.5 s of arriving, while the view is being computed;
#   - Cancel of a running dense fit frees the CPU: 0.2 s after the click the process uses less
#     than half a core over 0.3 s (its utime + stime, /proc/PID/stat), where the factorisation
#     kept both cores busy.
# Exit 77 = skipped (no Xvfb / xdotool) unless HERMITE_REQUIRE_XVFB=1.
#   usage: xvfb_scan.sh HERMITE_LAB_EXE
set -u
EXE=$1
WORK=$(mktemp -d)
APID=""
XPID=""
cleanup() {
  [ -n "$APID" ] && kill "$APID" 2>/dev/null
  [ -n "$XPID" ] && kill "$XPID" 2>/dev/null
  rm -rf "$WORK"
}
trap cleanup EXIT
fail() { echo "FAIL: $*"; [ -f "$WORK/app.log" ] && sed 's/^/  app: /' "$WORK/app.log"; [ -f "$WORK/gui.log" ] && tail -3 "$WORK/gui.log" | sed 's/^/  log: /'; exit 1; }

source "$(dirname "$0")/xvfb_common.sh"
require_tools Xvfb xdotool python3
start_xvfb 231 300

# Two raw scans of a noisy torus: 5 000 points (opened as it is: the fit picks the partition of
# unity) and 2 500 points (fitted dense, 10 000 unknowns: about 5 s of factorisation on a 2-core
# AVX-512 machine, more elsewhere; 1 500 points took only 0.7-1.4 s there, so the fit could end
# between the check that it runs and the click).
python3 - "$WORK" <<'PY'
import math, random, sys
random.seed(7)
for name, n in (("scan.xyz", 5000), ("small.xyz", 2500)):
    with open(f"{sys.argv[1]}/{name}", "w") as f:
        for _ in range(n):
            u, v = random.uniform(0, 2 * math.pi), random.uniform(0, 2 * math.pi)
            r = 0.35 + random.gauss(0, 0.002)
            f.write(f"{(1 + r * math.cos(v)) * math.cos(u):.6f} {(1 + r * math.cos(v)) * math.sin(u):.6f} {r * math.sin(v):.6f}\n")
PY

# Queries over the frame log: "idle" (a fit is on screen, nothing runs), "last" (frame number),
# "key K F" (input wait of the first frame after F that took key K), "widget NAME" (its centre).
q() { python3 - "$WORK/gui.log" "$@" <<'PY'
import json, sys
lines = [json.loads(l) for l in open(sys.argv[1]) if l.strip()]
frames = [l for l in lines if "frame" in l]
what = sys.argv[2]
if what == "idle":
    f = frames[-1] if frames else None
    print(1 if f and f["fits"] >= 1 and not f["fit_running"] and not f["view_pending"] else 0)
elif what == "last":
    print(frames[-1]["frame"] if frames else 0)
elif what == "running":
    print(1 if frames and frames[-1]["fit_running"] else 0)
elif what == "key":
    k, after = int(sys.argv[3]), int(sys.argv[4])
    hit = [f for f in frames if f["frame"] > after and k in f["keys"]]
    print(hit[0]["input_wait_ms"] if hit else "none")
elif what == "widget":
    widgets = {}
    for l in lines:
        widgets.update(l.get("widgets", {}))
    r = widgets.get(sys.argv[3])
    print(f"{round((r[0] + r[2]) / 2)} {round((r[1] + r[3]) / 2)}" if r else "none")
PY
}
start_app() {
  rm -f "$WORK/gui.log"
  HERMITE_GUI_LOG="$WORK/gui.log" "$EXE" "$@" > "$WORK/app.log" 2>&1 &
  APID=$!
  WID=$(timeout 60 xdotool search --sync --name "Hermite Lab" 2> /dev/null | head -1)
  [ -n "$WID" ] || fail "no window appeared"
  eval "$(xdotool getwindowgeometry --shell "$WID")"  # X Y WIDTH HEIGHT
  for _ in $(seq 100); do [ -s "$WORK/gui.log" ] && break; sleep 0.1; done
}
quit_app() {
  xdotool key --clearmodifiers ctrl+q
  for _ in $(seq 100); do kill -0 "$APID" 2> /dev/null || break; sleep 0.1; done
  if kill -0 "$APID" 2> /dev/null; then fail "the program did not quit on Ctrl+Q"; fi
  wait "$APID"; local rc=$?
  APID=""
  [ "$rc" = 0 ] || fail "exit code $rc"
}

# 1. The raw scan from the command line; F1 while its view is computed; the fit and view arrive.
start_app "$WORK/scan.xyz"
TITLE=$(xdotool getwindowname "$WID")
case "$TITLE" in *scan.xyz*) ;; *) fail "the window title '$TITLE' does not name scan.xyz" ;; esac
sleep 1
BEFORE=$(q last)
xdotool key F1; sleep 1
WAIT=$(q key 290 "$BEFORE")  # GLFW_KEY_F1 = 290
[ "$WAIT" != none ] || fail "F1 was never taken by a frame"
echo "F1 while the scan is fitted and drawn: taken $WAIT ms after it arrived"
python3 -c "import sys; sys.exit(0 if float('$WAIT') <= 500 else 1)" || fail "F1 waited $WAIT ms (limit 500)"
T0=$(date +%s)
for _ in $(seq 1200); do [ "$(q idle)" = 1 ] && break; sleep 0.2; done
[ "$(q idle)" = 1 ] || fail "the scan's fit and settled view did not arrive within 240 s"
echo "the 5 000-point scan is fitted and drawn, $(( $(date +%s) - T0 )) s after F1"
quit_app

# 2. A dense fit of the small scan; Cancel while it factorises.
start_app "$WORK/small.xyz" --set fit.partition.enabled=false
for _ in $(seq 300); do [ "$(q widget diagnostics.cancel)" != none ] && break; sleep 0.1; done
read -r CX CY <<< "$(q widget diagnostics.cancel)"
[ "$CX" != none ] || fail "no Cancel button while the dense fit runs"
sleep 1  # well inside the factorisation
[ "$(q running)" = 1 ] || fail "the dense fit ended before Cancel (too fast to test)"
ticks() { awk '{print $14 + $15}' "/proc/$APID/stat"; }
HZ=$(getconf CLK_TCK)
A=$(ticks); sleep 0.3; B=$(ticks)
echo "CPU time of the process over 0.3 s while the dense fit runs: $(( (B - A) * 1000 / HZ )) ms"
[ "$(q running)" = 1 ] || fail "the dense fit ended before Cancel was clicked (too fast to test)"
xdotool mousemove $((X + CX)) $((Y + CY)); sleep 0.1
xdotool click 1
sleep 0.2
A=$(ticks); sleep 0.3; B=$(ticks)
CPU_MS=$(( (B - A) * 1000 / HZ ))
echo "CPU time of the process over 0.3 s, 0.2 s after Cancel: $CPU_MS ms"
[ "$CPU_MS" -lt 150 ] || fail "the process still used $CPU_MS ms of CPU in 300 ms after Cancel"
[ "$(q running)" = 0 ] || fail "the log still shows a fit running after Cancel"
quit_app
echo "PASS"
