"""collide(): verdicts and contact sets equal the C++ tool's (`antcd collide --json`) on real
meshes, every pose form gives the same answer, and bad poses or options raise ValueError."""
import json
import zlib

import numpy as np
import pytest

import antcd
from conftest import box_mesh, quaternion_matrix, random_quaternion, run_cli, sphere_mesh

PAIRS = [("PLY/Wuson.ply", "STL/Spider_binary.stl"), ("OFF/Wuson.off", "PLY/Wuson.ply"),
         ("OBJ/spider.obj", "OFF/Cube.off"), ("STL/sphereWithHole.stl", "PLY/cube.ply")]


def _poses(model_a, model_b, rng, count):
    """Poses of B around A, alternately: B's box centre at a random vertex of A (near A's
    surface, so most collide), and anywhere in A's box grown by half of B's size."""
    lo, hi = model_a.bounds
    size_b = np.linalg.norm(np.ptp(model_b.bounds, axis=0))
    centre_b = model_b.bounds.mean(axis=0)
    for k in range(count):
        q = random_quaternion(rng)
        if k % 2 == 0:
            target = model_a.vertices[rng.integers(0, model_a.vertex_count)]
            target = target + rng.uniform(-0.1, 0.1, 3) * size_b
        else:
            target = rng.uniform(lo - 0.5 * size_b, hi + 0.5 * size_b)
        yield q, target - quaternion_matrix(q, np.zeros(3))[:3, :3] @ centre_b


def _cli_pose(q, t):
    return ",".join(repr(float(x)) for x in (*t, *q))


@pytest.mark.parametrize("name_a, name_b", PAIRS)
def test_contacts_equal_the_cli(models_dir, cli, name_a, name_b):
    path_a, path_b = models_dir / name_a, models_dir / name_b
    a, b = antcd.Model.load(path_a), antcd.Model.load(path_b)
    rng = np.random.default_rng(zlib.crc32((name_a + name_b).encode()))
    verdicts = []
    for q, t in _poses(a, b, rng, 6):
        pose_b = quaternion_matrix(q, t)
        out = json.loads(run_cli(cli, "collide", str(path_a), str(path_b), "--pose-b", _cli_pose(q, t),
                                 "--all", "--json"))
        mine = antcd.collide(a, None, b, pose_b, all_contacts=True)
        assert mine.colliding == out["colliding"]
        theirs = {(c["triangle_a"], c["triangle_b"]): c["point"] for c in out["contacts"]}
        pairs = list(zip(mine.triangles_a.tolist(), mine.triangles_b.tolist()))
        assert set(pairs) == set(theirs) and len(pairs) == len(theirs)
        for (ta, tb), point in zip(pairs, mine.points):
            np.testing.assert_allclose(point, theirs[(ta, tb)], rtol=1e-9, atol=1e-9)
        # The boolean query agrees on the verdict and its one contact is a real one.
        first = antcd.collide(a, None, b, pose_b)
        assert first.colliding == mine.colliding and len(first) == (1 if mine.colliding else 0)
        if first:
            assert (int(first.triangles_a[0]), int(first.triangles_b[0])) in theirs
        verdicts.append(mine.colliding)
    assert any(verdicts) and not all(verdicts), "poses drawn give one verdict only: a one-sided comparison"


def test_delta_equals_the_cli(models_dir, cli):
    path = models_dir / "PLY" / "Wuson.ply"
    a = antcd.Model.load(path)
    gap = np.ptp(a.bounds[:, 0]) + 0.01  # side by side along x, 1 cm apart
    for delta in (0.0, 0.005, 0.02):
        out = json.loads(run_cli(cli, "collide", str(path), str(path), "--pose-b", f"{gap},0,0",
                                 "--delta", repr(delta), "--all", "--json"))
        mine = antcd.collide(a, None, a, ([[1, 0, 0], [0, 1, 0], [0, 0, 1]], [gap, 0, 0]), delta=delta,
                             all_contacts=True)
        assert mine.colliding == out["colliding"]
        assert set(zip(mine.triangles_a.tolist(), mine.triangles_b.tolist())) == {
            (c["triangle_a"], c["triangle_b"]) for c in out["contacts"]}
        np.testing.assert_allclose(np.sort(mine.distances), np.sort([c["distance"] for c in out["contacts"]]),
                                   rtol=1e-9, atol=1e-12)


def test_pose_forms_agree_and_max_contacts_caps():
    v, f = box_mesh()
    a = antcd.Model(v, f)
    rng = np.random.default_rng(5)
    q = random_quaternion(rng)
    m = quaternion_matrix(q, [0.6, 0.2, 0.1])
    forms = [m, m.tolist(), (m[:3, :3], m[:3, 3]), [m[:3, :3].tolist(), m[:3, 3].tolist()],
             (m[:3, :3], m[:3, 3].reshape(3, 1)), np.asfortranarray(m), m.astype(np.float32).astype(np.float64)]
    results = [antcd.collide(a, None, a, pose, all_contacts=True) for pose in forms[:-1]]
    assert results[0].colliding
    for r in results[1:]:
        np.testing.assert_array_equal(r.triangles_a, results[0].triangles_a)
        np.testing.assert_array_equal(r.points, results[0].points)
    assert len(antcd.collide(a, None, a, m, all_contacts=True, max_contacts=2)) == 2
    # The inverse pose on A gives the same contacts, points moved by the inverse.
    inv = np.linalg.inv(m)
    moved = antcd.collide(a, inv, a, None, all_contacts=True)
    np.testing.assert_array_equal(moved.triangles_a, results[0].triangles_a)
    np.testing.assert_allclose(moved.points, results[0].points @ inv[:3, :3].T + inv[:3, 3], atol=1e-12)


def _scaled(s):
    m = np.eye(4)
    m[:3, :3] *= s
    return m


BAD_POSES = [
    (np.eye(3), "4x4"), (np.eye(4)[:3], "4x4"), (_scaled(1.5), "not orthonormal"),
    (np.diag([1.0, 1.0, -1.0, 1.0]), "reflection"),
    (np.array([[1, 0.2, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]]), "not orthonormal"),
    (np.where(np.eye(4) == 0, np.nan, 1.0), "non-finite"),
    (np.array([[1, 0, 0, np.inf], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]]), "non-finite"),
    (np.array([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0.1, 0, 0, 1.0]]), "last row"),
    ((np.eye(3), [0, 0]), "translation"), ((np.eye(2), [0, 0, 0]), "rotation"),
    ((np.eye(3) * 2, [0, 0, 0]), "not orthonormal"), ("pose", "pose_b"), (np.eye(4, dtype=bool), "real numbers"),
]


@pytest.mark.parametrize("pose, message", BAD_POSES)
def test_bad_poses_raise_value_error(pose, message):
    v, f = box_mesh()
    a = antcd.Model(v, f)
    with pytest.raises(ValueError, match=message):
        antcd.collide(a, None, a, pose)


@pytest.mark.parametrize("kwargs, message", [({"delta": -1.0}, "delta"), ({"delta": float("nan")}, "delta"),
                                             ({"delta": float("inf")}, "delta"), ({"max_contacts": -1}, "max_contacts")])
def test_bad_options_raise_value_error(kwargs, message):
    v, f = box_mesh()
    a = antcd.Model(v, f)
    with pytest.raises(ValueError, match=message):
        antcd.collide(a, None, a, None, **kwargs)


def test_surfaces_not_volumes():
    """A box strictly inside another does not collide; touching faces do."""
    v, f = box_mesh()
    outer, inner = antcd.Model(v * 4, f), antcd.Model(v, f)
    assert not antcd.collide(outer, None, inner, None)
    touching = np.eye(4)
    touching[0, 3] = 1.0  # unit boxes side by side, faces in contact
    assert antcd.collide(inner, None, inner, touching).colliding
    touching[0, 3] = 1.0 + 1e-9
    assert not antcd.collide(inner, None, inner, touching).colliding
    assert antcd.collide(inner, None, inner, touching, delta=1e-6).colliding


def test_normals_and_depths_equal_the_cli(models_dir, cli):
    path_a, path_b = models_dir / "OBJ/spider.obj", models_dir / "OFF/Cube.off"
    a, b = antcd.Model.load(path_a), antcd.Model.load(path_b)
    rng = np.random.default_rng(15)
    checked = 0
    for q, t in _poses(a, b, rng, 6):
        pose_b = quaternion_matrix(q, t)
        r = antcd.collide(a, None, b, pose_b, all_contacts=True, contact_normals=True)
        plain = antcd.collide(a, None, b, pose_b, all_contacts=True)
        assert np.array_equal(plain.normals, np.zeros((len(plain), 3)))  # not asked for
        assert np.array_equal(r.triangles_a, plain.triangles_a)
        if not r:
            continue
        checked += 1
        assert r.normals.shape == (len(r), 3) and r.depths.shape == (len(r),)
        np.testing.assert_allclose(np.linalg.norm(r.normals, axis=1), 1.0, atol=1e-12)
        assert np.all(r.depths >= 0)  # delta 0: every contact intersects
        out = json.loads(run_cli(cli, "collide", str(path_a), str(path_b), "--pose-b",
                                 _cli_pose(q, t), "--all", "--normals", "--json"))
        assert [c["triangle_a"] for c in out["contacts"]] == r.triangles_a.tolist()
        np.testing.assert_allclose([c["normal"] for c in out["contacts"]], r.normals, atol=1e-9)
        np.testing.assert_allclose([c["depth"] for c in out["contacts"]], r.depths, atol=1e-9)
        m = antcd.collide(a, None, b, pose_b, all_contacts=True, manifold_points=2)
        counts = np.bincount(m.regions)
        assert counts.min() >= 1 and counts.max() <= 2
    assert checked >= 2
    with pytest.raises(ValueError, match="manifold_points"):
        antcd.collide(a, None, b, None, manifold_points=-1)


def test_large_leaves_are_culled_triangle_by_triangle():
    """A small sphere just inside a big box's +x face: the box's leaves (4 big triangles each) are
    tested triangle by triangle against the sphere's nodes (stats['triangle_rejects']); the
    verdict follows the gap to the face."""
    v, f = box_mesh((10.0, 10.0, 10.0))
    big = antcd.Model(v, f)
    sv, sf = sphere_mesh(0.2, 16, 8)
    small = antcd.Model(sv, sf)
    pose = np.eye(4)
    pose[:3, 3] = (9.7, 1.0, 2.0)  # 0.1 from the face x = 10
    apart = antcd.collide(big, None, small, pose)
    assert not apart.colliding
    assert apart.stats["triangle_rejects"] > 0
    assert antcd.collide(big, None, small, pose, delta=0.11).colliding
    pose[0, 3] = 9.85  # crosses the face
    assert antcd.collide(big, None, small, pose).colliding
