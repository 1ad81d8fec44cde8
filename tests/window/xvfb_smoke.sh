#!/bin/bash
# End-to-end smoke test of the real window: Xvfb + the GLFW window + xdotool.
# Opens a 2D scene, drags a sample with the mouse, saves with Ctrl+S, quits with Ctrl+Q, and
# checks the saved scene (the sample moved to where the mouse went) and the screenshots taken
# with ImageMagick's `import` (the view changed). Exit 77 = skipped (no Xvfb / xdotool / import)
# unless HERMITE_REQUIRE_XVFB=1, which CI sets so that a skip there is a failure.
#   usage: xvfb_smoke.sh HERMITE_LAB_EXE
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
fail() { echo "FAIL: $*"; [ -f "$WORK/app.log" ] && sed 's/^/  app: /' "$WORK/app.log"; exit 1; }

source "$(dirname "$0")/xvfb_common.sh"
require_tools Xvfb xdotool import compare python3
start_xvfb 91 160

# Eight samples on the unit circle; the view shows [-1.5, 1.5] vertically around the origin.
python3 - "$WORK/scene.json" <<'PY'
import json, math, sys
pts = [[math.cos(2 * math.pi * k / 8), math.sin(2 * math.pi * k / 8)] for k in range(8)]
json.dump({"version": 1, "mode": "implicit2d", "data": {"points": pts, "normals": pts},
           "fit": {"kernel": "cubic", "polynomial": "linear"},
           "view": {"view2d": {"center": [0, 0], "half_height": 1.5}}}, open(sys.argv[1], "w"))
PY

"$EXE" "$WORK/scene.json" --ui-scale 1 > "$WORK/app.log" 2>&1 &
APID=$!
WID=$(timeout 60 xdotool search --sync --name "Hermite Lab" 2> /dev/null | head -1)
[ -n "$WID" ] || fail "no window appeared"
sleep 2  # first fit and frames
eval "$(xdotool getwindowgeometry --shell "$WID")"  # X Y WIDTH HEIGHT
import -window root "$WORK/before.png" || fail "import failed"

# The fixed layout at UI scale 1: the view is right of the 330 px panel, above the 40 px status bar.
read -r PX PY TX TY S <<< "$(python3 -c "
x, y, w, h = $X, $Y, $WIDTH, $HEIGHT
vx, vw, vh = 330, w - 330, h - 40
s = 3.0 / vh                       # world units per pixel
def px(wx, wy): return x + vx + vw / 2 + wx / s, y + vh / 2 - wy / s
a = px(1.0, 0.0); b = px(1.3, 0.25)
print(round(a[0]), round(a[1]), round(b[0]), round(b[1]), s)")"

xdotool mousemove "$PX" "$PY"; sleep 0.3
xdotool click 1; sleep 0.3          # a click selects the sample; a drag on the selection moves it
xdotool mousedown 1; sleep 0.2
for k in 1 2 3 4 5 6; do
  xdotool mousemove $((PX + (TX - PX) * k / 6)) $((PY + (TY - PY) * k / 6)); sleep 0.1
done
xdotool mouseup 1
sleep 1.5
import -window root "$WORK/after.png" || fail "import failed"
xdotool windowfocus "$WID" 2> /dev/null
xdotool key --clearmodifiers ctrl+s; sleep 1
xdotool key --clearmodifiers ctrl+q
for _ in $(seq 100); do kill -0 "$APID" 2> /dev/null || break; sleep 0.1; done
if kill -0 "$APID" 2> /dev/null; then fail "the program did not quit on Ctrl+Q"; fi
wait "$APID"; RC=$?
APID=""
[ "$RC" = 0 ] || fail "exit code $RC"

python3 - "$WORK/scene.json" "$TX" "$TY" "$X" "$Y" "$WIDTH" "$HEIGHT" <<'PY' || fail "saved scene check"
import json, sys
scene = json.load(open(sys.argv[1]))
tx, ty, x, y, w, h = map(float, sys.argv[2:])
vx, vw, vh = 330, w - 330, h - 40
s = 3.0 / vh
want = ((tx - x - vx - vw / 2) * s, (y + vh / 2 - ty) * s)
got = scene["data"]["points"][0]
err = ((got[0] - want[0]) ** 2 + (got[1] - want[1]) ** 2) ** 0.5
print(f"sample 0 saved at {got}, mouse released at {want}, distance {err:.3g} (pixel {s:.3g})")
sys.exit(0 if err <= 1.5 * s else 1)
PY
CHANGED=$(compare -metric AE "$WORK/before.png" "$WORK/after.png" null: 2>&1 | cut -d' ' -f1)
echo "pixels changed by the drag: $CHANGED"
python3 -c "import sys; sys.exit(0 if float('$CHANGED') > 500 else 1)" || fail "the view did not change"
echo "PASS"
