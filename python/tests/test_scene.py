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



@pytest.fixture(scope="module")
def tunnel_path(tmp_path_factory):
    """Sheet b (0.01 thick) falls 1.0 per frame through sheet a between frames 1 and 2 (discrete
    checks at the frames never see them touch); c stays far away."""
    out = tmp_path_factory.mktemp("tunnel")
    corners = [(x, y, z) for x in (-0.5, 0.5) for y in (-0.5, 0.5) for z in (-0.005, 0.005)]
    faces = [(1, 2, 4), (1, 4, 3), (5, 7, 8), (5, 8, 6), (1, 5, 6), (1, 6, 2), (3, 4, 8), (3, 8, 7),
             (1, 3, 7), (1, 7, 5), (2, 6, 8), (2, 8, 4)]
    (out / "sheet.obj").write_text("".join(f"v {x} {y} {z}\n" for x, y, z in corners) +
                                   "".join(f"f {a} {b} {c}\n" for a, b, c in faces))

    def track(zs, x=0.0):
        return [{"rotation_wxyz": [1, 0, 0, 0], "translation": [x, 0, z]} for z in zs]

    scene = {"format": "antcd-scene/1", "frames": 4, "objects": [
        {"name": "a", "mesh": "sheet.obj", "poses": track([0, 0, 0, 0])},
        {"name": "b", "mesh": "sheet.obj", "poses": track([1.5, 0.5, -0.5, -1.5])},
        {"name": "c", "mesh": "sheet.obj", "poses": track([0, 0, 0, 0], x=5.0)}]}
    (out / "scene.json").write_text(json.dumps(scene))
    return out / "scene.json"


def test_continuous_catches_the_tunnelling_sheet_like_the_cli(cli, tunnel_path, tmp_path):
    scene = antcd.Scene(tunnel_path)
    mine = scene.run(continuous=True)
    discrete = scene.run()
    assert mine.continuous and not discrete.continuous and "continuous" in repr(mine)
    assert all(len(p) == 0 for p in discrete.pairs)  # tunnels at the frames
    assert [mine.pair_names(k) for k in range(4)] == [[], [], [("a", "b")], []]
    # b's lower face meets a's upper face when b's centre is at z = 0.01: t* = 0.49 of the step.
    toi = mine.toi[2][0]
    assert 0.49 - 1e-5 <= toi <= 0.49
    np.testing.assert_allclose(mine.contact_points[2][0][2], 0.005, atol=1e-4)
    assert all(t.shape == (0,) for t in discrete.toi)
    assert all(c.shape == (0, 3) for c in discrete.contact_points)
    theirs = _cli_run(cli, tunnel_path, tmp_path, "--continuous")
    assert theirs["continuous"] is True
    for k, frame in enumerate(theirs["frames"]):
        assert mine.pair_names(k) == [tuple(p) for p in frame["pairs"]]
        np.testing.assert_allclose(mine.toi[k], frame["toi"], rtol=0, atol=1e-15)
        np.testing.assert_allclose(mine.contact_points[k].reshape(-1, 3),
                                   np.reshape(frame["contact_points"], (-1, 3)), rtol=0, atol=1e-15)
    one = antcd.run_scene(tunnel_path, frames=2, continuous=True)
    np.testing.assert_array_equal(one.toi[0], mine.toi[2])
    with pytest.raises(ValueError, match="continuous"):
        scene.run(method="sphere-obb", continuous=True)


def test_continuous_frames_cover_the_discrete_pairs(scene_path):
    scene = antcd.Scene(scene_path)
    mine, discrete = scene.run(continuous=True), scene.run()
    assert sum(len(p) for p in discrete.pairs) > 0
    for k in range(len(mine)):
        pairs, toi = mine.pairs[k], mine.toi[k]
        assert toi.shape == (len(pairs),) and mine.contact_points[k].shape == (len(pairs), 3)
        assert ((toi >= 0) & (toi <= 1)).all() and (k > 0 or (toi == 0).all())
        # A pair touching at the frame touches during the step that ends there.
        assert {tuple(p) for p in discrete.pairs[k]} <= {tuple(p) for p in pairs}
