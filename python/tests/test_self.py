"""antcd.self_intersections, antcd.self_proximity and Model.set_vertices: the answers equal the
C++ CLI's (itself checked against CGAL in the C++ suite) or brute force, bad input leaves the model
as it was, and threads querying a Model while another sets its vertices see one state or the
other."""
import itertools
import json
import threading

import numpy as np
import pytest

import antcd
from conftest import box_mesh, run_cli, sphere_mesh


def grid_faces(nx, ny):
    """Triangles of an nx x ny vertex grid (vertex i * ny + j), two per cell."""
    faces = []
    for i in range(nx - 1):
        for j in range(ny - 1):
            a, b, c, d = i * ny + j, (i + 1) * ny + j, (i + 1) * ny + j + 1, i * ny + j + 1
            faces += [[a, b, c], [a, c, d]]
    return np.array(faces, dtype=np.int64)


def alpha_sheet(nx, ny, folded=True):
    """A strip whose cross-section is the curve (t^2 - 1, t^3 - t), t in [-1.3, 1.25], extruded
    along y: it passes through itself along a line near x = z = 0 (t = -1 and t = 1 meet there, off
    the grid's sample points). folded=False: the same grid laid flat in the plane z = 0."""
    t = np.linspace(-1.3, 1.25, nx)
    y = np.linspace(0.0, 1.0, ny)
    tt, yy = np.meshgrid(t, y, indexing="ij")
    if folded:
        v = np.stack([tt**2 - 1, yy, tt**3 - tt], axis=-1)
    else:
        v = np.stack([tt, yy, np.zeros_like(tt)], axis=-1)
    return v.reshape(-1, 3).astype(np.float64), grid_faces(nx, ny)


def write_obj(path, v, f):
    with open(path, "w") as out:
        for p in v:
            out.write("v %.17g %.17g %.17g\n" % tuple(p))
        for t in f:
            out.write("f %d %d %d\n" % tuple(int(k) + 1 for k in t))


def cli_pairs(cli, path):
    j = json.loads(run_cli(cli, "self-intersect", str(path), "--json"))
    return np.array(j["pairs"], dtype=np.int64).reshape(-1, 2), j


@pytest.mark.parametrize("case", ["alpha", "box", "box_duplicate_face", "crossed_spheres"])
def test_self_intersections_equal_the_cli(tmp_path, cli, case):
    if case == "alpha":
        v, f = alpha_sheet(23, 5)
    elif case.startswith("box"):
        v, f = box_mesh()
        if case == "box_duplicate_face":
            f = np.vstack([f, f[4:5]])
    else:  # two spheres in one mesh (a soup of two shells), one pushed into the other
        va, fa = sphere_mesh(1.0, 16, 8)
        vb, fb = sphere_mesh(0.7, 12, 6)
        v = np.vstack([va, vb + [0.9, 0.05, 0.02]])
        f = np.vstack([fa, fb + len(va)])
    path = tmp_path / "mesh.obj"
    write_obj(path, v, f)
    expected, j = cli_pairs(cli, path)
    m = antcd.Model(v, f)
    r = antcd.self_intersections(m)
    assert r.pairs.dtype == np.uint32 and r.pairs.shape == (len(expected), 2)
    np.testing.assert_array_equal(r.pairs, expected)
    assert len(r) == j["count"] and bool(r) == (j["count"] > 0) and r.intersecting == bool(r)
    np.testing.assert_array_equal(r.degenerate_triangles, j["degenerate_triangles"])
    if case == "box":
        assert len(r) == 0
    if case == "box_duplicate_face":
        np.testing.assert_array_equal(r.pairs, [[4, 12]])
    if case in ("alpha", "crossed_spheres"):
        assert len(r) > 0
    # The normal-cone cull changes the cost, never the pairs; first_only gives one of the pairs.
    np.testing.assert_array_equal(antcd.self_intersections(m, normal_cones=False).pairs, r.pairs)
    first = antcd.self_intersections(m, first_only=True)
    assert len(first) == min(1, len(r))
    if len(r):
        assert any((first.pairs[0] == p).all() for p in r.pairs)
    assert set(r.stats) == {"node_pairs", "volume_rejects", "triangle_pairs", "adjacent_pairs",
                            "cone_culled", "cone_tests", "cone_cache_bytes"}


def test_degenerate_triangle_is_listed_and_in_no_pair():
    v, f = box_mesh()
    v = np.vstack([v, [[0.0, 0.0, -1.0], [0.0, 0.0, 1.0]]])
    f = np.vstack([f, [[8, 9, 9]]])  # a zero-area needle through the box
    r = antcd.self_intersections(antcd.Model(v, f))
    np.testing.assert_array_equal(r.degenerate_triangles, [12])
    assert len(r) == 0


# ---- self_proximity against brute force ----

def closest_on_triangle(p, a, b, c):
    """Closest point of triangle abc to p (Ericson, Real-Time Collision Detection 5.1.5)."""
    ab, ac, ap = b - a, c - a, p - a
    d1, d2 = ab @ ap, ac @ ap
    if d1 <= 0 and d2 <= 0:
        return a
    bp = p - b
    d3, d4 = ab @ bp, ac @ bp
    if d3 >= 0 and d4 <= d3:
        return b
    vc = d1 * d4 - d3 * d2
    if vc <= 0 and d1 >= 0 and d3 <= 0:
        return a + d1 / (d1 - d3) * ab
    cp = p - c
    d5, d6 = ab @ cp, ac @ cp
    if d6 >= 0 and d5 <= d6:
        return c
    vb = d5 * d2 - d1 * d6
    if vb <= 0 and d2 >= 0 and d6 <= 0:
        return a + d2 / (d2 - d6) * ac
    va = d3 * d6 - d5 * d4
    if va <= 0 and (d4 - d3) >= 0 and (d5 - d6) >= 0:
        return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b)
    denom = 1.0 / (va + vb + vc)
    return a + ab * (vb * denom) + ac * (vc * denom)


def segment_distance(p1, q1, p2, q2):
    """Distance between segments p1q1 and p2q2 (Ericson 5.1.9, non-degenerate segments)."""
    d1, d2, r = q1 - p1, q2 - p2, p1 - p2
    a, e, f = d1 @ d1, d2 @ d2, d2 @ r
    c, b = d1 @ r, d1 @ d2
    denom = a * e - b * b
    s = np.clip((b * f - c * e) / denom, 0, 1) if denom > 0 else 0.0
    t = (b * s + f) / e
    if t < 0:
        t, s = 0.0, np.clip(-c / a, 0, 1)
    elif t > 1:
        t, s = 1.0, np.clip((b - c) / a, 0, 1)
    return np.linalg.norm((p1 + d1 * s) - (p2 + d2 * t))


def test_self_proximity_equals_brute_force():
    v, f = alpha_sheet(9, 3)
    delta = 0.35
    m = antcd.Model(v, f)
    r = antcd.self_proximity(m, delta)
    edges = sorted({tuple(sorted((int(t[i]), int(t[(i + 1) % 3])))) for t in f for i in range(3)})
    np.testing.assert_array_equal(r.edges, edges)

    vt = {}
    for vi, p in enumerate(v):
        for ti, t in enumerate(f):
            if vi in t:
                continue
            d = np.linalg.norm(p - closest_on_triangle(p, *v[t]))
            assert abs(d - delta) > 1e-9, "the brute force must not sit on the threshold"
            if d <= delta:
                vt[(vi, ti)] = d
    ee = {}
    for (ia, ea), (ib, eb) in itertools.combinations(enumerate(edges), 2):
        if set(ea) & set(eb):
            continue
        d = segment_distance(v[ea[0]], v[ea[1]], v[eb[0]], v[eb[1]])
        assert abs(d - delta) > 1e-9
        if d <= delta:
            ee[(ia, ib)] = d
    assert len(vt) > 0 and len(ee) > 0 and len(r) == len(vt) + len(ee)

    np.testing.assert_array_equal(r.vertex_triangle_pairs, sorted(vt))
    np.testing.assert_allclose(r.vertex_triangle_distances, [vt[k] for k in sorted(vt)], atol=1e-12)
    np.testing.assert_array_equal(r.edge_edge_pairs, sorted(ee))
    np.testing.assert_allclose(r.edge_edge_distances, [ee[k] for k in sorted(ee)], atol=1e-12)
    # Closest points: on their primitive, at the reported distance.
    pv = v[r.vertex_triangle_pairs[:, 0]]
    np.testing.assert_allclose(np.linalg.norm(pv - r.vertex_triangle_points, axis=1),
                               r.vertex_triangle_distances, atol=1e-12)
    np.testing.assert_allclose(np.linalg.norm(r.edge_edge_points_a - r.edge_edge_points_b, axis=1),
                               r.edge_edge_distances, atol=1e-12)


@pytest.mark.parametrize("delta", [-1.0, float("nan"), float("inf")])
def test_self_proximity_bad_delta(delta):
    m = antcd.Model(*box_mesh())
    with pytest.raises(ValueError, match="delta"):
        antcd.self_proximity(m, delta)


# ---- set_vertices ----

def test_set_vertices_answers_as_a_fresh_model():
    flat, f = alpha_sheet(23, 5, folded=False)
    folded, _ = alpha_sheet(23, 5)
    m = antcd.Model(flat, f)
    assert len(antcd.self_intersections(m)) == 0 and m.refit_growth == 1.0
    view = m.vertices
    assert m.set_vertices(folded) is None
    np.testing.assert_array_equal(m.vertices, folded)
    np.testing.assert_array_equal(view, folded)  # the view shows the storage set_vertices wrote
    fresh = antcd.Model(folded, f)
    np.testing.assert_array_equal(antcd.self_intersections(m).pairs,
                                  antcd.self_intersections(fresh).pairs)
    np.testing.assert_array_equal(m.bounds, fresh.bounds)
    probe = antcd.Model(*sphere_mesh(0.2, 12, 6))
    pose = (np.eye(3), [0.0, 0.5, 0.1])
    a, b = antcd.collide(m, None, probe, pose, all_contacts=True), antcd.collide(fresh, None, probe, pose, all_contacts=True)
    assert a.colliding and a.colliding == b.colliding
    assert sorted(zip(a.triangles_a, a.triangles_b)) == sorted(zip(b.triangles_a, b.triangles_b))
    assert antcd.distance(m, None, probe, (np.eye(3), [3.0, 0.5, 0])).distance == \
        antcd.distance(fresh, None, probe, (np.eye(3), [3.0, 0.5, 0])).distance
    assert m.refit_growth > 0
    # Lists and float32 are accepted (copied as float64).
    m.set_vertices(flat.astype(np.float32).tolist())
    assert len(antcd.self_intersections(m)) == 0


@pytest.mark.parametrize("make, message", [
    (lambda v: v[:, :2], r"vertices must have shape \(n, 3\)"),
    (lambda v: v.ravel(), r"vertices must have shape \(n, 3\)"),
    (lambda v: v[:-1], "vertices has 7 rows, the model has 8 vertices"),
    (lambda v: np.vstack([v, v[:1]]), "vertices has 9 rows, the model has 8 vertices"),
    (lambda v: np.where(np.arange(24).reshape(8, 3) == 5, np.nan, v), "vertices has a non-finite entry"),
    (lambda v: v * np.inf, "vertices has a non-finite entry"),
    (lambda v: v.astype(bool), "vertices must hold real numbers"),
    (lambda v: None, "vertices must be an array"),
    (lambda v: "abc", "vertices"),
])
def test_set_vertices_bad_input_keeps_the_model(make, message):
    v, f = box_mesh()
    m = antcd.Model(v, f, name="box")
    before = np.array(m.vertices)
    with pytest.raises(ValueError, match=message):
        m.set_vertices(make(v + 0.25))
    np.testing.assert_array_equal(m.vertices, before)
    assert antcd.collide(m, None, m, (np.eye(3), [0.99, 0, 0]))


def test_set_vertices_refuses_a_triangle_that_gains_an_area():
    v, f = box_mesh()
    v = np.vstack([v, [[0.0, 0.0, 2.0], [0.0, 0.0, 3.0], [0.0, 0.0, 4.0]]])
    f = np.vstack([f, [[8, 9, 10]]])  # collinear: out of the hierarchy
    m = antcd.Model(v, f, name="needle")
    moved = v.copy()
    moved[10] = [1.0, 0.0, 4.0]
    with pytest.raises(ValueError, match="needle.*triangle 12 had zero area"):
        m.set_vertices(moved)
    np.testing.assert_array_equal(m.vertices, v)


def test_set_vertices_refuses_a_model_held_by_a_manager():
    v, f = box_mesh()
    m = antcd.Model(v, f, name="held")
    manager = antcd.CollisionManager()
    manager.add_object("a", m)
    manager.add_object("b", m)
    with pytest.raises(ValueError, match="'held' is held by a CollisionManager"):
        m.set_vertices(v * 2)
    np.testing.assert_array_equal(m.vertices, v)
    manager.remove_object("a")
    with pytest.raises(ValueError, match="held by a CollisionManager"):
        m.set_vertices(v * 2)  # still in "b"
    manager.remove_object("b")
    m.set_vertices(v * 2)
    np.testing.assert_array_equal(m.vertices, v * 2)
    other = antcd.CollisionManager()
    other.add_object("c", m)
    del other  # a manager that goes away lets its models go
    import gc
    gc.collect()
    m.set_vertices(v)


def test_set_vertices_refuses_a_scene_model(tmp_path):
    v, f = box_mesh()
    write_obj(tmp_path / "box.obj", v, f)
    (tmp_path / "scene.json").write_text(json.dumps({
        "format": "antcd-scene/1", "frames": 1,
        "objects": [{"name": "a", "mesh": "box.obj", "poses": [{"translation": [0, 0, 0]}]}]}))
    scene = antcd.Scene(tmp_path / "scene.json")
    with pytest.raises(ValueError, match="held by a CollisionManager or a Scene"):
        scene.model(0).set_vertices(v * 2)


def test_set_vertices_releases_the_gil():
    """Another Python thread runs while set_vertices refits a large model."""
    v, f = sphere_mesh(1.0, 400, 200)
    m = antcd.Model(v, f)
    ticks = []
    done = threading.Event()

    def refit_many():
        for k in range(6):
            m.set_vertices(v * (1.0 + 0.01 * k))
        done.set()

    for _ in range(3):  # a loaded machine may park this thread: up to three tries
        done.clear()
        ticks.clear()
        thread = threading.Thread(target=refit_many)
        thread.start()
        while not done.is_set():
            ticks.append(1)
        thread.join()
        if len(ticks) > 1000:
            return
    pytest.fail(f"this thread hardly ran during set_vertices: {len(ticks)} iterations")


def test_queries_never_see_a_torn_model():
    """One thread flips a Model between a flat and a folded sheet while others query it: every
    answer is that of one state or the other."""
    flat, f = alpha_sheet(160, 60, folded=False)
    folded, _ = alpha_sheet(160, 60)
    m = antcd.Model(flat, f)
    probe = antcd.Model(*sphere_mesh(0.1, 10, 5))
    probe_pose = (np.eye(3), [0.0, 0.5, 2.0])
    states = {}
    for name, vertices in (("flat", flat), ("folded", folded)):
        ref = antcd.Model(vertices, f)
        states[name] = (antcd.self_intersections(ref).pairs.tobytes(),
                        antcd.distance(ref, None, probe, probe_pose).distance)
    assert states["flat"][0] == b"" and states["folded"][0] != b""
    stop = threading.Event()
    flips = [0]

    def flipper():
        while not stop.is_set():
            m.set_vertices(folded if flips[0] % 2 == 0 else flat)
            flips[0] += 1

    bad = []
    seen = set()

    def querier():
        for _ in range(40):
            pairs = antcd.self_intersections(m).pairs.tobytes()
            d = antcd.distance(m, None, probe, probe_pose).distance
            kinds = {name for name, (p, _) in states.items() if p == pairs}
            if not kinds:
                bad.append(("pairs", len(pairs)))
            seen.update(kinds)
            if d not in (states["flat"][1], states["folded"][1]):
                bad.append(("distance", d))

    thread = threading.Thread(target=flipper)
    thread.start()
    queriers = [threading.Thread(target=querier) for _ in range(2)]
    try:
        for q in queriers:
            q.start()
        for q in queriers:
            q.join()
    finally:
        stop.set()
        thread.join()
    assert not bad, bad[:5]
    assert flips[0] >= 2 and seen == {"flat", "folded"}, (flips[0], seen)


def test_set_vertices_with_manager_queries_and_adds_does_not_deadlock():
    """One thread queries a manager's world with a free Model, one adds that Model to it and
    removes it again, one calls set_vertices on it (refused while it is held): the three lock
    orders must not close a cycle. Every thread finishes. (The engine under CollisionManager,
    antcd._antcd._World, is driven directly: the manager's name table is not what is tested.)"""
    v, f = sphere_mesh(0.5, 40, 20)
    m = antcd.Model(v, f, name="shared")
    world = antcd._antcd._World()
    world.add(antcd.Model(*box_mesh()), None)
    stop = threading.Event()
    counts = {"query": 0, "add": 0, "set": 0, "refused": 0}

    def query():
        while not stop.is_set():
            world.collide_single(m, (np.eye(3), [0.3, 0, 0]), "verdict")
            counts["query"] += 1

    def add_remove():
        while not stop.is_set():
            world.remove(world.add(m, None))
            counts["add"] += 1

    def set_vertices():
        while not stop.is_set():
            try:
                m.set_vertices(v)
                counts["set"] += 1
            except ValueError:
                counts["refused"] += 1

    threads = [threading.Thread(target=t, daemon=True) for t in (query, add_remove, set_vertices)]
    for t in threads:
        t.start()
    stop.wait(2.0)
    stop.set()
    for t in threads:
        t.join(timeout=30)
    assert not any(t.is_alive() for t in threads), f"a thread is stuck: {counts}"
    assert counts["query"] > 0 and counts["add"] > 0 and counts["set"] > 0 and counts["refused"] > 0, counts
