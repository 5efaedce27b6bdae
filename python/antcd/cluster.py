"""Batches and scene runs on a Dask cluster (Debian ``python3-distributed``).

The pattern: the models go to every worker ONCE (``client.scatter(..., broadcast=True)``: each
``antcd.Model`` is pickled as its model-file bytes, ``Model.to_bytes``, and unpickled on the worker
without building anything); the poses are cut into chunks, one ``client.submit`` of
``antcd.collide_batch`` (or ``distance_batch``) per chunk, with the scattered models as
arguments; the chunks' answers are gathered and joined IN CHUNK ORDER, so the result is exactly
the serial ``collide_batch`` over all poses (each entry is an independent exact query).

    from distributed import Client
    import antcd, antcd.cluster

    client = Client("tcp://scheduler-host:8786")     # or Client(LocalCluster(...))
    verdicts = antcd.cluster.collide_batch(client, a, b, poses_a, poses_b, chunk=20000)

Workers need ``antcd`` importable (the same version: the model-file format is versioned and a
worker refuses another version with ValueError). Scene runs (``run_scenes``) read the scene files
and their meshes ON THE WORKERS, so the paths must name the same files there (a shared file
system).
"""
from __future__ import annotations

from typing import Any, Callable, Iterable, Sequence

import numpy as np

from . import _antcd
from ._antcd import Model

__all__ = ["collide_batch", "distance_batch", "run_scenes", "scene_result"]


def _pose_chunks(poses_a: Any, poses_b: Any, chunk: int) -> list[tuple[Any, Any]]:
    """The pose pairs cut into consecutive chunks of at most `chunk` pairs; a single (4, 4) pose or
    None is passed whole to every chunk (the batch functions broadcast it)."""
    if isinstance(chunk, bool) or not isinstance(chunk, (int, np.integer)) or chunk < 1:
        raise ValueError(f"chunk must be an integer >= 1, got {chunk!r}")

    def as_batch(poses: Any, name: str) -> np.ndarray | None:
        if poses is None:
            return None
        array = np.asarray(poses, dtype=np.float64)
        if array.shape == (4, 4):
            return None if np.array_equal(array, np.eye(4)) else array
        if array.ndim != 3 or array.shape[1:] != (4, 4):
            raise ValueError(f"{name} must be (n, 4, 4), (4, 4) or None, got shape {array.shape}")
        return array

    a, b = as_batch(poses_a, "poses_a"), as_batch(poses_b, "poses_b")
    batches = [p for p in (a, b) if p is not None and p.ndim == 3]
    if not batches:
        raise ValueError("poses_a and poses_b are both single poses: give at least one (n, 4, 4) "
                         "batch")
    n = len(batches[0])
    if any(len(p) != n for p in batches):
        raise ValueError(f"poses_a and poses_b have different lengths ({len(batches[0])} and "
                         f"{len(batches[1])})")

    def part(poses: np.ndarray | None, begin: int) -> Any:
        return poses[begin:begin + chunk] if poses is not None and poses.ndim == 3 else poses

    return [(part(a, begin), part(b, begin)) for begin in range(0, n, chunk)]


def _map_chunks(client: Any, function: Callable, a: Model, b: Model, poses_a: Any, poses_b: Any,
                chunk: int, dtype: Any, **options: Any) -> np.ndarray:
    if not isinstance(a, Model) or not isinstance(b, Model):
        raise TypeError("a and b must be antcd.Model objects, got "
                        f"{type(a).__name__} and {type(b).__name__}")
    chunks = _pose_chunks(poses_a, poses_b, chunk)
    # Once per worker: scatter pickles each model once and copies it to every worker.
    models = [a] if a is b else [a, b]
    remote = client.scatter(models, broadcast=True, hash=False)
    remote_a, remote_b = remote[0], remote[-1]
    futures = [client.submit(function, remote_a, remote_b, pa, pb, pure=False, **options)
               for pa, pb in chunks]
    parts = client.gather(futures)  # in submission order, whatever order the workers finish in
    return np.concatenate(parts) if parts else np.zeros(0, dtype=dtype)


# The tasks: module-level functions, pickled by reference (antcd.cluster is imported on the
# worker); the extension's own functions cannot be pickled.
def _collide_chunk(a: Model, b: Model, poses_a: Any, poses_b: Any, **options: Any) -> np.ndarray:
    return _antcd.collide_batch(a, b, poses_a, poses_b, **options)


def _distance_chunk(a: Model, b: Model, poses_a: Any, poses_b: Any, **options: Any) -> np.ndarray:
    return _antcd.distance_batch(a, b, poses_a, poses_b, **options)


def collide_batch(client: Any, a: Model, b: Model, poses_a: Any, poses_b: Any, *,
                  delta: float = 0.0, chunk: int = 10000, threads: int = 1) -> np.ndarray:
    """``antcd.collide_batch(a, b, poses_a, poses_b, delta=delta)`` computed on a Dask cluster.

    client: a ``distributed.Client``. The models are sent to each worker once; each chunk of
    `chunk` pose pairs is one task, answered by ``antcd.collide_batch`` on `threads` C++ threads
    of its worker (1 suits one Dask thread per core; 0 uses every hardware thread). Returns bool[n],
    equal to the serial call entry for entry, in the same order.
    """
    return _map_chunks(client, _collide_chunk, a, b, poses_a, poses_b, chunk, np.bool_,
                       delta=delta, threads=threads)


def distance_batch(client: Any, a: Model, b: Model, poses_a: Any, poses_b: Any, *,
                   chunk: int = 2000, threads: int = 1) -> np.ndarray:
    """``antcd.distance_batch`` on a Dask cluster, as collide_batch above: float64[n], bit for bit
    the serial answer, in order."""
    return _map_chunks(client, _distance_chunk, a, b, poses_a, poses_b, chunk, np.float64,
                       threads=threads)


def scene_result(path: str, **run_options: Any) -> dict:
    """Runs one scene file (``antcd.run_scene(path, **run_options)``) and returns its answers as
    plain data (picklable, unlike SceneRun): ``path``, ``method``, ``object_names``, ``frames``
    (int64[f]) and ``pairs`` (one uint32[k, 2] array of colliding object indices per frame)."""
    run = _antcd.run_scene(path, **run_options)
    return {"path": str(path), "method": run.method, "object_names": list(run.object_names),
            "frames": run.frames, "pairs": run.pairs}


def run_scenes(client: Any, paths: Iterable[Any], **run_options: Any) -> list[dict]:
    """Runs scene files in bulk on a Dask cluster, one task per file (what ``antcd run`` does for
    one file), and returns their ``scene_result`` dicts in the order of `paths`. run_options are
    ``antcd.run_scene``'s (method, frames, delta, threads, ...). Each worker reads the scene file
    and its meshes itself (a mesh may be a saved model, ``*.antcd``, which loads without a build),
    so the paths must be valid on the workers. A bad file raises its ValueError / OSError here."""
    names: Sequence[str] = [str(p) for p in paths]
    futures = [client.submit(scene_result, p, pure=False, **run_options) for p in names]
    return client.gather(futures)
