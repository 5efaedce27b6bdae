"""sweep(): continuous collision between moving models; the CLI (`antcd sweep --json`) gives the
same answer, dense sub-stepping with collide() never touches before toi, bad input raises."""
import json

import numpy as np
import pytest

import antcd
from conftest import box_mesh, run_cli


def _translation(x, y, z):
    pose = np.eye(4)
    pose[:3, 3] = (x, y, z)
    return pose


def _turn_z(angle):
    pose = np.eye(4)
    c, s = np.cos(angle), np.sin(angle)
    pose[:2, :2] = [[c, -s], [s, c]]
    return pose


def test_thin_sheets_tunnel_but_the_sweep_catches_them():
    sheet = antcd.Model(*box_mesh((0.5, 0.5, 0.005)))
    a0, a1 = _translation(0, 0, -0.5), _translation(0, 0, 0.5)
    assert not antcd.collide(sheet, a0, sheet, None) and not antcd.collide(sheet, a1, sheet, None)
    r = antcd.sweep(sheet, a0, a1, sheet, None, None)
    assert r.hit and bool(r)
    assert 0.49 - 2e-6 <= r.toi <= 0.49
    assert r.contact is not None and r.contact.normal[2] < -0.99
    # Dense sub-stepping finds the first contact no earlier.
    steps = np.linspace(0, 1, 1001)
    first = next(t for t in steps if antcd.collide(sheet, _translation(0, 0, -0.5 + t), sheet, None))
    assert r.toi <= first


def test_rotation_counts_and_misses_are_proofs():
    bar = antcd.Model(*box_mesh((2, 0.05, 0.05)))
    cube = antcd.Model(*box_mesh((0.1, 0.1, 0.1)))
    where = _translation(1.2, 1.2, 0)
    r = antcd.sweep(bar, None, _turn_z(np.pi / 2), cube, where, where)
    assert r.hit and 0 < r.toi < 0.5
    far = _translation(5, 5, 0)
    miss = antcd.sweep(bar, None, _turn_z(np.pi / 2), cube, far, far)
    assert not miss and miss.contact is None and miss.distance > 0
    near = antcd.sweep(bar, None, _turn_z(np.pi / 2), cube, far, far, min_separation=5.0)
    assert near.hit


def test_same_answer_as_the_cli(models_dir, cli, tmp_path):
    box = models_dir / "OBJ/box.obj"
    model = antcd.Model.load(box)
    out = json.loads(run_cli(cli, "sweep", str(box), str(box), "--pose-a0", "-5,0,0", "--pose-a1",
                             "5,0,0", "--json"))
    mine = antcd.sweep(model, _translation(-5, 0, 0), _translation(5, 0, 0), model, None, None)
    assert mine.hit == out["hit"] and mine.toi == out["toi"]
    assert mine.contact.triangle_a == out["contact"]["triangle_a"]


def test_bad_input_raises():
    cube = antcd.Model(*box_mesh((0.1, 0.1, 0.1)))
    with pytest.raises(ValueError, match="min_separation"):
        antcd.sweep(cube, None, None, cube, None, None, min_separation=-1.0)
    with pytest.raises(ValueError, match="time_tolerance"):
        antcd.sweep(cube, None, None, cube, None, None, time_tolerance=0.0)
    with pytest.raises(ValueError, match="pose_b1"):
        antcd.sweep(cube, None, None, cube, None, np.zeros((4, 4)))


def test_pass_through_beyond_the_coordinate_range_raises():
    # Issue 41: at +-1e155 a box passing through a ball answered a proven miss (hit False, lower
    # bound inf); at +-1e154 the error named distance's abs_tolerance, an option never given.
    box = antcd.Model(*box_mesh((0.5, 0.5, 0.5)))
    for s in (1e154, 1e155, 1e200, 1e300, np.finfo(float).max / 2):
        with pytest.raises(ValueError, match="sweep: pose_a0 translation is beyond the continuous "
                                             "queries' coordinate range"):
            antcd.sweep(box, _translation(-s, 0, 0), _translation(s, 0, 0), box, None, None)
    with pytest.raises(ValueError, match="sweep: min_separation is beyond"):
        antcd.sweep(box, None, None, box, None, None, min_separation=1e300)
    for s in (1.0, 1e50, 1e100):
        r = antcd.sweep(box, _translation(-s, 0, 0), _translation(s, 0, 0), box, None, None)
        assert r.hit and r.toi <= 0.5
