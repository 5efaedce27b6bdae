"""CollisionManager with deforming objects (issues 36 and 37): set_vertices, self pairs
(name, name) equal to antcd.self_intersections of the same vertices, the pins following the
Model each object uses, sweep_motion / set_motion_continuous against dense sub-stepping, bad
input, and a query thread while another thread sets vertices."""
import threading

import numpy as np
import pytest

import antcd
from conftest import box_mesh, sphere_mesh


def sheet(n=8, size=1.0):
    """A flat open n x n grid in the plane z = 0, centred on the origin."""
    xs = np.linspace(-size / 2, size / 2, n)
    v = np.array([[x, y, 0.0] for y in xs for x in xs])
    f = []
    for j in range(n - 1):
        for i in range(n - 1):
            a = j * n + i
            f += [[a, a + 1, a + n + 1], [a, a + n + 1, a + n]]
    return v, np.array(f, dtype=np.int64)


def folded(v, depth, tilt):
    """The sheet with its half x > 0 folded back over the half x < 0, tilted so that it cuts
    through it along x = -depth / tilt: a self-intersecting surface."""
    out = v.copy()
    right = v[:, 0] > 0
    out[right, 0] = -v[right, 0]
    out[right, 2] = tilt * v[right, 0] - depth
    return out


def pose(t):
    m = np.eye(4)
    m[:3, 3] = t
    return m


def _self_pairs(data, name):
    return sorted(c.triangles for c in data if c.names == {name})


@pytest.mark.parametrize("depth, tilt", [(0.25, 1.0), (0.1, 0.6), (0.3, 2.0)])
def test_self_pairs_equal_self_intersections(depth, tilt):
    v, f = sheet()
    manager = antcd.CollisionManager()
    given = manager.add_object("cloth", (v, f), pose([1.0, 2.0, 3.0]), self_collision=True)
    manager.add_object("rigid", (v, f), pose([5.0, 0.0, 0.0]))  # no self_collision: never (n, n)
    assert manager.in_collision_internal(return_names=True) == (False, set())

    bent = folded(v, depth, tilt)
    manager.set_vertices("cloth", bent)
    manager.set_vertices("rigid", bent)
    truth = antcd.self_intersections(antcd.Model(bent, f)).pairs
    assert len(truth) > 0
    hit, names, data = manager.in_collision_internal(return_names=True, return_data=True)
    assert hit and names == {("cloth", "cloth")}
    assert _self_pairs(data, "cloth") == sorted(map(tuple, truth.tolist()))
    for c in data:  # a world point on both triangles (the pose's translation applied)
        i, j = c.triangles
        assert c.index("cloth") == i < j and c.distance == 0
        world = bent[f[[i, j]]] + [1.0, 2.0, 3.0]
        lo, hi = world.min(axis=(0, 1)), world.max(axis=(0, 1))
        assert np.all(c.point >= lo - 1e-12) and np.all(c.point <= hi + 1e-12)
        assert np.isclose(np.linalg.norm(c.normal), 1)
    # Models: the object's current mesh; the one given to add_object untouched.
    assert np.array_equal(manager.model("cloth").vertices, bent)
    assert np.array_equal(given.vertices, v)
    # Verdict and names only: the same answer without the data.
    assert manager.in_collision_internal() is True
    # Unfolded again: no self pair.
    manager.set_vertices("cloth", v)
    assert manager.in_collision_internal() is False


def test_pairs_with_deformed_objects_use_the_current_mesh():
    v, f = sheet()
    box = antcd.Model(*box_mesh((0.1, 0.1, 0.1)))
    manager = antcd.CollisionManager()
    manager.add_object("cloth", (v, f), pose([0, 0, 0.5]))
    manager.add_object("box", box)
    assert manager.in_collision_internal() is False
    low = v.copy()
    low[:, 2] = -0.5  # model frame: world z = 0, through the box
    manager.set_vertices("cloth", low)
    hit, names, data = manager.in_collision_internal(return_names=True, return_data=True)
    truth = antcd.collide(antcd.Model(low, f), pose([0, 0, 0.5]), box, None, all_contacts=True)
    assert hit and names == {("box", "cloth")}
    assert sorted((c.index("cloth"), c.index("box")) for c in data) == \
        sorted(zip(truth.triangles_a.tolist(), truth.triangles_b.tolist()))
    single = manager.in_collision_single(antcd.Model(low, f), pose([0, 0, 0.5]), return_names=True)
    assert single == (True, {"box", "cloth"})


def test_pins_follow_the_model_each_object_uses():
    v, f = sheet(4)
    given = antcd.Model(v, f)
    manager = antcd.CollisionManager()
    manager.add_object("cloth", given, self_collision=True)
    with pytest.raises(ValueError, match="held by a CollisionManager"):
        given.set_vertices(v)
    manager.set_vertices("cloth", v + [0, 0, 0.1])
    given.set_vertices(v * 2)  # no longer the object's: free again
    current = manager.model("cloth")
    assert current is not given and np.allclose(current.vertices, v + [0, 0, 0.1])
    with pytest.raises(ValueError, match="held by a CollisionManager"):
        current.set_vertices(v)  # the World's own copy
    manager.set_vertices("cloth", v + [0, 0, 0.2])  # `current` is held: copied, not refitted
    assert np.allclose(current.vertices, v + [0, 0, 0.1])
    current.set_vertices(v)  # dropped by the object, now the holder's
    assert np.allclose(manager.model("cloth").vertices, v + [0, 0, 0.2])
    manager.remove_object("cloth")
    with pytest.raises(ValueError, match="cloth not in collision manager"):
        manager.model("cloth")


def _interpolated(v0, p0, v1, p1, t):
    """World vertices of a deforming object at time t (world.hpp: linear in world space)."""
    w0 = v0 @ p0[:3, :3].T + p0[:3, 3]
    w1 = v1 @ p1[:3, :3].T + p1[:3, 3]
    return (1 - t) * w0 + t * w1


def test_sweep_motion_against_dense_substeps():
    """A waving cloth falls through a box while a sphere slides into a second box and a third
    object stays far away; a second cloth folds through itself. Every pair that 200 sub-steps
    of exact discrete tests (meshes built from the interpolated world vertices) find in contact
    is reported, with toi no later than the first sub-step in contact."""
    v, f = sheet(10)
    wave = v.copy()
    wave[:, 2] = 0.1 * np.sin(4 * v[:, 0]) * np.cos(3 * v[:, 1])
    sphere = antcd.Model(*sphere_mesh(0.2, 16, 8))
    box = antcd.Model(*box_mesh((0.2, 0.2, 0.2)))
    start = {"cloth": pose([0, 0, 0.6]), "box": pose([0, 0, 0]), "ball": pose([3, 0, 0]),
             "wall": pose([3.9, 0, 0]), "far": pose([20, 0, 0]), "fold": pose([0, 6, 0])}
    manager = antcd.CollisionManager()
    manager.add_object("cloth", (v, f), start["cloth"], self_collision=True)
    manager.add_object("box", box, start["box"])
    manager.add_object("ball", sphere, start["ball"])
    manager.add_object("wall", box, start["wall"])
    manager.add_object("far", box, start["far"])
    manager.add_object("fold", (v, f), start["fold"], self_collision=True)
    end_cloth, end_ball = pose([0.05, 0, -0.3]), pose([3.6, 0, 0])
    fold_end = folded(v, 0.25, 1.0)
    motions = manager.sweep_motion(poses={"cloth": end_cloth, "ball": end_ball},
                                   vertices={"cloth": wave, "fold": fold_end})
    reported = {m.names: m for m in motions}

    steps = 200
    first = {}
    for k in range(steps + 1):
        t = k / steps
        cloth = antcd.Model(_interpolated(v, start["cloth"], wave, end_cloth, t), f)
        fold = antcd.Model(_interpolated(v, start["fold"], fold_end, start["fold"], t), f)
        ball_pose = pose((1 - t) * start["ball"][:3, 3] + t * end_ball[:3, 3])
        checks = {("cloth", "box"): antcd.collide(cloth, None, box, start["box"]),
                  ("ball", "wall"): antcd.collide(sphere, ball_pose, box, start["wall"]),
                  ("cloth", "cloth"): bool(antcd.self_intersections(cloth, first_only=True)),
                  ("fold", "fold"): bool(antcd.self_intersections(fold, first_only=True))}
        for pair, touching in checks.items():
            if touching and pair not in first:
                first[pair] = t
    assert set(first) == {("cloth", "box"), ("ball", "wall"), ("fold", "fold")}
    for pair, t in first.items():
        assert pair in reported, f"{pair} missed (sub-steps: contact at t = {t})"
        assert reported[pair].toi <= t, pair
    assert not any("far" in names for names in reported)
    ball = reported[("ball", "wall")]
    assert ball.kind == "rigid_sweep" and ball.sweep.hit and ball.triangles is not None
    assert ball.toi == pytest.approx(5 / 6, abs=1e-5)  # surfaces 0.5 apart, closing 0.6 per unit
    cloth = reported[("cloth", "box")]
    assert cloth.kind == "deform" and cloth.primitive is not None and cloth.triangles is None
    # The manager is not changed by sweep_motion.
    assert np.array_equal(manager.model("cloth").vertices, v)
    assert manager.in_collision_internal() is False


def test_falling_sheet_toi_and_set_motion_continuous():
    """A flat sheet falls from z = 0.5 to z = -0.5 onto a box whose top is at z = 0.2: first
    contact at t = 0.3. set_motion_continuous applies the motion and returns the same records."""
    v, f = sheet(6)
    box = antcd.Model(*box_mesh((0.2, 0.2, 0.2)))
    manager = antcd.CollisionManager()
    manager.add_object("sheet", (v, f), pose([0, 0, 0.5]))
    manager.add_object("box", box)
    (m,) = manager.sweep_motion(vertices={"sheet": v - [0, 0, 1.0]})
    assert m.names == ("sheet", "box") and m.kind == "deform"
    assert 0.3 - 1e-5 <= m.toi <= 0.3 + 1e-12 and m.point[2] == pytest.approx(0.2, abs=1e-4)
    (s,) = manager.sweep_motion(vertices={"sheet": v - [0, 0, 1.0]}, min_separation=0.1)
    assert s.toi <= 0.2 + 1e-12 and s.toi == pytest.approx(0.2, abs=1e-4)
    # Half the fall (to world z = 0, through the box), the box shifted sideways: t = 0.6.
    (applied,) = manager.set_motion_continuous(vertices={"sheet": v - [0, 0, 0.5]},
                                               poses={"box": pose([0.05, 0, 0])})
    assert applied.names == m.names and 0.6 - 1e-5 <= applied.toi <= 0.6 + 1e-12
    assert np.array_equal(manager.model("sheet").vertices, v - [0, 0, 0.5])
    assert manager.in_collision_internal(return_names=True) == (True, {("box", "sheet")})
    probe = antcd.Model(*box_mesh((0.02, 0.02, 0.02)))  # inside the box at its new pose only
    assert manager.in_collision_single(probe, pose([0.23, 0, -0.1]), return_names=True) == \
        (True, {"box"})
    # Started in contact: toi 0, a start_contact record for a deforming object, a rigid sweep's
    # when nothing deforms.
    (again,) = manager.sweep_motion(vertices={"sheet": v - [0, 0, 0.5]})
    assert again.kind == "start_contact" and again.toi == 0 and again.triangles is not None
    (rigid,) = manager.sweep_motion()
    assert rigid.kind == "rigid_sweep" and rigid.toi == 0 and rigid.sweep.hit


def test_bad_input_names_the_argument_and_changes_nothing():
    v, f = sheet(4)
    manager = antcd.CollisionManager()
    manager.add_object("cloth", (v, f), self_collision=True)
    manager.add_object("box", antcd.Model(*box_mesh()), pose([3, 0, 0]))
    nan = v.copy()
    nan[2, 1] = np.nan
    cases = [
        (lambda: manager.set_vertices("nope", v), ValueError, "set_vertices: nope not in"),
        (lambda: manager.set_vertices("cloth", v[:5]), ValueError,
         r"vertices of 'cloth' has 5 rows, the model has 16"),
        (lambda: manager.set_vertices("cloth", v[:, :2]), ValueError,
         r"vertices of 'cloth' must have shape \(n, 3\)"),
        (lambda: manager.set_vertices("cloth", nan), ValueError, "vertices of 'cloth' has a non-finite"),
        (lambda: manager.sweep_motion(vertices={"nope": v}), ValueError,
         "sweep_motion: vertices: nope not in collision manager"),
        (lambda: manager.sweep_motion(poses={"nope": np.eye(4)}), ValueError,
         "sweep_motion: poses: nope not in collision manager"),
        (lambda: manager.sweep_motion(poses=[np.eye(4)]), TypeError,
         "sweep_motion: poses must be a dict"),
        (lambda: manager.sweep_motion(vertices={"cloth": v[:3]}), ValueError,
         r"sweep_motion: vertices\['cloth'\] has 3 rows"),
        (lambda: manager.sweep_motion(vertices={"cloth": nan}), ValueError,
         r"sweep_motion: vertices\['cloth'\] has a non-finite"),
        (lambda: manager.sweep_motion(vertices={"cloth": v * 1e151}), ValueError,
         r"sweep_motion: vertices\['cloth'\]\[0\] has a coordinate beyond"),
        (lambda: manager.sweep_motion(poses={"box": np.diag([2.0, 1, 1, 1])}), ValueError,
         r"sweep_motion: poses\['box'\].*orthonormal"),
        (lambda: manager.sweep_motion(min_separation=-1.0), ValueError,
         "sweep_motion: min_separation"),
        (lambda: manager.sweep_motion(time_tolerance=0.0), ValueError,
         "sweep_motion: time_tolerance"),
        (lambda: manager.sweep_motion(max_iterations=0), ValueError,
         "sweep_motion: max_iterations"),
        (lambda: manager.set_motion_continuous(poses={"box": pose([2, 0, 0])},
                                               vertices={"cloth": nan}), ValueError,
         r"set_motion_continuous: vertices\['cloth'\] has a non-finite"),
        (lambda: manager.add_object("bad", (v, f), rebuild_above=-1.0), ValueError,
         "rebuild_above"),
    ]
    for call, error, pattern in cases:
        with pytest.raises(error, match=pattern):
            call()
    assert np.array_equal(manager.model("cloth").vertices, v)
    assert manager.min_distance_internal() == pytest.approx(2.0)  # the box did not move
    assert "bad" not in manager and len(manager) == 2


def test_pickle_keeps_the_deformed_mesh_and_self_collision():
    import pickle
    v, f = sheet()
    manager = antcd.CollisionManager()
    manager.add_object("cloth", (v, f), self_collision=True, rebuild_above=2.0)
    manager.set_vertices("cloth", folded(v, 0.25, 1.0))
    copy = pickle.loads(pickle.dumps(manager))
    assert copy.in_collision_internal(return_names=True) == (True, {("cloth", "cloth")})
    assert np.array_equal(copy.model("cloth").vertices, manager.model("cloth").vertices)


def test_queries_while_another_thread_sets_vertices():
    """One thread alternates the cloth between flat and folded while this one queries: every
    answer is that of one of the two states, never a mix (self pairs, sweep records)."""
    v, f = sheet(12)
    bent = folded(v, 0.25, 1.0)
    manager = antcd.CollisionManager()
    manager.add_object("cloth", (v, f), self_collision=True)
    manager.add_object("box", antcd.Model(*box_mesh((0.1, 0.1, 0.1))), pose([0, 0, -0.6]))
    states = {}
    for name, verts in (("flat", v), ("bent", bent)):
        manager.set_vertices("cloth", verts)
        hit, data = manager.in_collision_internal(return_data=True)
        states[name] = (hit, _self_pairs(data, "cloth"))
    assert states["flat"] != states["bent"]
    fall = {"cloth": v - [0, 0, 1.0]}
    manager.set_vertices("cloth", v)
    flat_sweep = [(m.names, m.kind, m.toi) for m in manager.sweep_motion(vertices=fall)]
    stop = threading.Event()
    errors, sets = [], [0]

    def setter():
        while not stop.is_set():
            manager.set_vertices("cloth", bent if sets[0] % 2 == 0 else v)
            sets[0] += 1

    thread = threading.Thread(target=setter)
    thread.start()
    try:
        for _ in range(150):
            hit, data = manager.in_collision_internal(return_data=True)
            if (hit, _self_pairs(data, "cloth")) not in states.values():
                errors.append((hit, len(data)))
            records = manager.sweep_motion(vertices=fall)
            got = [(m.names, m.kind, m.toi) for m in records]
            # Folded: the self pair at t = 0 comes first; flat: exactly the flat answer.
            if got != flat_sweep and not (got and got[0][:2] == (("cloth", "cloth"), "start_contact")):
                errors.append(got)
    finally:
        stop.set()
        thread.join()
    assert not errors and sets[0] > 10
