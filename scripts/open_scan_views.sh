#!/bin/sh
# Renders CGAL's open scans from their open sides (docs/performance.md, "On a real GPU"): the views
# that show the tracer passing zeros without data (docs/maths.md, "No data"), to compare one GL
# driver with another.
#
#   scripts/open_scan_views.sh LAB BACKEND POINTS_DIR OUTDIR
#
# LAB is the hermite-lab binary, BACKEND osmesa or egl, POINTS_DIR CGAL's data/points_3 (Debian's
# libcgal-demo ships it in data.tar.gz). Six 1280x800 PNGs go to OUTDIR.
set -eu
if [ $# -ne 4 ]; then
  echo "usage: $0 LAB BACKEND POINTS_DIR OUTDIR" >&2
  exit 2
fi
L=$1 B=$2 P=$3 O=$4
mkdir -p "$O"
view() {  # view FILE OUT [camera JSON]
  if [ $# -eq 3 ]; then
    "$L" render "$P/$1" --backend "$B" --size 1280x800 -o "$O/$2" --set "view.camera=$3"
  else
    "$L" render "$P/$1" --backend "$B" --size 1280x800 -o "$O/$2"
  fi
}
view half.xyz half_in.png '{"eye":[0.4,0.3,2.2],"target":[0,0,-0.1],"up":[0,1,0],"fov_y_deg":40}'
view half.xyz half_out.png
view fin90_with_PCA_normals.xyz fin90.png
view fin90_with_PCA_normals.xyz fin90_back.png \
  '{"eye":[-1.6,-1.4,-1.2],"target":[0.15,0.37,0.23],"up":[0,0,1],"fov_y_deg":40}'
view oni.pwn oni_below.png '{"eye":[0.3,-2.4,0.4],"target":[0,0,0.1],"up":[0,0,1],"fov_y_deg":40}'
view oni.pwn oni.png
