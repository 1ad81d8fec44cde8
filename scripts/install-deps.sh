#!/bin/sh
# Installs the Debian 12 packages Hermite Lab needs to build, test and run.
# Idempotent: when every package is already installed it only runs dpkg-query and exits.
# Must run as root (or with sudo available) when something is missing.
set -eu

PACKAGES="
  build-essential cmake ninja-build pkg-config python3
  libeigen3-dev libopenblas-dev libopenblas-pthread-dev liblapacke-dev
  nlohmann-json3-dev libcli11-dev doctest-dev libnanoflann-dev libstb-dev
  libglfw3-dev libimgui-dev libglm-dev libosmesa6-dev libegl-dev libgl-dev python3-glad
  libegl-mesa0 libgl1-mesa-dri fonts-dejavu-core
  libtinygltf-dev libtinyobjloader-dev
  xvfb xauth xdotool imagemagick
  clang libclang-rt-14-dev
"

missing=""
for p in $PACKAGES; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  case "$status" in
    *"install ok installed"*) ;;
    *) missing="$missing $p" ;;
  esac
done

if [ -z "$missing" ]; then
  exit 0
fi

echo "install-deps: installing missing Debian packages:$missing"
SUDO=""
if [ "$(id -u)" != "0" ]; then
  if command -v sudo >/dev/null 2>&1; then SUDO="sudo"; else
    echo "install-deps: need root to install:$missing" >&2; exit 1
  fi
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
# shellcheck disable=SC2086
$SUDO apt-get install -y -qq --no-install-recommends $missing
