"""Shared fixtures of the antcd pytest suite.

The suite runs against the package in the build tree (ctest sets PYTHONPATH) or an installed one.
It needs Debian's assimp-testmodels (real third-party meshes) and, for the comparisons with the
C++ tool, the `antcd` CLI (ctest sets ANTCD_CLI; otherwise it is looked up on PATH).
"""
import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

import antcd  # noqa: F401  (an import failure must fail the suite, never skip it)

MODELS = Path(os.environ.get("ANTCD_ASSIMP_MODELS", "/usr/share/assimp/models"))


@pytest.fixture(scope="session")
def models_dir() -> Path:
    if not MODELS.is_dir():
        pytest.fail(f"{MODELS} missing: install Debian's assimp-testmodels (scripts/install-deps.sh)")
    return MODELS


@pytest.fixture(scope="session")
def cli() -> str:
    path = os.environ.get("ANTCD_CLI") or shutil.which("antcd")
    if not path or not os.path.exists(path):
        pytest.fail("the antcd CLI is needed (set ANTCD_CLI or put antcd on PATH)")
    return path


def run_cli(cli: str, *args: str) -> str:
    done = subprocess.run([cli, *args], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, f"antcd {' '.join(args)} failed: {done.stderr}"
    return done.stdout


def box_mesh(half=(0.5, 0.5, 0.5)):
    """A closed box centred on the origin: 8 vertices, 12 triangles (outward winding)."""
    hx, hy, hz = half
    v = np.array([[x, y, z] for x in (-hx, hx) for y in (-hy, hy) for z in (-hz, hz)], dtype=np.float64)
    f = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                  [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]], dtype=np.int64)
    return v, f


def sphere_mesh(radius=1.0, slices=24, stacks=12):
    """A closed UV sphere centred on the origin."""
    verts = [[0.0, 0.0, radius]]
    for i in range(1, stacks):
        theta = np.pi * i / stacks
        for j in range(slices):
            phi = 2 * np.pi * j / slices
            verts.append([radius * np.sin(theta) * np.cos(phi), radius * np.sin(theta) * np.sin(phi),
                          radius * np.cos(theta)])
    verts.append([0.0, 0.0, -radius])
    faces = []
    last = len(verts) - 1
    for j in range(slices):
        faces.append([0, 1 + j, 1 + (j + 1) % slices])
    for i in range(stacks - 2):
        for j in range(slices):
            a = 1 + i * slices + j
            b = 1 + i * slices + (j + 1) % slices
            faces.append([a, a + slices, b + slices])
            faces.append([a, b + slices, b])
    base = 1 + (stacks - 2) * slices
    for j in range(slices):
        faces.append([base + j, last, base + (j + 1) % slices])
    return np.array(verts), np.array(faces, dtype=np.int64)


def quaternion_matrix(q, t):
    """4x4 pose from a unit quaternion (w, x, y, z) and a translation."""
    w, x, y, z = q
    m = np.eye(4)
    m[:3, :3] = [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                 [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                 [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]
    m[:3, 3] = t
    return m


def random_quaternion(rng):
    q = rng.normal(size=4)
    return q / np.linalg.norm(q)


def random_pose(rng, extent):
    """A uniformly random rotation and a translation uniform in [-extent, extent]^3."""
    return quaternion_matrix(random_quaternion(rng), rng.uniform(-extent, extent, 3))


def random_manager_step(rng, manager, objects, shapes, names, extent):
    """One random mutation of a CollisionManager, mirrored in `objects` ({name: (model, pose)}):
    add (a name among `names` possibly present: it replaces the object), remove or move."""
    op = rng.uniform()
    if op < 0.4 or len(objects) < 2:
        name = f"obj{rng.integers(0, names)}"
        model = shapes[rng.integers(0, len(shapes))]
        pose = random_pose(rng, extent)
        manager.add_object(name, model, pose)
        objects[name] = (model, pose)
    elif op < 0.55:
        name = sorted(objects)[rng.integers(0, len(objects))]
        manager.remove_object(name)
        del objects[name]
    else:
        name = sorted(objects)[rng.integers(0, len(objects))]
        pose = random_pose(rng, extent)
        manager.set_transform(name, pose)
        objects[name] = (objects[name][0], pose)
