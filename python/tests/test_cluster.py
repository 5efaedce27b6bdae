"""antcd.cluster on a Dask LocalCluster of 2 worker processes (Debian python3-distributed): the
models are scattered once to each worker, pose chunks are mapped, and the gathered answers equal
the serial collide_batch / distance_batch in the same order; scene files run in bulk equal their
serial runs. Small on purpose (CI): a few thousand poses, two tiny scenes."""
import json

import numpy as np
import pytest

import antcd
import antcd.cluster
from conftest import box_mesh, random_pose, sphere_mesh

distributed = pytest.importorskip(
    "distributed", reason="Dask's distributed is missing (Debian python3-distributed, "
    "scripts/install-deps.sh)")


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(n_workers=2, processes=True, threads_per_worker=1,
                                       dashboard_address=None, silence_logs=40)
    with distributed.Client(cluster) as c:
        yield c
    cluster.close()


def test_batches_equal_the_serial_run_in_order(client):
    a = antcd.Model(*sphere_mesh(1.0, 16, 8), name="sphere")
    b = antcd.Model(*box_mesh((0.4, 0.3, 0.2)), name="box")
    rng = np.random.default_rng(11)
    poses_a = np.stack([random_pose(rng, 1.5) for _ in range(3000)])
    poses_b = np.stack([random_pose(rng, 1.5) for _ in range(3000)])
    serial = antcd.collide_batch(a, b, poses_a, poses_b, delta=0.01)
    assert 100 < serial.sum() < 2900
    got = antcd.cluster.collide_batch(client, a, b, poses_a, poses_b, delta=0.01, chunk=700)
    assert got.dtype == np.bool_
    np.testing.assert_array_equal(got, serial)
    # One fixed pose broadcast to every chunk, and the same model on both sides.
    fixed = random_pose(rng, 0.3)
    np.testing.assert_array_equal(
        antcd.cluster.collide_batch(client, a, a, fixed, poses_b[:500], chunk=128),
        antcd.collide_batch(a, a, fixed, poses_b[:500]))
    serial_d = antcd.distance_batch(a, b, poses_a[:400], poses_b[:400])
    np.testing.assert_array_equal(
        antcd.cluster.distance_batch(client, a, b, poses_a[:400], poses_b[:400], chunk=90),
        serial_d)
    # Both workers took part.
    assert len(client.scheduler_info()["workers"]) == 2


def test_bad_arguments_raise_before_anything_is_sent(client):
    a = antcd.Model(*box_mesh())
    with pytest.raises(ValueError, match="chunk"):
        antcd.cluster.collide_batch(client, a, a, None, np.zeros((3, 4, 4)), chunk=0)
    with pytest.raises(ValueError, match="both single poses"):
        antcd.cluster.collide_batch(client, a, a, None, np.eye(4))
    with pytest.raises(ValueError, match="different lengths"):
        antcd.cluster.collide_batch(client, a, a, np.tile(np.eye(4), (3, 1, 1)),
                                    np.tile(np.eye(4), (4, 1, 1)))
    with pytest.raises(TypeError, match="antcd.Model"):
        antcd.cluster.collide_batch(client, "mesh.obj", a, None, np.zeros((1, 4, 4)))


def _write_scene(path, mesh, seed):
    rng = np.random.default_rng(seed)
    objects = []
    for i in range(5):
        poses = [{"translation": rng.uniform(-1, 1, 3).tolist(), "rotation_wxyz": [1, 0, 0, 0]}
                 for _ in range(3)]
        objects.append({"name": f"o{i}", "mesh": str(mesh), "poses": poses})
    path.write_text(json.dumps({"format": "antcd-scene/1", "frames": 3, "objects": objects}))
    return path


def test_scene_files_in_bulk(client, tmp_path):
    box = antcd.Model(*box_mesh((0.4, 0.4, 0.4)))
    saved = tmp_path / "box.antcd"
    box.save(saved)
    scenes = [_write_scene(tmp_path / f"scene{i}.json", saved, i) for i in range(3)]
    results = antcd.cluster.run_scenes(client, scenes, method="exact")
    assert [r["path"] for r in results] == [str(s) for s in scenes]
    for scene, result in zip(scenes, results):
        serial = antcd.run_scene(str(scene))
        assert result["object_names"] == list(serial.object_names)
        np.testing.assert_array_equal(result["frames"], serial.frames)
        for got, expected in zip(result["pairs"], serial.pairs):
            np.testing.assert_array_equal(got, expected)
    assert sum(len(p) for r in results for p in r["pairs"]) > 0
    with pytest.raises(ValueError):
        antcd.cluster.run_scenes(client, [tmp_path / "box.antcd"])
