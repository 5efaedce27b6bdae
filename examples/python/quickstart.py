#!/usr/bin/python3
"""The README's Python example: load a mesh, one collision query, one distance query.

Run by ctest (python_example_quickstart) against build/python; needs Debian's assimp-testmodels.
"""
import numpy as np

import antcd

vertices, faces = antcd.load_mesh("/usr/share/assimp/models/PLY/Wuson.ply")  # float64, int64
wuson = antcd.Model(vertices, faces)  # checked (ValueError), hierarchy built once

pose = np.eye(4)  # a rigid 4x4 pose, or (R 3x3, t 3); None is the identity
pose[0, 3] = 0.5
hit = antcd.collide(wuson, None, wuson, pose, all_contacts=True)
print(f"colliding: {'yes' if hit.colliding else 'no'}, {len(hit.triangles_a)} triangle pairs")

d = antcd.distance(wuson, None, wuson, (np.eye(3), [3.0, 0, 0]))
print(f"distance at x = 3: {d.distance:.6f} (triangles {d.triangle_a} and {d.triangle_b})")
