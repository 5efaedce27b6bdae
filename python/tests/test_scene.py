"""Scene / run_scene: per-frame pairs equal the C++ tool's (`antcd run`) on a generated paper
scene, for the exact method and a seeded random one; bad files raise OSError / ValueError."""
import json

import numpy as np
import pytest

import antcd
from conftest import run_cli


@pytest.fixture(scope="module")
def scene_path(cli, tmp_path_factory):
    out = tmp_path_factory.mktemp("scene")
    run_cli(cli, "scene", "generate", "--out", str(out), "--objects", "12", "--vertices", "120",
            "--frames", "12", "--seed", "3")
    return out / "scene.json"


def _cli_run(cli, scene_path, tmp_path, *args):
    out = tmp_path / "run.json"
    run_cli(cli, "run", str(scene_path), "--out", str(out), *args)
    return json.loads(out.read_text())


@pytest.mark.parametrize("method, args", [("exact", []), ("sphere-obb", []),
                                          ("maco", ["--seed", "5", "--samples", "200"])])
def test_pairs_equal_the_cli(cli, scene_path, tmp_path, method, args):
    theirs = _cli_run(cli, scene_path, tmp_path, "--method", method, *args)
    kwargs = {"seed": 5, "samples_per_side": 200} if method == "maco" else {}
    mine = antcd.run_scene(scene_path, method=method, **kwargs)
    assert mine.method == method and len(mine) == len(theirs["frames"])
    np.testing.assert_array_equal(mine.frames, [f["frame"] for f in theirs["frames"]])
    total = 0
    for k, frame in enumerate(theirs["frames"]):
        assert sorted(mine.pair_names(k)) == sorted(tuple(p) for p in frame["pairs"])
        names = mine.object_names
        assert [(names[i], names[j]) for i, j in mine.pairs[k]] == mine.pair_names(k)
        total += len(frame["pairs"])
    assert (mine.times_ms >= 0).all() and mine.times_ms.shape == (len(mine),)
    if method == "exact":
        assert total > 0, "the generated scene has no contact: the comparison would be one-sided"


def test_scene_object_access_and_frame_selection(scene_path):
    scene = antcd.Scene(scene_path)
    assert scene.frames == 12 and scene.object_count == 12 and len(scene.object_names) == 12
    everything = scene.run()
    some = scene.run(frames=[3, 7])
    one = scene.run(frames=7, threads=2)
    np.testing.assert_array_equal(some.pairs[1], everything.pairs[7])
    np.testing.assert_array_equal(one.pairs[0], everything.pairs[7])
    # The scene's models and poses reproduce its verdicts through collide().
    for i, j in everything.candidates[7]:
        hit = antcd.collide(scene.model(int(i)), scene.pose(int(i), 7), scene.model(int(j)), scene.pose(int(j), 7))
        assert hit.colliding == any((p == (i, j)).all() for p in everything.pairs[7])
    with pytest.raises(ValueError, match="frame"):
        scene.run(frames=[12])
    with pytest.raises(ValueError, match="unknown method"):
        scene.run(method="bogus")
    with pytest.raises(ValueError, match="threads"):
        scene.run(threads=0)


def test_scene_file_errors(tmp_path):
    with pytest.raises(FileNotFoundError):
        antcd.run_scene(tmp_path / "nope.json")
    bad = tmp_path / "bad.json"
    bad.write_text('{"format": "antcd-scene/1", "frames": 2, "objects": [{"name": "a"}]}')
    with pytest.raises(ValueError, match="bad.json"):
        antcd.Scene(bad)
    bad.write_text("{not json")
    with pytest.raises(ValueError, match="bad.json"):
        antcd.Scene(bad)
    missing_mesh = tmp_path / "missing_mesh.json"
    missing_mesh.write_text('{"format": "antcd-scene/1", "frames": 1, "objects": ['
                            '{"name": "a", "mesh": "no.obj", "poses": [{"translation": [0,0,0]}]}]}')
    with pytest.raises(ValueError, match="no.obj"):
        antcd.Scene(missing_mesh)
