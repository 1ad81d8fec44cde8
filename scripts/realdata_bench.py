#!/usr/bin/env python3
"""Real-data yardstick (issue 17, docs/performance.md "Real data"): sample closed public meshes,
reconstruct with `hermite-lab mesh` (partition-of-unity HRBF) and, when open3d is installed,
with open3d's screened Poisson at depth 8 on the same oriented points, and report per method:

  time_s      wall clock of the reconstruction (hermite-lab: the whole `mesh` command, fit
              included; Poisson: create_from_point_cloud_poisson)
  comps       edge-connected components of the output
  closed      every edge used by exactly two triangles
  chi         Euler characteristic V − E + F, with the true mesh's in brackets (duplicate vertices
              merged first)
  mean, p99   distances of 200 000 points sampled on the true surface to the reconstruction
  max_vert    largest distance of a reconstruction vertex to the true surface
  (distances relative to the true mesh's bounding-box diagonal, in %)

Usage:
  scripts/realdata_bench.py [--lab build/release/hermite-lab] [--points 200000] [--resolution 256]
                            [--chord-tolerance F] [--meshes armadillo,elephant,bunny00,fandisk] [--threads N]
                            [--seed S | --seeds S1,S2,...] [--set KEY=VALUE ...]
                            [--no-poisson] [--json OUT]
--chord-tolerance passes `mesh --chord-tolerance F` (docs/cli.md; 0 turns it off); without it the
command's default applies (0.02 cells since issue 17's timing work). --set KEY=VALUE overrides a key
of the scene the bench writes (fit.partition.max_points_per_box 20, ...), as `mesh --set` does.
Meshes are looked up in /work/cgaldata/data/meshes (CGAL's data set; Debian's libcgal-demo ships
it as data.tar.gz) unless a path is given. Needs python3 with numpy and open3d (Debian:
python3-open3d); never a dependency of the product or its tests. A method that fails gets a
"failed: why" row (and a "failed" key in the JSON); the others go on, and the script exits 1
at the end, listing the failures.
With Poisson, a tally follows the table: per criterion (time, mean, p99, worst vertex, compared to
the printed digits) on how many (mesh, seed) pairs ours is no larger, naming the pairs where it is;
--seeds samples every mesh once per seed, so one run measures how often that holds.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import time

import numpy as np

try:
    import open3d as o3d
except ImportError:  # the whole yardstick measures distances with open3d
    sys.exit("realdata_bench.py needs open3d (Debian: python3-open3d)")

MESH_DIR = "/work/cgaldata/data/meshes"


def load_truth(name):
    path = name if os.path.exists(name) else os.path.join(MESH_DIR, name + ".off")
    mesh = o3d.io.read_triangle_mesh(path)
    mesh.remove_duplicated_vertices()
    # Triangles on repeated vertices (the Stanford dragon's vrip mesh has 108 once duplicates are
    # merged): without them the mesh is closed, and its Euler characteristic is the surface's.
    mesh.remove_degenerate_triangles()
    mesh.remove_unreferenced_vertices()
    mesh.compute_triangle_normals()
    if len(mesh.triangles) == 0:
        sys.exit(f"{path}: no triangles")
    return path, mesh


def sample_oriented(mesh, n, seed):
    """n points uniformly by area with the triangles' normals (outward for a closed oriented mesh)."""
    o3d.utility.random.seed(seed)
    pcd = mesh.sample_points_uniformly(number_of_points=n, use_triangle_normal=True)
    return pcd


def topology(mesh):
    """components, closed, Euler characteristic (V − E + F after merging duplicate vertices)."""
    _, counts, _ = mesh.cluster_connected_triangles()
    closed = mesh.is_edge_manifold(allow_boundary_edges=False) and len(mesh.triangles) > 0
    merged = o3d.geometry.TriangleMesh(mesh)
    merged.remove_duplicated_vertices()
    return len(counts), bool(closed), int(merged.euler_poincare_characteristic())


def with_area(mesh):
    """The mesh's triangles of nonzero area, as a tensor mesh for a RaycastingScene: open3d's
    distance query aborts the interpreter on a zero-area triangle (an Eigen assertion; screened
    Poisson's mesh of CGAL's man has 4). Such a triangle adds no point to the surface."""
    v = np.asarray(mesh.vertices)
    t = np.asarray(mesh.triangles)
    area = np.linalg.norm(np.cross(v[t[:, 1]] - v[t[:, 0]], v[t[:, 2]] - v[t[:, 0]]), axis=1)
    kept = o3d.geometry.TriangleMesh(mesh.vertices, o3d.utility.Vector3iVector(t[area > 0]))
    return o3d.t.geometry.TriangleMesh.from_legacy(kept)


def distances(truth, recon, diagonal, seed):
    """mean and 99th percentile of truth samples → recon, max of recon vertices → truth (% of diagonal)."""
    if len(recon.triangles) == 0:
        return float("inf"), float("inf"), float("inf")
    truth_scene = o3d.t.geometry.RaycastingScene()
    truth_scene.add_triangles(with_area(truth))
    recon_scene = o3d.t.geometry.RaycastingScene()
    recon_scene.add_triangles(with_area(recon))
    o3d.utility.random.seed(seed + 1)
    probe = np.asarray(truth.sample_points_uniformly(number_of_points=200000).points, dtype=np.float32)
    d_in = recon_scene.compute_distance(o3d.core.Tensor(probe)).numpy()
    verts = np.asarray(recon.vertices, dtype=np.float32)
    d_out = truth_scene.compute_distance(o3d.core.Tensor(verts)).numpy()
    scale = 100.0 / diagonal
    return float(d_in.mean() * scale), float(np.percentile(d_in, 99) * scale), float(d_out.max() * scale)


class MethodFailed(Exception):
    """A reconstruction that did not finish: its row says why, and the bench goes on."""


def run_lab(lab, pcd, resolution, threads, workdir, chord_tolerance=None, settings=()):
    pts = np.hstack([np.asarray(pcd.points), np.asarray(pcd.normals)])
    data = os.path.join(workdir, "points.xyzn")
    np.savetxt(data, pts, fmt="%.9g")
    scene = {
        "version": 1,
        "mode": "implicit3d",
        "data": {"file": "points.xyzn"},
        "fit": {"method": "hrbf", "kernel": "cubic", "polynomial": "linear",
                "partition": {"enabled": True, "max_points_per_box": 20, "overlap": 1.5}},
    }
    scene_path = os.path.join(workdir, "scene.json")
    with open(scene_path, "w") as f:
        json.dump(scene, f)
    out = os.path.join(workdir, "lab.ply")
    cmd = [lab, "mesh", scene_path, "-o", out, "--resolution", str(resolution)]
    if threads:
        cmd += ["--threads", str(threads)]
    if chord_tolerance is not None:
        cmd += ["--chord-tolerance", str(chord_tolerance)]
    for setting in settings:
        cmd += ["--set", setting]
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, capture_output=True, text=True)
    elapsed = time.perf_counter() - t0
    if proc.returncode != 0:
        raise MethodFailed(f"{' '.join(cmd)} failed ({proc.returncode}): {proc.stderr.strip()}")
    line = proc.stdout.strip().splitlines()[-1] if proc.stdout.strip() else ""
    mesh_ms = re.search(r"; ([0-9.]+) ms \(field ([0-9.]+) ms\)", line)
    recon = o3d.io.read_triangle_mesh(out)
    recon.remove_duplicated_vertices()
    extra = {"summary": line}
    if mesh_ms:
        extra["mesh_s"] = float(mesh_ms.group(1)) / 1000
        extra["field_s"] = float(mesh_ms.group(2)) / 1000
    return recon, elapsed, extra


def run_poisson(pcd, depth):
    t0 = time.perf_counter()
    recon, _ = o3d.geometry.TriangleMesh.create_from_point_cloud_poisson(pcd, depth=depth)
    elapsed = time.perf_counter() - t0
    return recon, elapsed, {}


def bench_mesh(name, seed, args, rows, failures):
    """Rows (appended to `rows`) for one mesh sampled with `seed`: ours, then Poisson."""
    path, truth = load_truth(name)
    lo, hi = truth.get_min_bound(), truth.get_max_bound()
    diagonal = float(np.linalg.norm(hi - lo))
    pcd = sample_oriented(truth, args.points, seed)
    truth_euler = topology(truth)[2]
    with tempfile.TemporaryDirectory() as work:
        methods = [("hermite-lab PU", lambda: run_lab(args.lab, pcd, args.resolution, args.threads, work,
                                                            args.chord_tolerance, args.set))]
        if not args.no_poisson:
            methods.append(("poisson depth 8", lambda: run_poisson(pcd, 8)))
        for label, run in methods:
            try:
                recon, elapsed, extra = run()
            except MethodFailed as e:
                failures.append(f"{os.path.basename(path)}, seed {seed}, {label}: {e}")
                rows.append({"mesh": os.path.basename(path), "points": args.points, "seed": seed, "method": label,
                             "failed": str(e)})
                print(f"| {os.path.basename(path)} | {args.points} | {seed} | {label} | failed: {e} |", flush=True)
                continue
            comps, closed, euler = topology(recon)
            mean, p99, worst = distances(truth, recon, diagonal, seed)
            ours = label.startswith("hermite")
            row = {"mesh": os.path.basename(path), "points": args.points, "seed": seed, "method": label,
                   "resolution": args.resolution if ours else None,
                   "chord_tolerance": (args.chord_tolerance if args.chord_tolerance is not None else "default")
                   if ours else None,
                   "settings": args.set if ours else None,
                   "time_s": elapsed, "components": comps, "closed": closed,
                   "euler": euler, "truth_euler": truth_euler,
                   "mean_pct": mean, "p99_pct": p99, "max_vertex_pct": worst, **extra}
            rows.append(row)
            print(f"| {row['mesh']} | {args.points} | {seed} | {label} | {elapsed:.1f} | {comps} | "
                  f"{'yes' if closed else 'no'} | {euler} ({truth_euler}) | {mean:.3f} | {p99:.3f} | {worst:.3f} |",
                  flush=True)


# What "no worse than Poisson" compares, per (mesh, seed): smaller is better, to the printed digits.
TALLY = [("time_s", "time", 1), ("mean_pct", "mean", 3), ("p99_pct", "p99", 3), ("max_vertex_pct", "max vertex", 3)]


def tally(rows):
    """Per criterion, on how many (mesh, seed) pairs ours is no worse than Poisson, with the losses."""
    pairs = {}
    for r in rows:
        if "failed" not in r:
            pairs.setdefault((r["mesh"], r["seed"]), {})["ours" if r["method"].startswith("hermite") else "poisson"] = r
    pairs = {k: v for k, v in pairs.items() if len(v) == 2}
    if not pairs:
        return
    print(f"\nours against Poisson over {len(pairs)} (mesh, seed) pairs:")
    closed = [k for k, v in pairs.items() if not (v["ours"]["closed"] and v["ours"]["components"] == 1)]
    print(f"  ours one closed piece: {len(pairs) - len(closed)} of {len(pairs)}" +
          (f"; not: {', '.join(f'{m} seed {s}' for m, s in closed)}" if closed else ""))
    for key, label, digits in TALLY:
        lost = [(k, v) for k, v in pairs.items() if round(v["ours"][key], digits) > round(v["poisson"][key], digits)]
        line = f"  {label} no larger: {len(pairs) - len(lost)} of {len(pairs)}"
        if lost:
            line += "; larger: " + ", ".join(
                f"{m} seed {s} ({v['ours'][key]:.{digits}f} / {v['poisson'][key]:.{digits}f})" for (m, s), v in lost)
        print(line)


def seed_list(text):
    """--seeds: comma-separated integers."""
    try:
        return [int(s) for s in text.split(",")]
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a comma-separated list of integers")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--lab", default="build/release/hermite-lab")
    ap.add_argument("--points", type=int, default=200000)
    ap.add_argument("--resolution", type=int, default=256)
    ap.add_argument("--meshes", default="armadillo,elephant,bunny00,fandisk")
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--chord-tolerance", type=float, default=None)
    ap.add_argument("--seed", type=int, default=17)
    ap.add_argument("--seeds", type=seed_list, metavar="S1,S2,...",
                    help="sampling seeds, each mesh sampled once per seed (replaces --seed)")
    ap.add_argument("--no-poisson", action="store_true")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="passed to `mesh --set` (repeatable), e.g. fit.partition.max_points_per_box=30")
    ap.add_argument("--json", help="also write the rows as JSON here")
    args = ap.parse_args()
    seeds = args.seeds or [args.seed]

    rows, failures = [], []
    print("| mesh | N | seed | method | time s | comps | closed | χ (truth) | mean % | p99 % | max vert % |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for name in args.meshes.split(","):
        for seed in seeds:
            bench_mesh(name, seed, args, rows, failures)
    tally(rows)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=1)
    if failures:
        sys.exit("failed:\n  " + "\n  ".join(failures))

if __name__ == "__main__":
    main()
