"""collide_batch() / distance_batch(): entry i equals the single query under pose pair i, for any
thread count, with broadcast single poses; bad batches raise ValueError naming the argument.
Throughput against a Python loop is measured by python/bench/batch.py, not asserted here."""
import numpy as np
import pytest

import antcd
from conftest import box_mesh, random_pose, sphere_mesh


@pytest.fixture(scope="module")
def pair():
    return antcd.Model(*sphere_mesh(1.0, 16, 8)), antcd.Model(*box_mesh((0.4, 0.3, 0.2)))


def _batch(rng, count, extent=2.0):
    return np.stack([random_pose(rng, extent) for _ in range(count)])


def test_collide_batch_equals_single_queries(pair):
    a, b = pair
    rng = np.random.default_rng(7)
    poses_a, poses_b = _batch(rng, 300), _batch(rng, 300)
    expected = np.array([antcd.collide(a, pa, b, pb).colliding for pa, pb in zip(poses_a, poses_b)])
    assert 20 < expected.sum() < 280  # both verdicts occur
    for threads in (0, 1, 3):
        got = antcd.collide_batch(a, b, poses_a, poses_b, threads=threads)
        assert got.dtype == np.bool_ and got.shape == (300,)
        np.testing.assert_array_equal(got, expected)
    near = antcd.collide_batch(a, b, poses_a, poses_b, delta=0.25)
    expected_near = [antcd.collide(a, pa, b, pb, delta=0.25).colliding for pa, pb in zip(poses_a, poses_b)]
    np.testing.assert_array_equal(near, expected_near)
    assert near.sum() > expected.sum()


def test_distance_batch_equals_single_queries(pair):
    a, b = pair
    rng = np.random.default_rng(8)
    poses_a, poses_b = _batch(rng, 120), _batch(rng, 120)
    expected = np.array([antcd.distance(a, pa, b, pb).distance for pa, pb in zip(poses_a, poses_b)])
    for threads in (0, 2):
        got = antcd.distance_batch(a, b, poses_a, poses_b, threads=threads)
        assert got.dtype == np.float64 and got.shape == (120,)
        np.testing.assert_array_equal(got, expected)  # the same exact computation, bit for bit
    colliding = antcd.collide_batch(a, b, poses_a, poses_b)
    np.testing.assert_array_equal(expected == 0, colliding)


def test_single_pose_broadcasts(pair):
    a, b = pair
    rng = np.random.default_rng(9)
    poses_b = _batch(rng, 50)
    fixed = random_pose(rng, 0.5)
    np.testing.assert_array_equal(
        antcd.collide_batch(a, b, fixed, poses_b),
        antcd.collide_batch(a, b, np.broadcast_to(fixed, (50, 4, 4)), poses_b))
    np.testing.assert_array_equal(
        antcd.distance_batch(a, b, None, poses_b),
        antcd.distance_batch(a, b, np.broadcast_to(np.eye(4), (50, 4, 4)), poses_b))
    assert antcd.collide_batch(a, b, np.zeros((0, 4, 4)), None).shape == (0,)


def test_bad_batches_raise(pair):
    a, b = pair
    good = np.broadcast_to(np.eye(4), (3, 4, 4)).copy()
    with pytest.raises(ValueError, match="poses_b has 2 poses, the other poses 3"):
        antcd.collide_batch(a, b, good, good[:2])
    with pytest.raises(ValueError, match=r"poses_a must have shape \(n, 4, 4\)"):
        antcd.collide_batch(a, b, np.zeros((3, 3, 3)), good)
    with pytest.raises(ValueError, match="both single poses"):
        antcd.distance_batch(a, b, None, np.eye(4))
    scaled = good.copy()
    scaled[1, :3, :3] *= 2
    with pytest.raises(ValueError, match=r"poses_b\[1\] is not a rigid motion: rotation is not orthonormal"):
        antcd.distance_batch(a, b, good, scaled)
    nan = good.copy()
    nan[2, 0, 3] = np.nan
    with pytest.raises(ValueError, match=r"poses_a\[2\] has a non-finite entry"):
        antcd.collide_batch(a, b, nan, good)
    with pytest.raises(ValueError, match="delta"):
        antcd.collide_batch(a, b, good, good, delta=-1.0)
    with pytest.raises(ValueError, match="threads"):
        antcd.collide_batch(a, b, good, good, threads=-1)

