#!/bin/bash
# The real window stays responsive while work runs (issue 18), under Xvfb + xdotool:
#   - a view toggle (the bounds box) clicked right after an orbit, while the settled view (128³
#     bake, exact refinement) is computed on the view's worker, changes the document within 0.5 s
#     of the click and submits no fit;
#   - a key pressed right after that is taken by a frame within 0.5 s;
#   - the slowest frame and the largest gap between frames are reported;
#   - Ctrl+Q quits.
# The program writes a frame log (HERMITE_GUI_LOG, docs/cli.md) that says when each frame began,
# how long its oldest input event waited, which keys went down, the fits submitted so far and
# whether view work was pending. Exit 77 = skipped (no Xvfb / xdotool) unless HERMITE_REQUIRE_XVFB=1.
#   usage: xvfb_busy.sh HERMITE_LAB_EXE
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
fail() { echo "FAIL: $*"; [ -f "$WORK/app.log" ] && sed 's/^/  app: /' "$WORK/app.log"; [ -f "$WORK/gui.log" ] && tail -5 "$WORK/gui.log" | sed 's/^/  log: /'; exit 1; }

source "$(dirname "$0")/xvfb_common.sh"
require_tools Xvfb xdotool python3
start_xvfb 161 230

# A partition-of-unity fit of the bunny's 1 839 samples: the fit takes a moment, the settled
# view (bake and exact refinement at full size) takes seconds on llvmpipe.
cat > "$WORK/scene.json" <<'JSON'
{"version": 1, "mode": "implicit3d", "data": {"preset": "bunny", "count": 1839},
 "fit": {"partition": {"enabled": true}}, "view": {"show_normals": false}}
JSON

HERMITE_GUI_LOG="$WORK/gui.log" "$EXE" "$WORK/scene.json" > "$WORK/app.log" 2>&1 &
APID=$!
WID=$(timeout 60 xdotool search --sync --name "Hermite Lab" 2> /dev/null | head -1)
[ -n "$WID" ] || fail "no window appeared"
eval "$(xdotool getwindowgeometry --shell "$WID")"  # X Y WIDTH HEIGHT

# Queries over the frame log (python, one JSON object per line).
q() { python3 - "$WORK/gui.log" "$@" <<'PY'
import json, sys
lines = [json.loads(l) for l in open(sys.argv[1]) if l.strip()]
frames = [l for l in lines if "frame" in l]
widgets = {}
for l in lines:
    widgets.update(l.get("widgets", {}))
what = sys.argv[2]
if what == "idle":      # the first fit is on screen and nothing runs: 1, else 0
    last = frames[-1] if frames else None
    print(1 if last and last["fits"] >= 1 and not last["fit_running"] and not last["view_pending"] else 0)
elif what == "last":    # the last frame's number, fits and version
    f = frames[-1]; print(f["frame"], f["fits"], f["version"])
elif what == "widget":  # the centre of a named widget and its bottom edge
    r = widgets[sys.argv[3]]; print(round((r[0] + r[2]) / 2), round((r[1] + r[3]) / 2), round(r[3]))
elif what == "key":     # the frame that took key K after frame F: its input wait and whether view work was pending
    k, after = int(sys.argv[3]), int(sys.argv[4])
    hit = [f for f in frames if f["frame"] > after and k in f["keys"]]
    if not hit: print("none"); sys.exit(0)
    f = hit[0]; print(f["input_wait_ms"], 1 if f["view_pending"] else 0)
elif what == "toggle":  # after frame F: the left press's input wait, the ms from the press to the
    # end of the first frame whose version differs from V, and whether view work was pending then
    after, v = int(sys.argv[3]), int(sys.argv[4])
    fs = [f for f in frames if f["frame"] > after]
    press = next((f for f in fs if 0 in f["buttons"]), None)
    done = next((f for f in fs if f["version"] != v), None)
    if not press or not done: print("none"); sys.exit(0)
    t = press["time"] - press["input_wait_ms"] / 1000
    print(press["input_wait_ms"], round(1000 * (done["time"] + done["ms"] / 1000 - t), 1), 1 if done["view_pending"] else 0)
elif what == "slowest": # the slowest frame after frame F (ms) and the largest gap between frame starts
    after = int(sys.argv[3])
    fs = [f for f in frames if f["frame"] > after]
    gaps = [b["time"] - a["time"] for a, b in zip(fs, fs[1:])]
    print(max(f["ms"] for f in fs), round(1000 * max(gaps or [0]), 1))
PY
}

for _ in $(seq 600); do [ -s "$WORK/gui.log" ] && [ "$(q idle)" = 1 ] && break; sleep 0.2; done
[ "$(q idle)" = 1 ] || fail "the first fit and its settled view did not arrive within 120 s"
read -r START _ _ <<< "$(q last)"

# Idle, the window draws a frame only when something is new, and twice a second besides
# (frame pacing): far fewer than 60 a second. No input reaches it in these 2 s.
sleep 2
read -r IDLE_END _ _ <<< "$(q last)"
echo "idle: $((IDLE_END - START)) frames in 2 s"
[ $((IDLE_END - START)) -le 10 ] || fail "the idle window drew $((IDLE_END - START)) frames in 2 s (frame pacing: about 4)"

# The View section may lie below the window: scroll the left panel until the bounds box shows.
xdotool mousemove $((X + 150)) $((Y + 300)); sleep 0.2
for _ in $(seq 20); do
  read -r BX BY BB <<< "$(q widget view.bounds_box)" || fail "no view.bounds_box widget in the log"
  [ "$BB" -lt $((HEIGHT - 30)) ] && break
  xdotool click 5; sleep 0.3
done
[ "$BB" -lt $((HEIGHT - 30)) ] || fail "the bounds box checkbox stays below the window (bottom at $BB)"
sleep 0.5
read -r _ FITS VERSION <<< "$(q last)"

# Orbit in the view's empty lower-left corner (right of the 330 px panel, above the status bar):
# the settled view of the new camera is computed from here on.
OX=$((X + 330 + 40)); OY=$((Y + HEIGHT - 24 - 50))
xdotool mousemove "$OX" "$OY"; sleep 0.2
xdotool mousedown 1
for k in 1 2 3 4 5 6; do xdotool mousemove $((OX + 15 * k)) $((OY - 4 * k)); sleep 0.05; done
xdotool mouseup 1
sleep 0.3  # the settled quality starts a few frames after the release
read -r BEFORE _ VERSION <<< "$(q last)"

# A view toggle at once: the bounds box changes the document within 0.5 s and submits no fit.
xdotool mousemove $((X + BX)) $((Y + BY)) click 1
sleep 1
read -r PRESS_WAIT RESPONSE PENDING <<< "$(q toggle "$BEFORE" "$VERSION")"
[ "$PRESS_WAIT" != none ] || fail "the click on the bounds box did not change the document"
read -r _ FITS2 VERSION2 <<< "$(q last)"
echo "bounds box clicked after an orbit: press taken $PRESS_WAIT ms after it arrived, document changed $RESPONSE ms after it (view work pending: $PENDING); fits $FITS -> $FITS2"
[ "$PENDING" = 1 ] || echo "note: the settled view was done before the toggle; the check ran on an idle view"
python3 -c "import sys; sys.exit(0 if float('$RESPONSE') <= 500 else 1)" || fail "the toggle took $RESPONSE ms (limit 500)"
[ "$FITS2" = "$FITS" ] || fail "a view toggle submitted a fit"

# A key right after, while the view of the new settings is computed.
read -r BEFORE _ _ <<< "$(q last)"
xdotool mousemove "$OX" "$OY" key F1
sleep 1
read -r WAIT PENDING <<< "$(q key 290 "$BEFORE")"  # GLFW_KEY_F1 = 290
[ "$WAIT" != none ] || fail "F1 was never taken by a frame"
echo "F1 after the toggle: taken $WAIT ms after it arrived (view work pending: $PENDING)"
python3 -c "import sys; sys.exit(0 if float('$WAIT') <= 500 else 1)" || fail "F1 waited $WAIT ms (limit 500)"

# Reported, not asserted: the GUI thread uploads bakes in slabs and traces the settled view in
# bands of about 12 ms a frame (docs/performance.md), but under a build's load on 2 cores a frame
# can still take hundreds of milliseconds.
read -r SLOW GAP <<< "$(q slowest "$START")"
echo "after the first fit: slowest frame $SLOW ms, largest gap between frames $GAP ms"

xdotool key --clearmodifiers ctrl+q
for _ in $(seq 100); do kill -0 "$APID" 2> /dev/null || break; sleep 0.1; done
if kill -0 "$APID" 2> /dev/null; then fail "the program did not quit on Ctrl+Q"; fi
wait "$APID"; RC=$?
APID=""
[ "$RC" = 0 ] || fail "exit code $RC"
echo "PASS"
