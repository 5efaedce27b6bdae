"""load_mesh and Model: real files in, numpy out, and every bad array rejected with ValueError."""
import numpy as np
import pytest

import antcd
from conftest import box_mesh

REAL = ["PLY/Wuson.ply", "OFF/Cube.off", "STL/Spider_binary.stl", "OBJ/spider.obj"]


@pytest.mark.parametrize("name", REAL)
def test_load_mesh_gives_float64_vertices_and_int64_faces(models_dir, name):
    vertices, faces = antcd.load_mesh(models_dir / name)
    assert vertices.dtype == np.float64 and vertices.ndim == 2 and vertices.shape[1] == 3
    assert faces.dtype == np.int64 and faces.ndim == 2 and faces.shape[1] == 3
    assert len(faces) > 0 and faces.min() >= 0 and faces.max() < len(vertices)
    assert np.isfinite(vertices).all()


@pytest.mark.parametrize("name", REAL)
def test_model_from_arrays_equals_model_load(models_dir, name):
    vertices, faces = antcd.load_mesh(str(models_dir / name))
    a = antcd.Model(vertices, faces)
    b = antcd.Model.load(models_dir / name)
    np.testing.assert_array_equal(a.vertices, vertices)
    np.testing.assert_array_equal(a.faces, faces)
    np.testing.assert_array_equal(b.faces, faces)
    assert a.stats["nodes"] == b.stats["nodes"]
    assert b.name == str(models_dir / name)


def test_model_arrays_are_read_only_views_not_copies():
    v, f = box_mesh()
    m = antcd.Model(v, f)
    first, second = m.vertices, m.vertices
    assert np.shares_memory(first, second)  # both views of the model's one copy
    assert not np.shares_memory(first, v)  # the model owns its data: later edits of v do not leak in
    assert not first.flags.writeable and not m.faces.flags.writeable
    with pytest.raises(ValueError):
        first[0, 0] = 1.0
    v[0, 0] = 99.0
    assert m.vertices[0, 0] != 99.0
    assert m.faces.dtype == np.uint32 and m.triangle_count == 12 and m.vertex_count == 8


def test_model_accepts_other_numeric_dtypes_and_layouts():
    v, f = box_mesh()
    ref = antcd.Model(v, f)
    for vertices, faces in [(v.astype(np.float32), f.astype(np.uint32)), (v.tolist(), f.tolist()),
                            (np.asfortranarray(v), np.asfortranarray(f.astype(np.int16))),
                            ((v * 2).astype(np.int64), f)]:
        m = antcd.Model(vertices, faces)
        assert m.triangle_count == ref.triangle_count
    assert antcd.Model(v, f, leaf_size=1, covariance="vertex").covariance == "vertex"


BAD = [
    (lambda v, f: (v[:, :2], f), "vertices must have shape"),
    (lambda v, f: (v.ravel(), f), "vertices must have shape"),
    (lambda v, f: (v, f[:, :2]), "faces must have shape"),
    (lambda v, f: (v, f.astype(np.float64)), "faces must have an integer dtype"),
    (lambda v, f: (v.astype(bool), f), "vertices must hold real numbers"),
    (lambda v, f: (v.astype(object), f), "vertices must hold real numbers"),
    (lambda v, f: (np.where(np.arange(24).reshape(8, 3) == 7, np.nan, v), f), "non-finite"),
    (lambda v, f: (np.where(np.arange(24).reshape(8, 3) == 3, np.inf, v), f), "non-finite"),
    (lambda v, f: (v, np.where(f == 5, 8, f)), "out of range"),
    (lambda v, f: (v, np.where(f == 5, -1, f)), "out of range"),
    (lambda v, f: (v, f[:0]), "faces is empty"),
    (lambda v, f: (v, np.zeros((1, 3), dtype=np.int64)), "mesh"),  # only a zero-area triangle
    (lambda v, f: (None, f), "vertices must be an array"),
    (lambda v, f: ("abc", f), "vertices"),
]


@pytest.mark.parametrize("make, message", BAD)
def test_bad_arrays_raise_value_error_naming_the_problem(make, message):
    v, f = box_mesh()
    vertices, faces = make(v, f)
    with pytest.raises(ValueError, match=message):
        antcd.Model(vertices, faces)


@pytest.mark.parametrize("kwargs, message", [({"leaf_size": 0}, "leaf_size"), ({"leaf_size": -3}, "leaf_size"),
                                             ({"leaf_size": 2.5}, "leaf_size"), ({"covariance": "pca"}, "covariance")])
def test_bad_build_options_raise_value_error(kwargs, message):
    v, f = box_mesh()
    with pytest.raises(ValueError, match=message):
        antcd.Model(v, f, **kwargs)


def test_load_mesh_file_errors(models_dir, tmp_path):
    with pytest.raises(FileNotFoundError, match="mesh file not found"):
        antcd.load_mesh(tmp_path / "missing.obj")
    with pytest.raises(IsADirectoryError):
        antcd.load_mesh(tmp_path)
    garbage = tmp_path / "garbage.obj"
    garbage.write_bytes(b"\x00\x01 this is not a mesh \xff" * 10)
    with pytest.raises(ValueError, match="garbage.obj"):
        antcd.load_mesh(garbage)
    with pytest.raises(ValueError, match="no triangles"):
        antcd.load_mesh(models_dir / "PLY" / "points.ply")
    with pytest.raises(TypeError):
        antcd.load_mesh(42)


@pytest.mark.parametrize("suffix", ["\0", "\0.ignored", "\0/../x"])
def test_paths_with_a_nul_byte_are_refused_not_truncated(models_dir, suffix):
    # Read up to the NUL, the path would name an existing file: Python's open raises ValueError.
    existing = str(models_dir / "OBJ" / "box.obj")
    for call in (antcd.load_mesh, antcd.Model.load, antcd.Scene):
        with pytest.raises(ValueError, match="null byte"):
            call(existing + suffix)
        with pytest.raises(ValueError, match="null byte"):
            call((existing + suffix).encode())
