#!/usr/bin/python3
"""How far a reconstruction stays from the reference's sharp edges (issue 17: "sharp edges must
stay sharp where the data shows them").

The reference's feature edges are its edges whose faces meet at a dihedral angle of --angle
degrees or more (fandisk's creases and corners). Points are taken along them every --step
voxels, and each mesh's distance to them (exact point-to-triangle distance, the eval tools'
SurfaceDistance) is given in voxels: mean, median, 90th percentile and max, and the share of
edge points farther than 1 voxel. A rounded crease of radius r leaves its edge r(sqrt(2) - 1)
away at a right angle, so these figures read as how much each mesh rounds the creases. Only
edge points with input points within --near voxels count (the data shows the edge there:
an edge in a hole or an unscanned part is not the data's).

  /usr/bin/python3 tests/bench/sharp_edges.py --gt ../shared/data/models/fandisk.obj \
      --points CLOUD.ply --voxel L MESH.ply [MESH.ply ...]

Run it with Debian's interpreter (python3-numpy, python3-scipy, python3-open3d).
"""
import argparse
import os
import sys

import numpy as np
from scipy.spatial import cKDTree

HERE = os.path.dirname(os.path.abspath(__file__))
EVAL = os.path.normpath(os.path.join(HERE, '..', '..', '..', 'shared', 'tools', 'eval'))
sys.path.insert(0, EVAL)
import meshlib  # noqa: E402  (the eval tools' loader and distances)


def feature_edges(V, F, angle_deg):
    """Edges (pairs of vertex indices) shared by two faces whose normals differ by angle_deg or
    more. Positions are merged first, so that a mesh split along its creases counts them."""
    _, inverse = np.unique(np.round(V, 9), axis=0, return_inverse=True)
    inverse = inverse.reshape(-1)
    P = _merged_positions(V, inverse)
    F = inverse[F]
    F = F[(F[:, 0] != F[:, 1]) & (F[:, 1] != F[:, 2]) & (F[:, 0] != F[:, 2])]
    N, area = meshlib.face_normals_areas(P, F)
    F, N = F[area > 0], N[area > 0]  # a degenerate face has no normal to compare
    edges = np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]])
    faces = np.tile(np.arange(len(F)), 3)
    key = np.sort(edges, axis=1)
    order = np.lexsort((key[:, 1], key[:, 0]))
    key, faces = key[order], faces[order]
    same = np.all(key[1:] == key[:-1], axis=1)
    i = np.nonzero(same)[0]
    cos = np.einsum('ij,ij->i', N[faces[i]], N[faces[i + 1]])
    sharp = cos <= np.cos(np.radians(angle_deg))
    return P, key[i[sharp]]


def _merged_positions(V, inverse):
    P = np.zeros((inverse.max() + 1, 3))
    P[inverse] = V
    return P


def edge_points(P, edges, step):
    pts = []
    for a, b in edges:
        length = np.linalg.norm(P[b] - P[a])
        k = max(int(np.ceil(length / step)), 1)
        t = (np.arange(k) + 0.5) / k
        pts.append(P[a] + t[:, None] * (P[b] - P[a]))
    return np.concatenate(pts) if pts else np.zeros((0, 3))


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('meshes', nargs='+')
    ap.add_argument('--gt', required=True)
    ap.add_argument('--points', required=True, help='the input cloud (PLY)')
    ap.add_argument('--voxel', type=float, required=True, help='voxel size L (model units)')
    ap.add_argument('--angle', type=float, default=30.0)
    ap.add_argument('--step', type=float, default=0.25, help='voxels between edge points')
    ap.add_argument('--near', type=float, default=1.0,
                    help='an edge point counts when an input point lies within this many voxels')
    args = ap.parse_args()

    V, F, _ = meshlib.load_mesh(args.gt)
    P, edges = feature_edges(np.asarray(V, np.float64), np.asarray(F), args.angle)
    E = edge_points(P, edges, args.step * args.voxel)
    cloud, _ = meshlib.read_points(args.points)
    d_data, _ = cKDTree(cloud).query(E)
    seen = d_data <= args.near * args.voxel
    print('%s: %d feature edges (>= %.0f deg), %d edge points, %d with data within %.1f voxels'
          % (os.path.basename(args.gt), len(edges), args.angle, len(E), int(seen.sum()),
             args.near))
    print('%-50s %8s %8s %8s %8s %8s' % ('mesh (voxels from the edges)', 'mean', 'median',
                                         'p90', 'max', '>1 vox'))
    for path in args.meshes:
        mv, mf, _ = meshlib.load_mesh(path)
        d, _ = meshlib.SurfaceDistance(np.asarray(mv, np.float64), np.asarray(mf)).query(E[seen])
        d = d / args.voxel
        print('%-50s %8.3f %8.3f %8.3f %8.3f %7.1f%%' % (
            os.path.basename(path), d.mean(), np.median(d), np.percentile(d, 90), d.max(),
            100.0 * np.mean(d > 1.0)))


if __name__ == '__main__':
    main()
