# Shared by the Xvfb window tests (sourced, not run): the tool check and a private Xvfb display.
# The sourcing script defines WORK (a scratch folder), XPID (empty) and fail MESSAGE before
# calling these.

# Exits 77 (skipped) when one of the tools is missing, unless HERMITE_REQUIRE_XVFB=1 (CI), where
# a missing tool is a failure.
require_tools() {
  local tool
  for tool in "$@"; do
    if ! command -v "$tool" > /dev/null; then
      if [ "${HERMITE_REQUIRE_XVFB:-0}" = 1 ]; then fail "$tool is not installed (HERMITE_REQUIRE_XVFB=1)"; fi
      echo "SKIP: $tool is not installed (scripts/install-deps.sh installs it)"
      exit 77
    fi
  done
}

# Starts Xvfb (1400×900) on the first free display number in FIRST…LAST, sets XPID and DISPLAY,
# and waits up to 10 s for its socket. Each test uses its own range so that they can run at once.
start_xvfb() {
  local first=$1 last=$2 n D=""
  for n in $(seq "$first" "$last"); do
    if [ ! -e "/tmp/.X11-unix/X$n" ] && [ ! -e "/tmp/.X$n-lock" ]; then D=$n; break; fi
  done
  [ -n "$D" ] || fail "no free X display number"
  Xvfb ":$D" -screen 0 1400x900x24 -nolisten tcp > "$WORK/xvfb.log" 2>&1 &
  XPID=$!
  for _ in $(seq 100); do [ -e "/tmp/.X11-unix/X$D" ] && break; sleep 0.1; done
  [ -e "/tmp/.X11-unix/X$D" ] || fail "Xvfb did not start: $(cat "$WORK/xvfb.log")"
  export DISPLAY=":$D"
}
