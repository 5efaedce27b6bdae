"""antcd.penetration, antcd.distance(signed=True) and the manager's signed minimum distances."""
import numpy as np
import pytest

import antcd


def _cube(half=1.0):
    v = np.array([[x, y, z] for x in (-half, half) for y in (-half, half) for z in (-half, half)],
                 dtype=float)
    f = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                  [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])
    return v, f


def _pose(t):
    m = np.eye(4)
    m[:3, 3] = t
    return m


def test_penetration_of_overlapping_cubes_is_exact():
    cube = antcd.Model(*_cube())
    assert antcd.is_convex(cube)
    r = antcd.penetration(cube, None, cube, _pose([1.7, 0.3, 0.2]))
    assert r.overlapping and r.exact and r.converged
    assert r.lower == pytest.approx(0.3, abs=1e-12) and r.upper == pytest.approx(0.3, abs=1e-12)
    assert r.direction == pytest.approx([-1, 0, 0], abs=1e-12)
    assert antcd.collide(cube, _pose(r.witness * 0), cube, _pose([1.7, 0.3, 0.2])).colliding


def test_penetration_general_bounds_and_errors():
    cube = antcd.Model(*_cube())
    r = antcd.penetration(cube, None, cube, _pose([1.7, 0.3, 0.2]), 0.01, shape="general")
    assert not r.exact and r.converged
    assert r.lower <= 0.3 <= r.upper and r.upper - r.lower <= 0.01 * r.upper
    moved = _pose(r.direction * (r.upper + 1e-9))
    assert not antcd.collide(cube, moved, cube, _pose([1.7, 0.3, 0.2])).colliding
    v, f = _cube()
    open_box = antcd.Model(v, f[:-1], name="lidless")
    with pytest.raises(ValueError, match="lidless"):
        antcd.penetration(open_box, None, cube, None)
    with pytest.raises(ValueError):
        antcd.penetration(cube, None, cube, None, 1.5)


def test_signed_distance():
    cube = antcd.Model(*_cube())
    small = antcd.Model(*_cube(0.2))
    assert antcd.distance(cube, None, cube, _pose([1.7, 0.3, 0.2]), signed=True).distance == \
        pytest.approx(-0.3, abs=1e-12)
    assert antcd.distance(small, None, cube, None).distance == pytest.approx(0.8)
    assert antcd.distance(small, None, cube, None, signed=True).distance == pytest.approx(-1.2)
    assert antcd.distance(cube, None, cube, _pose([2.5, 0, 0]), signed=True).distance == \
        pytest.approx(0.5)


def test_manager_min_distance_is_signed_and_takes_a_name():
    m = antcd.CollisionManager()
    m.add_object("a", _cube())
    m.add_object("b", _cube(), _pose([1.5, 0, 0]))  # overlapping by 0.5
    m.add_object("c", _cube(), _pose([10, 0, 0]))
    d, names = m.min_distance_internal(return_names=True)
    assert d == pytest.approx(-0.5) and names == ("a", "b")
    assert m.min_distance_internal(name="c") == pytest.approx(6.5)
    d, names = m.min_distance_internal(name="a", return_names=True)
    assert d == pytest.approx(-0.5) and names == ("a", "b")
    assert m.min_distance_single(_cube(), _pose([0, 1.75, 0])) == pytest.approx(-0.25)
    with pytest.raises(ValueError):
        m.min_distance_internal(name="nope")


def test_manager_answers_trimesh_collision_tests():
    """The expectations of trimesh's tests/test_collision.py (on python-fcl), unit cubes."""
    cube = _cube(0.5)
    tf1, tf2, tf3, tf4, tf5 = (_pose([x, 0, 0]) for x in (5, -5, 2, -2, 5.75))
    m = antcd.CollisionManager()
    m.add_object("cube0", cube)
    m.add_object("cube1", cube, tf1)
    ret, names, data = m.in_collision_single(cube, tf1, return_names=True, return_data=True)
    assert ret is True and "cube1" in names and len(data) == 1  # one contact per convex pair
    for c in data:
        assert c.depth == pytest.approx(1.0)
        # Coincident cubes: every axis ties; the smallest direction wins, -x as FCL reports it.
        assert c.normal == pytest.approx([-1, 0, 0])
        assert c.point[0] == pytest.approx(5.0) and np.all(np.abs(c.point[1:]) <= 0.5 + 1e-12)
    ret, names, data = m.in_collision_single(cube, tf2, return_names=True, return_data=True)
    assert ret is False and len(names) == 0 and data == []

    m = antcd.CollisionManager()
    m.add_object("cube1", cube, tf1)
    assert m.min_distance_single(cube) == pytest.approx(4.0)
    assert m.min_distance_single(cube, tf5) == pytest.approx(-0.25)
    m.add_object("cube2", cube, tf2)
    assert m.min_distance_single(cube, tf3, return_name=True) == (pytest.approx(2.0), "cube1")
    assert m.min_distance_internal(return_names=True) == (pytest.approx(9.0), ("cube1", "cube2"))
    m.add_object("cube3", cube, tf3)
    m.set_transform("cube3", tf4)
    assert m.min_distance_internal(return_names=True) == (pytest.approx(2.0), ("cube2", "cube3"))
    assert m.min_distance_internal(name="cube1", return_names=True) == \
        (pytest.approx(6.0), ("cube1", "cube3"))


def test_manager_nested_solids_collide_with_one_solid_contact():
    m = antcd.CollisionManager()
    m.add_object("big", _cube(1.0))
    m.add_object("small", _cube(0.2), _pose([0.1, 0, 0]))
    ret, names, data = m.in_collision_internal(return_names=True, return_data=True)
    assert ret is True and names == {("big", "small")} and len(data) == 1
    assert data[0].depth == pytest.approx(1.1)  # the small cube leaves through x = -1... or +1
    assert data[0].index("big") == -1
    v, f = _cube(1.0)
    torus = antcd.Model(*_torus())
    m2 = antcd.CollisionManager()
    m2.add_object("torus", torus)
    m2.add_object("box", (v * 2, f), _pose([2.0, 0, -1.8]))  # overlaps the tube by 0.3
    ret, data = m2.in_collision_internal(return_data=True)
    assert ret and len(data) > 1  # non-convex: one contact per triangle pair, each with a depth
    assert all(np.isfinite(c.depth) and c.depth >= 0 for c in data)


def _torus(major=2.0, minor=0.5, n=24, k=12):
    u, w = np.meshgrid(np.arange(n) * 2 * np.pi / n, np.arange(k) * 2 * np.pi / k, indexing="ij")
    rho = major + minor * np.cos(w)
    v = np.stack([rho * np.cos(u), rho * np.sin(u), minor * np.sin(w)], axis=-1).reshape(-1, 3)
    f = []
    for i in range(n):
        for j in range(k):
            a, b = i * k + j, ((i + 1) % n) * k + j
            c, d = ((i + 1) % n) * k + (j + 1) % k, i * k + (j + 1) % k
            f += [[a, b, c], [a, c, d]]
    return v, np.array(f)
