#!/bin/bash
# A click during a slow frame lands where it happened (issue 18), in the real 3D window under
# Xvfb + xdotool: every frame is made to take 300 ms (HERMITE_GUI_FRAME_DELAY_MS, docs/cli.md),
# and within one such frame the mouse moves onto sample A, clicks, and moves on to sample B. The
# click must select A (its own position), not B (the cursor's position when the frame reads
# the input), and must not be lost. Sample positions come from the frame log's "view.sample.K"
# rectangles. Exit 77 = skipped (no Xvfb / xdotool) unless HERMITE_REQUIRE_XVFB=1.
#   usage: xvfb_click.sh HERMITE_LAB_EXE
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
start_xvfb 301 370

cat > "$WORK/scene.json" <<'JSON'
{"version": 1, "mode": "implicit3d", "data": {"preset": "sphere", "count": 12},
 "view": {"show_points": true, "show_normals": false}}
JSON

# Queries over the frame log: "pair" (two samples A, B at least 80 px apart and 25 px from every
# other mark: "AX AY BX BY A B" in window pixels), "last" (the last frame's number and selection).
q() { python3 - "$WORK/gui.log" "$@" <<'PY'
import itertools, json, math, sys
lines = [json.loads(l) for l in open(sys.argv[1]) if l.strip()]
frames = [l for l in lines if "frame" in l]
widgets = {}
for l in lines:
    widgets.update(l.get("widgets", {}))
what = sys.argv[2]
if what == "pair":
    view_x = 340  # right of the 330 px left panel
    marks = {int(k.split(".")[-1]): ((r[0] + r[2]) / 2, (r[1] + r[3]) / 2)
             for k, r in widgets.items() if k.startswith("view.sample.")}
    marks = {k: p for k, p in marks.items() if p[0] > view_x and 40 < p[1] < 700}
    def apart(k):
        return all(math.dist(marks[k], marks[o]) >= 25 for o in marks if o != k)
    for a, b in itertools.combinations(sorted(marks), 2):
        if apart(a) and apart(b) and math.dist(marks[a], marks[b]) >= 80:
            (ax, ay), (bx, by) = marks[a], marks[b]
            print(round(ax), round(ay), round(bx), round(by), a, b); break
    else:
        print("none")
elif what == "last":
    f = frames[-1] if frames else {"frame": 0, "selected": -1}
    print(f["frame"], f["selected"])
PY
}

HERMITE_GUI_FRAME_DELAY_MS=300 HERMITE_GUI_LOG="$WORK/gui.log" "$EXE" "$WORK/scene.json" > "$WORK/app.log" 2>&1 &
APID=$!
WID=$(timeout 60 xdotool search --sync --name "Hermite Lab" 2> /dev/null | head -1)
[ -n "$WID" ] || fail "no window appeared"
eval "$(xdotool getwindowgeometry --shell "$WID")"  # X Y WIDTH HEIGHT
PAIR=none
for _ in $(seq 300); do
  [ -s "$WORK/gui.log" ] && PAIR=$(q pair) && [ "$PAIR" != none ] && break
  sleep 0.2
done
[ "$PAIR" != none ] || fail "no two samples far enough apart on screen within 60 s"
read -r AX AY BX BY A B <<< "$PAIR"
read -r _ SEL <<< "$(q last)"
[ "$SEL" = -1 ] || fail "sample $SEL is selected before the click"

# Onto A, click, on to B: one command, well within one 300 ms frame.
xdotool mousemove $((X + AX)) $((Y + AY)) click 1 mousemove $((X + BX)) $((Y + BY))
sleep 2  # a few frames: the events recorded in one frame may be replayed over the next ones
read -r _ SEL <<< "$(q last)"
echo "clicked sample $A at ($AX, $AY), then moved to sample $B at ($BX, $BY) within one slow frame: selected $SEL"
[ "$SEL" != -1 ] || fail "the click was lost (nothing selected)"
[ "$SEL" = "$A" ] || fail "the click selected sample $SEL, not sample $A under the click"

xdotool key --clearmodifiers ctrl+q
for _ in $(seq 100); do kill -0 "$APID" 2> /dev/null || break; sleep 0.1; done
if kill -0 "$APID" 2> /dev/null; then fail "the program did not quit on Ctrl+Q"; fi
wait "$APID"; RC=$?
APID=""
[ "$RC" = 0 ] || fail "exit code $RC"
echo "PASS"
