"""antcd.deform_sweep and antcd.collision_free_step (deforming continuous collision): hand-made
motions with a known time of impact, agreement with the C++ CLI (`antcd deform-ccd --json`), a
dense sub-stepping oracle made of exact discrete tests (self_intersections), bad input refused
with a ValueError/TypeError naming the argument, and a Model whose vertices another thread sets."""
import json
import threading

import numpy as np
import pytest

import antcd
from conftest import run_cli
from test_self import alpha_sheet, write_obj

TOL = 1e-6

# Triangle 0 lies still in z = 0; triangle 1 stands in the plane y = 0.2 above its interior, and
# only its vertex 3 moves: from z = 1 down to z = -1, through triangle 0 at t = 0.5 (its edges from
# vertex 3 pierce triangle 0's interior only later, far from triangle 0's edges).
CROSS_V0 = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0],
                     [0.2, 0.2, 1], [0.2, 0.2, 5], [0.3, 0.2, 5]], dtype=np.float64)
CROSS_FACES = np.array([[0, 1, 2], [3, 4, 5]], dtype=np.int64)


def crossing(end_z=-1.0):
    v1 = CROSS_V0.copy()
    v1[3, 2] = end_z
    return CROSS_V0.copy(), v1


def assert_toi_near(toi, t_star, tol=TOL):
    """Conservative (toi <= t*) and within the time tolerance (plus a little rounding)."""
    assert toi <= t_star
    assert t_star - toi <= tol + 1e-12


def test_self_vertex_through_triangle_at_half():
    v0, v1 = crossing()
    m = antcd.Model(v0, CROSS_FACES, name="crossing")
    r = antcd.deform_sweep(m, v0, v1)
    assert r and r.hit
    assert_toi_near(r.toi, 0.5)
    assert r.pair.kind == "vertex_face"
    assert r.pair.indices == (3, 0)
    assert r.pair.toi == r.toi
    assert r.pairs == []  # the earliest pair only without all_pairs
    assert r.primitive_queries > 0 and r.tasks >= 1 and r.scratch_bytes > 0
    every = antcd.deform_sweep(m, v0, v1, all_pairs=True)
    assert [(p.kind, p.indices) for p in every.pairs] == [("vertex_face", (3, 0))]
    assert every.pairs[0].toi == r.toi
    assert "hit=True" in repr(r) and "vertex_face" in repr(r.pair)


def test_self_miss_and_min_separation():
    v0, v1 = crossing(end_z=0.1)  # stops 0.1 above triangle 0
    m = antcd.Model(v0, CROSS_FACES)
    r = antcd.deform_sweep(m, v0, v1)
    assert not r and r.toi == 1.0 and r.pair is None
    assert antcd.collision_free_step(m, v0, v1, 0.0) == 1.0
    # Within 0.2 of triangle 0 when z = 1 - 0.9 t <= 0.2: t* = 8 / 9.
    r = antcd.deform_sweep(m, v0, v1, min_separation=0.2)
    assert r.hit
    assert_toi_near(r.toi, 8 / 9)
    step = antcd.collision_free_step(m, v0, v1, 0.2)
    assert step == r.toi
    # A coarser tolerance may give an earlier step, never a later one.
    coarse = antcd.collision_free_step(m, v0, v1, 0.2, time_tolerance=1e-2)
    assert_toi_near(coarse, 8 / 9, 1e-2)


def test_two_deforming_meshes_and_a_rigid_one():
    v0, v1 = crossing()
    a = antcd.Model(v0[3:], [[0, 1, 2]], name="mover")
    b = antcd.Model(v0[:3], [[0, 1, 2]], name="floor")
    r = antcd.deform_sweep(a, v0[3:], v1[3:], b, v0[:3], v1[:3])
    assert r.hit
    assert_toi_near(r.toi, 0.5)
    assert (r.pair.kind, r.pair.indices, r.pair.vertex_in_first) == ("vertex_face", (0, 0), True)
    # The same with the roles swapped: the vertex is now the second mesh's.
    s = antcd.deform_sweep(b, v0[:3], v1[:3], a, v0[3:], v1[3:])
    assert (s.pair.indices, s.pair.vertex_in_first) == ((0, 0), False)
    assert s.toi == r.toi
    # Rigid floor rising from z = 0 to z = 1 under a still vertex at z = 0.5: contact at t = 0.5.
    still = v0[3:].copy()
    still[0, 2] = 0.5
    lift = np.eye(4)
    lift[2, 3] = 1.0
    r = antcd.deform_sweep(a, still, still, b, pose_b0=np.eye(4), pose_b1=lift)
    assert r.hit
    assert_toi_near(r.toi, 0.5)
    assert r.pair.indices == (0, 0) and r.pair.vertex_in_first
    # Lifted only to z = 0.4: a miss (a proof).
    low = np.eye(4)
    low[2, 3] = 0.4
    assert not antcd.deform_sweep(a, still, still, b, pose_b0=np.eye(4), pose_b1=(np.eye(3), [0, 0, 0.4]))
    assert not antcd.deform_sweep(a, still, still, b, pose_b0=np.eye(4), pose_b1=low)
    # None marks a pose as not given (here it is not the identity, as in sweep()).
    with pytest.raises(ValueError, match="pose_b0 is missing"):
        antcd.deform_sweep(a, still, still, b, pose_b0=None, pose_b1=low)


def test_rigid_turning_model_hits_are_tolerance_decided():
    # The floor turns a quarter turn about the x axis (through its vertex 0) while a vertex sits at
    # (0.2, 0.2, 0.5): the floor's point (0.2, y, 0) goes to (0.2, y cos th, y sin th) and meets
    # the vertex when tan th = 2.5, th* = atan2(0.5, 0.2) of the quarter turn.
    a = antcd.Model(CROSS_V0[3:] - [0, 0, 0.5], [[0, 1, 2]])
    b = antcd.Model(CROSS_V0[:3], [[0, 1, 2]])
    quarter = np.array([[1.0, 0, 0, 0], [0, 0, -1, 0], [0, 1, 0, 0], [0, 0, 0, 1]])
    pos = a.vertices.copy()
    r = antcd.deform_sweep(a, pos, pos, b, pose_b0=np.eye(4), pose_b1=quarter)
    assert r.hit and r.tolerance_decided
    t_star = np.arctan2(0.5, 0.2) / (np.pi / 2)
    # A hit means within 2 delta (delta = 1e-3 of the floor's radius) of the vertex: a little
    # early, never late.
    assert t_star - 0.01 < r.toi <= t_star
    # Turning the other way the floor never reaches it.
    back = quarter.copy()
    back[1, 2], back[2, 1] = 1.0, -1.0
    assert not antcd.deform_sweep(a, pos, pos, b, pose_b0=np.eye(4), pose_b1=back)


def first_use_order(v0, v1, faces):
    """The mesh renumbered so that vertices come in order of first use by the faces, as the CLI's
    loader numbers them: then its indices and ours are the same."""
    order = {}
    for k in np.asarray(faces).ravel():
        order.setdefault(int(k), len(order))
    old = np.array(sorted(order, key=order.get))
    remap = np.empty(len(v0), dtype=np.int64)
    remap[old] = np.arange(len(old))
    return v0[old], v1[old], remap[np.asarray(faces)]


def cli_answer(cli, tmp_path, v0, v1, faces, *args):
    p0, p1 = tmp_path / "t0.obj", tmp_path / "t1.obj"
    write_obj(p0, v0, faces)
    write_obj(p1, v1, faces)
    return json.loads(run_cli(cli, "deform-ccd", str(p0), str(p1), "--json", *args))


def as_cli_lists(r):
    vf = [[p.indices[0], p.indices[1], p.toi] for p in r.pairs if p.kind == "vertex_face"]
    ee = [[*p.indices, p.toi] for p in r.pairs if p.kind == "edge_edge"]
    return vf, ee


@pytest.mark.parametrize("case", ["fold", "fold_separation", "crossing", "flat_shift"])
def test_deform_sweep_equals_the_cli(tmp_path, cli, case):
    args = []
    kwargs = {}
    if case == "fold":
        v0, f = alpha_sheet(15, 4, folded=False)
        v1, _ = alpha_sheet(15, 4, folded=True)
    elif case == "fold_separation":  # many pairs within the separation: a smaller sheet
        v0, f = alpha_sheet(9, 3, folded=False)
        v1, _ = alpha_sheet(9, 3, folded=True)
        args, kwargs = ["--min-separation", "0.05"], {"min_separation": 0.05}
    elif case == "crossing":
        (v0, v1), f = crossing(), CROSS_FACES
    else:  # a flat sheet sliding in its plane: a miss
        v0, f = alpha_sheet(15, 4, folded=False)
        v1 = v0 + [0.3, -0.1, 0.0]
    v0, v1, f = first_use_order(v0, v1, f)
    j = cli_answer(cli, tmp_path, v0, v1, f, "--all-pairs", *args)
    m = antcd.Model(v0, f)
    r = antcd.deform_sweep(m, v0, v1, all_pairs=True, **kwargs)
    assert r.hit == j["hit"]
    assert r.toi == j["toi"]
    assert r.tolerance_decided == j["tolerance_decided"]
    vf, ee = as_cli_lists(r)
    assert vf == j["vertex_face"]
    assert ee == j["edge_edge"]
    assert r.hit == (case != "flat_shift")
    # First-hit mode gives all_pairs' first entry.
    one = antcd.deform_sweep(m, v0, v1, **kwargs)
    assert one.hit == r.hit and one.toi == r.toi
    if r.hit:
        first = r.pairs[0]
        assert (one.pair.kind, one.pair.indices, one.pair.toi) == (first.kind, first.indices, first.toi)


def test_dense_substeps_never_meet_before_toi():
    """The flat sheet folding through itself: the exact discrete test at 60 sub-steps finds an
    intersection at some step; the sweep's toi is no later, and every step before toi is free."""
    v0, f = alpha_sheet(15, 4, folded=False)
    v1, _ = alpha_sheet(15, 4, folded=True)
    m = antcd.Model(v0, f)
    r = antcd.deform_sweep(m, v0, v1)
    assert r.hit
    probe = antcd.Model(v0, f)
    first = None
    for k in range(61):
        t = k / 60
        probe.set_vertices(v0 + t * (v1 - v0))
        if antcd.self_intersections(probe, first_only=True):
            first = t
            break
    assert first is not None, "the folded sheet intersects itself"
    assert r.toi <= first
    assert antcd.collision_free_step(m, v0, v1, 0.0) <= first


def _model():
    v0, v1 = crossing()
    return antcd.Model(v0, CROSS_FACES, name="crossing"), v0, v1


@pytest.mark.parametrize("arg, make, message", [
    ("a0", lambda v: v[:, :2], r"a0 must have shape \(n, 3\)"),
    ("a1", lambda v: v[:-1], r"a1 has 5 rows, the model has 6 vertices"),
    ("a1", lambda v: np.where(v == 5, np.nan, v), r"a1 has a non-finite entry"),
    ("a0", lambda v: v * 1e151, r"a0\[1\] has a coordinate beyond the deforming sweep's range"),
    ("a1", lambda v: v.astype(bool), r"a1 must hold real numbers"),
    ("a0", lambda v: None, r"a0 must be an array, got None"),
])
def test_bad_positions_name_the_argument(arg, make, message):
    m, v0, v1 = _model()
    given = {"a0": v0, "a1": v1}
    given[arg] = make(given[arg])
    with pytest.raises(ValueError, match=message):
        antcd.deform_sweep(m, given["a0"], given["a1"])
    with pytest.raises(ValueError, match=message.replace("a0", "v0").replace("a1", "v1")):
        antcd.collision_free_step(m, given["a0"], given["a1"], 0.0)


def test_bad_options_and_forms():
    m, v0, v1 = _model()
    b = antcd.Model(v0[:3], [[0, 1, 2]])
    with pytest.raises(ValueError, match="min_separation must be a finite number >= 0"):
        antcd.deform_sweep(m, v0, v1, min_separation=-1)
    with pytest.raises(ValueError, match="min_separation"):
        antcd.collision_free_step(m, v0, v1, float("nan"))
    with pytest.raises(ValueError, match="time_tolerance must be finite and > 0"):
        antcd.deform_sweep(m, v0, v1, time_tolerance=0)
    with pytest.raises(ValueError, match="pose_path_tolerance"):
        antcd.deform_sweep(m, v0, v1, b, pose_b0=np.eye(4), pose_b1=np.eye(4), pose_path_tolerance=-1)
    with pytest.raises(ValueError, match="need a second model b"):
        antcd.deform_sweep(m, v0, v1, None, v0, v1)
    with pytest.raises(ValueError, match="not both"):
        antcd.deform_sweep(m, v0, v1, b, v0[:3], v1[:3], pose_b0=np.eye(4), pose_b1=np.eye(4))
    with pytest.raises(ValueError, match="not neither"):
        antcd.deform_sweep(m, v0, v1, b)
    with pytest.raises(ValueError, match="b1 is missing"):
        antcd.deform_sweep(m, v0, v1, b, v0[:3])
    with pytest.raises(ValueError, match="pose_b0 is missing"):
        antcd.deform_sweep(m, v0, v1, b, pose_b1=np.eye(4))
    with pytest.raises(ValueError, match="b0 has 6 rows, the model has 3 vertices"):
        antcd.deform_sweep(m, v0, v1, b, v0, v1[:3])
    with pytest.raises(ValueError, match="b1 has a non-finite entry"):
        antcd.deform_sweep(m, v0, v1, b, v0[:3], np.full((3, 3), np.inf))
    bad_pose = np.eye(4)
    bad_pose[0, 0] = 2.0
    with pytest.raises(ValueError, match="pose_b1"):
        antcd.deform_sweep(m, v0, v1, b, pose_b0=np.eye(4), pose_b1=bad_pose)
    with pytest.raises(TypeError, match="b must be an antcd.Model"):
        antcd.deform_sweep(m, v0, v1, "floor", v0[:3], v1[:3])
    with pytest.raises(TypeError):
        antcd.deform_sweep("model", v0, v1)


@pytest.mark.parametrize("far", [1e140, 1e155, 1e300])
def test_huge_rigid_motion_is_refused_or_hit_never_missed(far):
    """A rigid floor passing from x = -far to x = +far through a vertex in its plane (issue 41):
    the contact at t = 0.5 - 0.3 / far is found or the input is refused with a ValueError, never
    answered with a miss."""
    still = CROSS_V0[3:] - [0, 0, 1]  # the mover's vertex 0 at (0.2, 0.2, 0): on the floor's path
    a = antcd.Model(still, [[0, 1, 2]])
    b = antcd.Model(CROSS_V0[:3], [[0, 1, 2]])
    p0, p1 = np.eye(4), np.eye(4)
    p0[0, 3], p1[0, 3] = -far, far
    try:
        r = antcd.deform_sweep(a, still, still, b, pose_b0=p0, pose_b1=p1)
    except ValueError as e:
        assert "pose_b" in str(e)
        return
    assert r.hit, f"a proven miss for a contact at t = 0.5 (translation +-{far:g})"
    assert r.toi <= 0.5


def test_queries_while_another_thread_sets_the_vertices():
    """deform_sweep reads only the model's triangles and hierarchy; set_vertices refits it under
    the exclusive lock. Every query answers as the reference, however the two interleave."""
    v0, f = alpha_sheet(21, 6, folded=False)
    v1, _ = alpha_sheet(21, 6, folded=True)
    m = antcd.Model(v0, f)
    ref = antcd.deform_sweep(m, v0, v1, all_pairs=True)
    ref_pairs = [(p.kind, p.indices, p.toi) for p in ref.pairs]
    stop = threading.Event()
    errors = []

    def flip():
        try:
            k = 0
            while not stop.is_set():
                m.set_vertices(v1 if k % 2 else v0)
                k += 1
        except Exception as e:  # noqa: BLE001  (reported below)
            errors.append(e)

    writer = threading.Thread(target=flip)
    writer.start()
    try:
        for _ in range(20):
            r = antcd.deform_sweep(m, v0, v1, all_pairs=True)
            assert [(p.kind, p.indices, p.toi) for p in r.pairs] == ref_pairs
            assert antcd.collision_free_step(m, v0, v1, 0.0) == ref.toi
    finally:
        stop.set()
        writer.join()
    assert not errors
