"""CollisionManager's minimum-distance queries (trimesh's min_distance_single / _internal / _other):
answers equal brute force (antcd.distance on every pair) over seeded random add / remove / move
sequences of real and generated meshes, trimesh's return conventions, clear errors."""
import itertools
import math

import numpy as np
import pytest

import antcd
from conftest import box_mesh, random_manager_step, random_pose, sphere_mesh


@pytest.fixture(scope="module")
def shapes(models_dir):
    box = antcd.Model(*box_mesh((0.5, 0.3, 0.2)))
    sphere = antcd.Model(*sphere_mesh(0.45, 16, 8))
    v, f = antcd.load_mesh(models_dir / "PLY" / "Wuson.ply")
    wuson = antcd.Model(v * 0.4, f)  # about 1 unit tall, like the others
    v, f = antcd.load_mesh(models_dir / "STL" / "Spider_binary.stl")
    spider = antcd.Model((v - v.mean(axis=0)) * (1.2 / np.ptp(v, axis=0).max()), f)  # an open mesh
    return [box, sphere, wuson, spider]


def _random_pose(rng):
    return random_pose(rng, 2.5)


def _signed(a, pose_a, b, pose_b):
    """The manager's distance: signed for two closed meshes, the surface distance otherwise."""
    try:
        return antcd.distance(a, pose_a, b, pose_b, signed=True)
    except ValueError:  # an open mesh
        return antcd.distance(a, pose_a, b, pose_b)


def _same(d, expected):
    return math.isclose(d, expected, rel_tol=1e-12, abs_tol=1e-12)


def _triangle_model(model, pose, index):
    """The one triangle `index` of a posed model, as a Model in world coordinates."""
    corners = model.vertices[model.faces[index]] @ pose[:3, :3].T + pose[:3, 3]
    return antcd.Model(corners, np.array([[0, 1, 2]]))


def _on_triangle(p, corners, tol=1e-9):
    """Whether p lies on the triangle (in its plane, barycentric coordinates >= 0, up to tol)."""
    a, b, c = corners
    n = np.cross(b - a, c - a)
    area2 = np.dot(n, n)
    if abs(np.dot(p - a, n)) > tol * math.sqrt(area2):
        return False
    bary = [np.dot(np.cross(v1 - p, v2 - p), n) / area2 for v1, v2 in ((b, c), (c, a), (a, b))]
    return min(bary) >= -1e-7


def _check_data(data, names, expected, posed):
    """DistanceData: the names, the distance, closest points that far apart, and closest points
    lying on the named triangles, which are themselves that far apart."""
    assert data.names == set(names)
    assert _same(data.distance, expected)
    if expected < 0:  # overlapping solids: the points are penetration()'s, not closest points
        return
    a, b = names
    assert np.linalg.norm(data.point(a) - data.point(b)) == pytest.approx(expected, rel=1e-9, abs=1e-9)
    tri_a = _triangle_model(*posed[a], data.index(a))
    tri_b = _triangle_model(*posed[b], data.index(b))
    assert antcd.distance(tri_a, None, tri_b, None).distance == pytest.approx(expected, rel=1e-9, abs=1e-9)
    for name, tri in ((a, tri_a), (b, tri_b)):
        assert _on_triangle(data.point(name), tri.vertices), f"point({name}) is off its triangle"


@pytest.mark.parametrize("seed", [1, 2])
def test_min_distances_equal_brute_force_over_random_sequences(shapes, seed):
    rng = np.random.default_rng(seed)
    manager = antcd.CollisionManager()
    objects = {}
    seen_zero = seen_positive = 0
    for step in range(36):
        random_manager_step(rng, manager, objects, shapes, names=9, extent=2.5)
        pair_distances = {
            (na, nb): _signed(ma, pa, mb, pb).distance
            for (na, (ma, pa)), (nb, (mb, pb)) in itertools.combinations(sorted(objects.items()), 2)
        }
        d, names, data = manager.min_distance_internal(return_names=True, return_data=True)
        if not pair_distances:  # one object left (a name was replaced): nothing to measure
            assert (d, names, data) == (math.inf, None, None)
        else:
            truth = min(pair_distances.values())
            assert _same(d, truth) and _same(manager.min_distance_internal(), truth)
            assert names == tuple(sorted(names)) and _same(pair_distances[names], truth)
            _check_data(data, names, truth, objects)
            seen_zero += truth <= 0  # touching or overlapping (signed: negative)
            seen_positive += truth > 0

        probe_model, probe_pose = shapes[step % len(shapes)], _random_pose(rng)
        single = {n: _signed(m, p, probe_model, probe_pose).distance for n, (m, p) in objects.items()}
        d, name, data = manager.min_distance_single(probe_model, probe_pose, return_name=True, return_data=True)
        assert _same(d, min(single.values())) and _same(single[name], d)
        _check_data(data, (name, "__external"), d, {**objects, "__external": (probe_model, probe_pose)})

        if step % 6 == 0:
            others = {"p": (probe_model, probe_pose), "q": (shapes[0], _random_pose(rng))}
            other = antcd.CollisionManager()
            for n, (m, p) in others.items():
                other.add_object(n, m, p)
            cross = {(n, o): _signed(m, p, om, op_).distance
                     for n, (m, p) in objects.items() for o, (om, op_) in others.items()}
            d, names, data = manager.min_distance_other(other, return_names=True, return_data=True)
            assert _same(d, min(cross.values())) and _same(cross[names], d)
            assert names[0] in objects and names[1] in others  # (this manager's, the other's)
            _check_data(data, names, d, {**objects, **others})
            back, back_names = other.min_distance_other(manager, return_names=True)
            assert _same(back, d) and _same(cross[back_names[::-1]], d)
    assert seen_zero and seen_positive, "the sequence never met both touching and apart objects"


def test_min_distance_return_conventions(shapes):
    box = shapes[0]
    manager = antcd.CollisionManager()
    assert manager.min_distance_internal() == math.inf
    assert manager.min_distance_internal(return_names=True, return_data=True) == (math.inf, None, None)
    assert manager.min_distance_single(box, return_name=True) == (math.inf, None)

    manager.add_object("b", box)
    manager.add_object("a", box, (np.eye(3), [3.0, 0, 0]))  # faces 2 apart along x
    manager.add_object("c", box, (np.eye(3), [0, 0, 10.0]))
    d = manager.min_distance_internal()
    assert isinstance(d, float) and d == pytest.approx(2.0)
    d, names = manager.min_distance_internal(return_names=True)
    assert names == ("a", "b")  # alphabetical
    d, data = manager.min_distance_internal(return_data=True)
    assert isinstance(data, antcd.DistanceData) and not data.intersecting
    assert data.point("b")[0] == pytest.approx(0.5) and data.point("a")[0] == pytest.approx(2.5)
    assert 0 <= data.index("a") < 12 and 0 <= data.index("b") < 12

    d, name, data = manager.min_distance_single(box, (np.eye(3), [0, 0, 8.5]), return_name=True, return_data=True)
    assert name == "c" and d == pytest.approx(1.1) and data.names == {"c", "__external"}
    assert data.point("__external")[2] == pytest.approx(8.7) and data.point("c")[2] == pytest.approx(9.8)
    d, name = manager.min_distance_single(box, (np.eye(3), [0.2, 0, 0]), return_name=True)
    assert d == pytest.approx(-0.4) and name == "b"  # overlapping solids: minus the depth

    other = antcd.CollisionManager()
    assert manager.min_distance_other(other, return_names=True) == (math.inf, None)
    other.add_object("x", box, (np.eye(3), [0, 0, -5.0]))
    d, names = manager.min_distance_other(other, return_names=True)
    assert names == ("b", "x") and d == pytest.approx(4.6)
    assert other.min_distance_other(manager, return_names=True)[1] == ("x", "b")
    manager.set_transform("b", (np.eye(3), [0, 0, -4.0]))
    assert manager.min_distance_other(other) == pytest.approx(0.6)
    manager.remove_object("b")
    assert manager.min_distance_other(other, return_names=True)[1] == ("a", "x")


def test_min_distance_internal_finds_the_deepest_overlap(shapes):
    # Two overlapping pairs of solids; the shallow pair holds the objects added first. A search
    # that stopped at the first negative distance (as the manager's own search once did) would
    # report -0.1 instead of the deeper pair's -0.3.
    box = shapes[0]  # half extents (0.5, 0.3, 0.2)
    manager = antcd.CollisionManager()
    manager.add_object("shallow1", box)
    manager.add_object("shallow2", box, (np.eye(3), [0.9, 0, 0]))
    manager.add_object("deep1", box, (np.eye(3), [10.0, 0, 0]))
    manager.add_object("deep2", box, (np.eye(3), [10.0, 0, 0.1]))  # overlap 0.3 along z
    d, names = manager.min_distance_internal(return_names=True)
    assert names == ("deep1", "deep2") and d == pytest.approx(-0.3)
    d, names = manager.min_distance_internal(return_names=True, name="shallow2")
    assert names == ("shallow1", "shallow2") and d == pytest.approx(-0.1)


def test_min_distance_errors(shapes):
    manager = antcd.CollisionManager()
    manager.add_object("a", shapes[0])
    with pytest.raises(ValueError, match="transform.*non-finite|non-finite.*transform"):
        manager.min_distance_single(shapes[0], np.full((4, 4), np.nan))
    with pytest.raises(ValueError, match="not orthonormal"):
        manager.min_distance_single(shapes[0], np.diag([2.0, 1.0, 1.0, 1.0]))
    with pytest.raises(ValueError, match="transform"):
        manager.min_distance_single(shapes[0], np.eye(3))
    with pytest.raises(TypeError, match="mesh must be"):
        manager.min_distance_single("box")
    with pytest.raises(TypeError, match="other_manager"):
        manager.min_distance_other(None)
    with pytest.raises(ValueError, match="upper_bound"):
        antcd.distance(shapes[0], None, shapes[0], None, upper_bound=-1.0)
    with pytest.raises(ValueError, match="rel_tolerance"):
        antcd.distance(shapes[0], None, shapes[0], None, rel_tolerance=1.5)
    with pytest.raises(ValueError, match="abs_tolerance"):
        antcd.distance(shapes[0], None, shapes[0], None, abs_tolerance=float("nan"))
    with pytest.raises(ValueError, match="pose_b"):
        antcd.distance(shapes[0], None, shapes[0], np.zeros((4, 4)))


def test_distance_function(shapes):
    box, sphere = shapes[0], shapes[1]
    r = antcd.distance(box, None, sphere, (np.eye(3), [2.0, 0, 0]))
    # The sphere mesh is inscribed in a radius-0.45 sphere: its surface is no nearer than 1.05.
    assert r.distance >= 1.05 - 1e-12 and r.distance == pytest.approx(1.05, abs=0.02)
    assert np.linalg.norm(r.point_a - r.point_b) == pytest.approx(r.distance)
    assert r.point_a.shape == (3,) and r.point_a[0] == pytest.approx(0.5)
    assert not r.intersecting and r.lower_bound <= r.distance and float(r) == r.distance
    touching = antcd.distance(box, None, box, (np.eye(3), [0.9, 0, 0]))
    assert touching.intersecting and touching.distance == 0
    bounded = antcd.distance(box, None, sphere, (np.eye(3), [2.0, 0, 0]), upper_bound=0.5)
    assert bounded.beyond_upper_bound and bounded.lower_bound > 0.5
