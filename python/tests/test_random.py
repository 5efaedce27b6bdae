"""random_collide(): deterministic per seed, its hits are real colliding feature pairs (a subset of
the exhaustive enumeration's), and bad methods or options raise ValueError."""
import numpy as np
import pytest

import antcd
from conftest import box_mesh, sphere_mesh


@pytest.fixture(scope="module")
def spheres():
    v, f = sphere_mesh(1.0, 32, 16)
    m = antcd.Model(v, f)
    pose = np.eye(4)
    pose[:3, 3] = [1.2, 0.3, 0.1]  # overlapping spheres
    return m, pose


@pytest.mark.parametrize("method", ["maco", "aco", "pso", "ga"])
def test_same_seed_same_hits_and_hits_are_real(spheres, method):
    m, pose = spheres
    kwargs = dict(method=method, samples_per_side=200, iterations=30, agents=20)
    first = antcd.random_collide(m, None, m, pose, seed=7, **kwargs)
    again = antcd.random_collide(m, None, m, pose, seed=7, **kwargs)
    assert first.method == method and first.found
    np.testing.assert_array_equal(first.cells, again.cells)
    np.testing.assert_array_equal(first.distances, again.distances)
    assert first.evaluations == again.evaluations
    truth = antcd.random_collide(m, None, m, pose, method="exhaustive", seed=7, samples_per_side=200)
    exhaustive = set(zip(truth.triangles_a.tolist(), truth.triangles_b.tolist()))
    assert set(zip(first.triangles_a.tolist(), first.triangles_b.tolist())) <= exhaustive
    assert first.delta == 0  # the witness verdict: pairs confirmed by the exact test at delta
    # The centroids really are that far apart.
    ca = m.vertices[m.faces[first.triangles_a]].mean(axis=1)
    cb = m.vertices[m.faces[first.triangles_b]].mean(axis=1) + pose[:3, 3]
    np.testing.assert_allclose(np.linalg.norm(ca - cb, axis=1), first.distances, rtol=1e-5)


def test_first_hit_and_separated_models(spheres):
    m, pose = spheres
    r = antcd.random_collide(m, None, m, pose, first_hit=True, seed=1)
    assert r.found and r.stop == "first-hit" and len(r.cells) >= 1
    far = np.eye(4)
    far[0, 3] = 10.0
    r = antcd.random_collide(m, None, m, far, seed=1)
    assert not r.found and r.stop == "empty-space" and r.evaluations == 0


@pytest.mark.parametrize("kwargs, message", [
    ({"method": "ant"}, "ant"), ({"method": "exact"}, "needs a search method"), ({"seed": -1}, "seed"), ({"seed": 1.5}, "seed"),
    ({"delta": -0.1}, "delta"), ({"delta": float("nan")}, "delta"), ({"samples_per_side": 0}, "samples_per_side"),
    ({"iterations": 0}, "iterations"), ({"agents": 1}, "agents"), ({"max_evaluations": -5}, "max_evaluations"),
])
def test_bad_arguments_raise_value_error(kwargs, message):
    v, f = box_mesh()
    m = antcd.Model(v, f)
    with pytest.raises(ValueError, match=message):
        antcd.random_collide(m, None, m, None, **kwargs)
