"""CollisionManager: trimesh's interface and return conventions, and answers equal to brute force
(collide() on every pair) over seeded random add / remove / move sequences."""
import itertools

import numpy as np
import pytest

import antcd
from conftest import box_mesh, random_manager_step, random_pose, sphere_mesh


class FakeTrimesh:
    """Duck-typed stand-in for trimesh.Trimesh (the manager only reads .vertices and .faces)."""

    def __init__(self, vertices, faces):
        self.vertices, self.faces = vertices, faces


@pytest.fixture(scope="module")
def shapes(models_dir):
    box = antcd.Model(*box_mesh((0.5, 0.3, 0.2)))
    sphere = antcd.Model(*sphere_mesh(0.45, 20, 10))
    v, f = antcd.load_mesh(models_dir / "PLY" / "Wuson.ply")
    wuson = antcd.Model(v * 0.4, f)  # about 1 unit tall, like the others
    return [box, sphere, wuson]


def _random_pose(rng):
    return random_pose(rng, 1.6)


def _pair_truth(ma, pa, mb, pb):
    """The contacts the manager reports for a pair as (triangle, triangle) index pairs, None when
    the pair does not collide: the surfaces' colliding triangle pairs, or one solid contact
    (-1, -1) for two convex meshes, or for closed ones whose surfaces are apart but whose solids
    overlap (nested)."""
    r = antcd.collide(ma, pa, mb, pb, all_contacts=True)
    if r:
        if antcd.is_convex(ma) and antcd.is_convex(mb):
            return {(-1, -1)}
        return set(zip(r.triangles_a.tolist(), r.triangles_b.tolist()))
    try:
        nested = antcd.penetration(ma, pa, mb, pb).overlapping
    except ValueError:  # an open mesh: surfaces only
        nested = False
    return {(-1, -1)} if nested else None


def _brute_internal(objects):
    hits = {}
    for (na, (ma, pa)), (nb, (mb, pb)) in itertools.combinations(sorted(objects.items()), 2):
        truth = _pair_truth(ma, pa, mb, pb)
        if truth:
            hits[(na, nb)] = truth
    return hits


def _probe_last(names):
    (name,) = names - {"__external"}
    return name, "__external"


def _this_first(names, objects):
    (name,) = names & set(objects)
    (other,) = names - {name}
    return name, other


def _contact_sets(data, order=sorted):
    """{name pair (ordered by `order`): {(triangle of first name, triangle of second name)}} from
    ContactData."""
    out = {}
    for c in data:
        first, second = order(c.names)
        out.setdefault((first, second), set()).add((c.index(first), c.index(second)))
    return out


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_internal_equals_brute_force_over_random_sequences(shapes, seed):
    rng = np.random.default_rng(seed)
    manager = antcd.CollisionManager()
    objects = {}
    checked_colliding = checked_free = 0
    for step in range(60):
        random_manager_step(rng, manager, objects, shapes, names=12, extent=1.6)
        assert len(manager) == len(objects)
        truth = _brute_internal(objects)
        verdict, names, data = manager.in_collision_internal(return_names=True, return_data=True)
        assert verdict == bool(truth) == manager.in_collision_internal()
        assert names == set(truth)
        assert manager.in_collision_internal(return_names=True) == (bool(truth), set(truth))
        assert _contact_sets(data) == truth
        checked_colliding += bool(truth)
        checked_free += not truth
        # One more object checked against everything, and a second manager against this one.
        probe_model, probe_pose = shapes[step % len(shapes)], _random_pose(rng)
        single_truth = {}
        for n, (m, p) in objects.items():
            truth_np = _pair_truth(m, p, probe_model, probe_pose)
            if truth_np:
                single_truth[(n, "__external")] = truth_np
        hit, single_names = manager.in_collision_single(probe_model, probe_pose, return_names=True)
        assert hit == bool(single_truth) and single_names == {n for n, _ in single_truth}
        hit, single_data = manager.in_collision_single(probe_model, probe_pose, return_data=True)
        assert hit == bool(single_truth) and _contact_sets(single_data, order=_probe_last) == single_truth
        if step % 10 == 0:
            other_objects = {"probe": (probe_model, probe_pose), "probe2": (shapes[0], _random_pose(rng))}
            other = antcd.CollisionManager()
            for other_name, (m, p) in other_objects.items():
                other.add_object(other_name, m, p)
            other_truth = {}
            for n, (m, p) in objects.items():
                for on, (om, op_) in other_objects.items():
                    truth_no = _pair_truth(m, p, om, op_)
                    if truth_no:
                        other_truth[(n, on)] = truth_no
            assert manager.in_collision_other(other, return_names=True) == (bool(other_truth), set(other_truth))
            hit, other_data = manager.in_collision_other(other, return_data=True)
            assert hit == bool(other_truth)
            assert _contact_sets(other_data, order=lambda names: _this_first(names, objects)) == other_truth
    assert checked_colliding > 5 and checked_free > 0, "the sequence never tested both outcomes"


def test_return_conventions_match_trimesh(shapes):
    box = shapes[0]
    manager = antcd.CollisionManager()
    shifted = np.eye(4)
    shifted[0, 3] = 0.8  # boxes of half width 0.5 overlap
    returned = manager.add_object("b", box)
    assert returned is box
    manager.add_object("a", FakeTrimesh(*box_mesh((0.5, 0.3, 0.2))), shifted)
    manager.add_object("far", (box.vertices, box.faces), (np.eye(3), [10.0, 0, 0]))

    assert manager.in_collision_internal() is True
    result, names = manager.in_collision_internal(return_names=True)
    assert result and names == {("a", "b")}  # 2-tuples, alphabetical order
    result, data = manager.in_collision_internal(return_data=True)
    result, names, data = manager.in_collision_internal(return_names=True, return_data=True)
    assert data and all(c.names == {"a", "b"} for c in data)
    c = data[0]
    assert c.point.shape == (3,) and c.normal.shape == (3,) and np.isclose(np.linalg.norm(c.normal), 1)
    # Two convex boxes: one solid contact, FCL-Convex-like: the solids' depth (0.2 along x).
    assert len(data) == 1 and c.index("a") == -1 and c.index("b") == -1 and c.distance == 0
    assert c.depth == pytest.approx(0.2) and np.allclose(np.abs(c.normal), [1, 0, 0])

    single = manager.in_collision_single(box, shifted, return_names=True, return_data=True)
    assert single[0] and single[1] == {"a", "b"}
    assert all(c.names in ({"a", "__external"}, {"b", "__external"}) for c in single[2])
    assert manager.in_collision_single(box, (np.eye(3), [20.0, 0, 0])) is False
    assert manager.in_collision_single(box, (np.eye(3), [20.0, 0, 0]), return_names=True) == (False, set())

    other = antcd.CollisionManager()
    other.add_object("x", box, (np.eye(3), [10.5, 0, 0]))
    assert manager.in_collision_other(other, return_names=True) == (True, {("far", "x")})
    assert other.in_collision_other(manager, return_names=True) == (True, {("x", "far")})

    manager.set_transform("far", (np.eye(3), [30.0, 0, 0]))
    assert manager.in_collision_other(other) is False
    manager.remove_object("a")
    assert manager.in_collision_internal() is False and "a" not in manager and len(manager) == 2
    # Re-adding a name replaces the object.
    manager.add_object("b", box, shifted)
    assert len(manager) == 2


def test_manager_errors(shapes):
    manager = antcd.CollisionManager()
    manager.add_object("a", shapes[0])
    with pytest.raises(ValueError, match="nope not in collision manager"):
        manager.remove_object("nope")
    with pytest.raises(ValueError, match="nope not in collision manager"):
        manager.set_transform("nope", np.eye(4))
    with pytest.raises(ValueError, match="not orthonormal"):
        manager.set_transform("a", np.diag([2.0, 2.0, 2.0, 1.0]))
    with pytest.raises(ValueError, match="transform"):
        manager.add_object("b", shapes[0], np.eye(3))
    assert "b" not in manager and len(manager) == 1  # a failed add leaves the manager unchanged
    with pytest.raises(ValueError, match="non-finite"):
        manager.in_collision_single(shapes[0], np.full((4, 4), np.nan))
    with pytest.raises(TypeError, match="mesh must be"):
        manager.add_object("c", 42)
    with pytest.raises(ValueError, match="out of range"):
        manager.add_object("c", FakeTrimesh(np.zeros((3, 3)), np.array([[0, 1, 3]])))
    with pytest.raises(TypeError, match="other_manager"):
        manager.in_collision_other("not a manager")
