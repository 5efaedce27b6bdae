#!/usr/bin/python3
"""Moves mesh B along a straight path past mesh A and prints where they first touch.

Loads two meshes with antcd.load_mesh, builds their Models once, then walks B's pose from
`start` to `end` (spinning about z as it goes) in `steps` poses, asking antcd.collide at each.
At the first colliding step it bisects between the last free pose and that one to find the
moment of first contact to within --tolerance of the path, and prints the contact.

Usage: examples/python/first_contact.py [MESH_A] [MESH_B] [--steps 200] [--tolerance 1e-6]
Defaults: two meshes of Debian's assimp-testmodels.
"""
import argparse

import numpy as np

import antcd

MODELS = "/usr/share/assimp/models"


def pose_at(s, start, end, spin):
    """Pose of B at path parameter s in [0, 1]: translation on the segment, rotation about z."""
    angle = spin * s
    c, n = np.cos(angle), np.sin(angle)
    m = np.eye(4)
    m[:3, :3] = [[c, -n, 0], [n, c, 0], [0, 0, 1]]
    m[:3, 3] = (1 - s) * start + s * end
    return m


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("mesh_a", nargs="?", default=f"{MODELS}/PLY/Wuson.ply")
    parser.add_argument("mesh_b", nargs="?", default=f"{MODELS}/OFF/Wuson.off")
    parser.add_argument("--steps", type=int, default=200)
    parser.add_argument("--spin", type=float, default=np.pi, help="radians turned over the path")
    parser.add_argument("--tolerance", type=float, default=1e-6, help="bisection stop, path fraction")
    args = parser.parse_args()

    va, fa = antcd.load_mesh(args.mesh_a)
    vb, fb = antcd.load_mesh(args.mesh_b)
    a, b = antcd.Model(va, fa, name=args.mesh_a), antcd.Model(vb, fb, name=args.mesh_b)
    print(f"A: {args.mesh_a} ({a.triangle_count} triangles)\nB: {args.mesh_b} ({b.triangle_count} triangles)")

    # B starts to the left of A, clear of it by its own size, and passes through A's centre line.
    lo, hi = a.bounds
    size_b = float(np.linalg.norm(np.ptp(b.bounds, axis=0)))
    centre = (lo + hi) / 2
    start = centre - np.array([hi[0] - lo[0] + 2 * size_b, 0, 0])
    end = centre + np.array([0, 0.1 * (hi[1] - lo[1]), 0])

    previous = 0.0
    for k in range(args.steps + 1):
        s = k / args.steps
        if not antcd.collide(a, None, b, pose_at(s, start, end, args.spin)):
            previous = s
            continue
        low, high = previous, s  # free at low, colliding at high
        while high - low > args.tolerance:
            mid = (low + high) / 2
            if antcd.collide(a, None, b, pose_at(mid, start, end, args.spin)):
                high = mid
            else:
                low = mid
        pose = pose_at(high, start, end, args.spin)
        hit = antcd.collide(a, None, b, pose, all_contacts=True)
        print(f"first contact at step {k} of {args.steps}; bisected to path fraction {high:.7f}")
        print(f"B's translation there: {np.array2string(pose[:3, 3], precision=6)}")
        print(f"{len(hit)} touching triangle pair(s); the first: A's triangle {hit.triangles_a[0]}, "
              f"B's triangle {hit.triangles_b[0]}, at {np.array2string(hit.points[0], precision=6)} (world)")
        return
    print("no contact along the path")


if __name__ == "__main__":
    main()
