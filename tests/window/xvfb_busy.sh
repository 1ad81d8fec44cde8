#!/bin/bash
# The real window stays responsive while work runs (issue 18), under Xvfb + xdotool:
#   - a key pressed right after an orbit, while the settled view (128³ bake, exact refinement)
#     is computed on the view's worker, is taken by a frame within 0.5 s;
#   - the slowest frame and the largest gap between frames are reported;
#   - toggling a view setting (the bounds box) changes the document but submits no fit;
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

# Orbit in the view's empty lower-left corner (right of the 330 px panel, above the status bar),
# then F1 (the help window, a view toggle) at once: the settled view of the new camera is now computed.
OX=$((X + 330 + 40)); OY=$((Y + HEIGHT - 24 - 50))
xdotool mousemove "$OX" "$OY"; sleep 0.2
xdotool mousedown 1
for k in 1 2 3 4 5 6; do xdotool mousemove $((OX + 15 * k)) $((OY - 4 * k)); sleep 0.05; done
xdotool mouseup 1
sleep 0.3  # the settled quality starts a few frames after the release
read -r BEFORE _ _ <<< "$(q last)"
xdotool key F1
sleep 1
read -r WAIT PENDING <<< "$(q key 290 "$BEFORE")"  # GLFW_KEY_F1 = 290
[ "$WAIT" != none ] || fail "F1 was never taken by a frame"
echo "F1 after an orbit: taken $WAIT ms after it arrived (view work pending: $PENDING)"
[ "$PENDING" = 1 ] || echo "note: the settled view was done before F1 arrived; the check ran on an idle view"
python3 -c "import sys; sys.exit(0 if float('$WAIT') <= 500 else 1)" || fail "F1 waited $WAIT ms (limit 500)"

# A view toggle: the bounds box changes the document and submits no fit.
for _ in $(seq 600); do [ "$(q idle)" = 1 ] && break; sleep 0.2; done
read -r _ FITS VERSION <<< "$(q last)"
# The View section may lie below the window: scroll the left panel until the checkbox shows.
xdotool mousemove $((X + 150)) $((Y + 300)); sleep 0.2
for _ in $(seq 20); do
  read -r BX BY BB <<< "$(q widget view.bounds_box)" || fail "no view.bounds_box widget in the log"
  [ "$BB" -lt $((HEIGHT - 30)) ] && break
  xdotool click 5; sleep 0.3
done
[ "$BB" -lt $((HEIGHT - 30)) ] || fail "the bounds box checkbox stays below the window (bottom at $BB)"
xdotool mousemove $((X + BX)) $((Y + BY)); sleep 0.2
xdotool click 1; sleep 1.5
read -r _ FITS2 VERSION2 <<< "$(q last)"
echo "bounds box toggled: version $VERSION -> $VERSION2, fits $FITS -> $FITS2"
[ "$VERSION2" != "$VERSION" ] || fail "the click on the bounds box did not change the document"
[ "$FITS2" = "$FITS" ] || fail "a view toggle submitted a fit"

# Reported, not yet asserted: the GUI thread still uploads each bake whole and traces the settled
# view in bands of about 12 ms a frame (docs/performance.md), so under a build's load a frame can
# take hundreds of milliseconds and a key arriving then waits that long.
read -r SLOW GAP <<< "$(q slowest "$START")"
echo "after the first fit: slowest frame $SLOW ms, largest gap between frames $GAP ms"

xdotool key --clearmodifiers ctrl+q
for _ in $(seq 100); do kill -0 "$APID" 2> /dev/null || break; sleep 0.1; done
if kill -0 "$APID" 2> /dev/null; then fail "the program did not quit on Ctrl+Q"; fi
wait "$APID"; RC=$?
APID=""
[ "$RC" = 0 ] || fail "exit code $RC"
echo "PASS"
