#!/usr/bin/env python3
"""One point file, `hermite-lab mesh` against open3d's screened Poisson, alternated (issue 17's
"no more time than Poisson", docs/performance.md "Cheaper local factorisations").

Usage:
  /usr/bin/python3 scripts/mesh_vs_poisson.py POINTS.xyzn LAB[,LAB...] [ROUNDS]

Each round runs every LAB's plain `mesh POINTS -o /tmp/mesh_vs_poisson.ply` (the default scene
and resolution) and then create_from_point_cloud_poisson at depth 8 on the same oriented points
(x y z nx ny nz per line), and prints per run the wall clock, the user CPU time and the load
average before it. Needs numpy and open3d (Debian: python3-open3d); never a dependency of the
product or its tests.
"""
import os
import resource
import subprocess
import sys
import time

import numpy as np
import open3d as o3d


def main():
    points, labs = sys.argv[1], sys.argv[2].split(",")
    rounds = int(sys.argv[3]) if len(sys.argv) > 3 else 3
    data = np.loadtxt(points)
    pcd = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(data[:, :3]))
    pcd.normals = o3d.utility.Vector3dVector(data[:, 3:6])
    for i in range(rounds):
        for lab in labs + ["poisson"]:
            load = open("/proc/loadavg").read().split()[0]
            t0 = time.perf_counter()
            if lab == "poisson":
                u0 = resource.getrusage(resource.RUSAGE_SELF).ru_utime
                o3d.geometry.TriangleMesh.create_from_point_cloud_poisson(pcd, depth=8)
                user = resource.getrusage(resource.RUSAGE_SELF).ru_utime - u0
            else:
                c0 = os.times().children_user
                subprocess.run([lab, "mesh", points, "-o", "/tmp/mesh_vs_poisson.ply"], check=True,
                               stdout=subprocess.DEVNULL)
                user = os.times().children_user - c0
            wall = time.perf_counter() - t0
            print(f"round {i + 1} {lab}: {wall:.2f} s wall, {user:.2f} s user (load {load})", flush=True)


if __name__ == "__main__":
    main()
