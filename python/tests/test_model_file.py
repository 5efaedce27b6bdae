"""Model files and pickling: Model.save / load / to_bytes / from_bytes and pickle give back the
same model bit for bit (same bytes, same answers) without building; CollisionManager pickles
through the same bytes, each shared Model once; bad data raises ValueError / TypeError / OSError
naming the problem."""
import pickle

import numpy as np
import pytest

import antcd
from conftest import box_mesh, random_pose, run_cli, sphere_mesh


@pytest.fixture(scope="module")
def models():
    return (antcd.Model(*sphere_mesh(1.0, 16, 8), name="sphere"),
            antcd.Model(*box_mesh((0.4, 0.3, 0.2)), leaf_size=1, covariance="vertex", name="box"))


def _same_answers(a, b, la, lb, seed):
    rng = np.random.default_rng(seed)
    poses_a = np.stack([random_pose(rng, 1.5) for _ in range(100)])
    poses_b = np.stack([random_pose(rng, 1.5) for _ in range(100)])
    np.testing.assert_array_equal(antcd.collide_batch(a, b, poses_a, poses_b),
                                  antcd.collide_batch(la, lb, poses_a, poses_b))
    np.testing.assert_array_equal(antcd.distance_batch(a, b, poses_a, poses_b),
                                  antcd.distance_batch(la, lb, poses_a, poses_b))


def test_bytes_and_pickle_round_trip(models):
    a, b = models
    for model in models:
        data = model.to_bytes()
        assert isinstance(data, bytes) and data[:8] == b"ANTCDMDL"
        for copy in (antcd.Model.from_bytes(data), antcd.Model.from_bytes(bytearray(data)),
                     antcd.Model.from_bytes(memoryview(data)), pickle.loads(pickle.dumps(model))):
            assert copy.to_bytes() == data
            assert copy.name == model.name
            assert copy.leaf_size == model.leaf_size and copy.covariance == model.covariance
            assert copy.stats == model.stats
            np.testing.assert_array_equal(copy.vertices, model.vertices)
            np.testing.assert_array_equal(copy.faces, model.faces)
    _same_answers(a, b, pickle.loads(pickle.dumps(a)), pickle.loads(pickle.dumps(b)), 1)


def test_save_and_load_files(models, tmp_path, cli):
    a, b = models
    path = tmp_path / "sphere.antcd"
    a.save(path)
    assert path.read_bytes() == a.to_bytes()
    loaded = antcd.Model.load(path)
    assert loaded.name == str(path)
    _same_answers(a, b, loaded, b, 2)
    vertices, faces = antcd.load_mesh(str(path))
    np.testing.assert_array_equal(vertices, a.vertices)
    np.testing.assert_array_equal(faces, a.faces)
    # The CLI writes model files (antcd info --save) and reads them wherever a mesh is accepted.
    obj = tmp_path / "box.obj"
    v, f = box_mesh((0.4, 0.3, 0.2))
    obj.write_text("".join(f"v {x!r} {y!r} {z!r}\n" for x, y, z in v) +
                   "".join(f"f {i + 1} {j + 1} {k + 1}\n" for i, j, k in f))
    saved = tmp_path / "box.antcd"
    run_cli(cli, "info", str(obj), "--leaf-size", "2", "--save", str(saved))
    from_cli = antcd.Model.load(saved)
    assert from_cli.leaf_size == 2 and from_cli.triangle_count == 12
    info = run_cli(cli, "info", str(saved))
    assert "leaf size:   2" in info
    assert run_cli(cli, "collide", str(saved), str(obj)).strip() != ""


def test_bad_data_is_a_clear_error(models, tmp_path):
    a, _ = models
    data = a.to_bytes()
    with pytest.raises(ValueError, match="not an antcd model file"):
        antcd.Model.from_bytes(b"solid cube\n")
    with pytest.raises(ValueError, match="truncated"):
        antcd.Model.from_bytes(data[:-5])
    corrupted = bytearray(data)
    corrupted[100] ^= 0x10
    with pytest.raises(ValueError, match="checksum"):
        antcd.Model.from_bytes(bytes(corrupted))
    newer = bytearray(data)
    newer[8] = 9
    with pytest.raises(ValueError, match="version 9 is not supported"):
        antcd.Model.from_bytes(bytes(newer))
    with pytest.raises(TypeError, match="bytes-like"):
        antcd.Model.from_bytes("ANTCDMDL")
    with pytest.raises(ValueError, match="1-tuple"):
        antcd.Model.__new__(antcd.Model).__setstate__((data, data))
    with pytest.raises(FileNotFoundError):
        antcd.Model.load(tmp_path / "missing.antcd")
    bad = tmp_path / "bad.antcd"
    bad.write_bytes(data[:40])
    with pytest.raises(ValueError, match="bad.antcd: truncated"):
        antcd.Model.load(bad)
    with pytest.raises(ValueError, match="bad.antcd"):
        antcd.load_mesh(bad)
    with pytest.raises(ValueError, match="cannot write"):
        a.save(tmp_path / "missing" / "a.antcd")
    with pytest.raises(TypeError):
        a.save(3)


def test_collision_manager_pickles_with_each_model_once(models):
    a, b = models
    manager = antcd.CollisionManager()
    rng = np.random.default_rng(5)
    for i in range(6):
        manager.add_object(f"o{i}", a if i % 2 == 0 else b, random_pose(rng, 1.2))
    manager.remove_object("o3")
    data = pickle.dumps(manager)
    # Two models of the same bytes stored once each, however many objects use them.
    assert len(data) < len(a.to_bytes()) + len(b.to_bytes()) + 4000
    copy = pickle.loads(data)
    assert copy.in_collision_internal(return_names=True) == \
        manager.in_collision_internal(return_names=True)
    assert copy.min_distance_internal(return_names=True) == \
        manager.min_distance_internal(return_names=True)
    probe = antcd.Model(*box_mesh((0.2, 0.2, 0.2)))
    for _ in range(10):
        pose = random_pose(rng, 1.5)
        assert copy.in_collision_single(probe, pose, return_names=True) == \
            manager.in_collision_single(probe, pose, return_names=True)
    with pytest.raises(ValueError, match="pickle state"):
        antcd.CollisionManager().__setstate__({"objects": [("x", "not a model", None)]})
