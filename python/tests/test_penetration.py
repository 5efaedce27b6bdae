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
