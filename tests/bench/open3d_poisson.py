#!/usr/bin/python3
"""The peer a user would pick: Open3D screened Poisson reconstruction of a point cloud file.

Positions only, like the membrane: normals are estimated (KNN 30) and oriented consistently
(orient_normals_consistent_tangent_plane(k=30)), as Open3D's users must before Poisson, then
TriangleMesh.create_from_point_cloud_poisson(depth=9). Reading the file is not timed.

Prints one JSON line:
  {"file", "points", "threads", "normals_seconds", "orient_seconds", "poisson_seconds",
   "seconds" (= normals + orient + poisson, wall), "vertices", "faces"}
Exit status 2 when open3d cannot be imported (message on stderr), 1 on other errors.

--write-mesh PATH saves the (unclipped) Poisson mesh as binary PLY for accuracy measurements
(bench_surface); the JSON line is unchanged.

Run with Debian's interpreter, which has python3-open3d: /usr/bin/python3 open3d_poisson.py F.ply
"""
import argparse
import json
import sys
import time


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cloud", help="point cloud file (.ply, .xyz, .pcd)")
    parser.add_argument("--depth", type=int, default=9, help="Poisson octree depth (9)")
    parser.add_argument("--knn", type=int, default=30, help="neighbours for normals (30)")
    parser.add_argument("--orient-k", type=int, default=30,
                        help="neighbours of the consistent-tangent-plane graph (30)")
    parser.add_argument("--threads", type=int, default=-1,
                        help="Poisson threads (-1 = all; normals follow OMP_NUM_THREADS)")
    parser.add_argument("--write", help="write the mesh here (not timed)")
    parser.add_argument("--write-mesh", metavar="PATH",
                        help="save Poisson's mesh as PLY at PATH (not timed; like --write)")
    args = parser.parse_args()

    try:
        import open3d as o3d
    except ImportError as e:  # pragma: no cover - environment dependent
        print(f"open3d not available: {e}", file=sys.stderr)
        return 2
    o3d.utility.set_verbosity_level(o3d.utility.VerbosityLevel.Error)

    pcd = o3d.io.read_point_cloud(args.cloud)
    points = len(pcd.points)
    if points == 0:
        print(f"{args.cloud}: no points read", file=sys.stderr)
        return 1
    pcd.normals = o3d.utility.Vector3dVector()  # positions only, like the membrane

    t0 = time.perf_counter()
    pcd.estimate_normals(search_param=o3d.geometry.KDTreeSearchParamKNN(knn=args.knn))
    t1 = time.perf_counter()
    pcd.orient_normals_consistent_tangent_plane(args.orient_k)
    t2 = time.perf_counter()
    mesh, _densities = o3d.geometry.TriangleMesh.create_from_point_cloud_poisson(
        pcd, depth=args.depth, n_threads=args.threads)
    t3 = time.perf_counter()

    if args.write:
        o3d.io.write_triangle_mesh(args.write, mesh)
    if args.write_mesh:
        # Binary PLY, positions and triangles only (no normals or colours): what ReadMesh needs.
        mesh.vertex_normals = o3d.utility.Vector3dVector()
        mesh.vertex_colors = o3d.utility.Vector3dVector()
        if not o3d.io.write_triangle_mesh(args.write_mesh, mesh, write_ascii=False):
            print(f"{args.write_mesh}: could not write the mesh", file=sys.stderr)
            return 1
    print(json.dumps({
        "file": args.cloud,
        "points": points,
        "threads": args.threads,
        "normals_seconds": round(t1 - t0, 4),
        "orient_seconds": round(t2 - t1, 4),
        "poisson_seconds": round(t3 - t2, 4),
        "seconds": round(t3 - t0, 4),
        "vertices": len(mesh.vertices),
        "faces": len(mesh.triangles),
    }))
    return 0


if __name__ == "__main__":
    sys.exit(main())
