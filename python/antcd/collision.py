"""A collision manager with trimesh's interface, on antcd's exact mesh-vs-mesh query.

``antcd.CollisionManager`` keeps the method names, arguments and return conventions of
``trimesh.collision.CollisionManager`` so that a script using trimesh's manager runs after
changing its import: ``add_object(name, mesh, transform=None)`` (same name replaces),
``remove_object`` / ``set_transform`` (ValueError for an unknown name), ``in_collision_single`` /
``in_collision_internal`` / ``in_collision_other`` returning ``is_collision`` and, on request, the
names (a set of names; a set of 2-tuples sorted alphabetically; a set of (this, other) tuples) and
a list of ``ContactData``, one per colliding triangle pair.

Beyond trimesh: deforming objects (``add_object(..., self_collision=True)``, ``set_vertices``;
``in_collision_internal`` then also reports an object that intersects itself as the pair
``(name, name)``) and continuous motion (``sweep_motion`` / ``set_motion_continuous``: the first
time of impact of every pair while objects move and deform, as ``MotionToi`` records).

``min_distance_single`` / ``min_distance_internal`` / ``min_distance_other`` return the minimum
distance and, on request, the name(s) of the closest object(s) (a name; a 2-tuple in alphabetical
order; a (this, other) tuple) and a ``DistanceData`` with the closest point and face index per name.

The objects live in an ``antcd`` World (a dynamic AABB tree over the objects' boxes, exact
triangle tests behind it). Collision and minimum-distance queries are the World's: minimum
distances (``antcd.distance``: signed for two closed meshes, the surface distance otherwise) come
from a best-first search over the tree's node pairs pruned by the best distance so far (ties: the
objects added first).

Differences from trimesh/FCL, all documented on the methods: meshes may be ``antcd.Model``s
(shared, built once), trimesh meshes, or ``(vertices, faces)`` pairs; collision means the surfaces
share a point (touching counts) or, for closed meshes, that one lies wholly inside the other
(FCL reports the nested case only for its convex shapes); contacts (``ContactData``) are FCL's:
one per pair with the solids' penetration depth for convex pairs (and nested ones), one per
triangle pair with that pair's depth otherwise; a minimum distance between two closed meshes is
signed like FCL's (minus the penetration depth of overlapping solids, nested ones included),
between open meshes the surface distance (never negative); it is ``inf`` with the names and data
``None`` when there is no pair to measure.
"""
from __future__ import annotations

import math
from typing import Any, Iterable, Mapping

import numpy as np

from . import _antcd
from ._antcd import CollisionResult, DistanceResult, Model

__all__ = ["CollisionManager", "ContactData", "DistanceData", "MotionToi"]


def _as_model(mesh: Any) -> Model:
    if isinstance(mesh, Model):
        return mesh
    if isinstance(mesh, (tuple, list)) and len(mesh) == 2:
        return Model(mesh[0], mesh[1])
    if hasattr(mesh, "vertices") and hasattr(mesh, "faces"):
        return Model(np.asarray(mesh.vertices), np.asarray(mesh.faces))
    raise TypeError(
        "mesh must be an antcd.Model, a (vertices, faces) pair or an object with .vertices and "
        f".faces (e.g. trimesh.Trimesh), got {type(mesh).__name__}"
    )


def _unit_normals(model: Model, pose: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    v = model.vertices[model.faces[triangles]]  # (k, 3, 3), model frame
    n = np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]) @ pose[:3, :3].T
    length = np.linalg.norm(n, axis=1, keepdims=True)
    return n / np.where(length > 0, length, 1.0)


class ContactData:
    """One contact between two named objects.

    ``names`` is the set of the two names; ``index(name)`` the face index of that object's
    triangle (-1 for a solid contact); ``point`` a world-frame point; ``normal`` a world-frame
    unit normal; ``depth`` a penetration depth; ``distance`` the triangle distance.

    Two kinds, as FCL gives them (trimesh's manager on python-fcl):

    - Two convex meshes, or a closed mesh wholly inside another: ONE contact per pair, for the
      solids (antcd.penetration): ``depth`` the solids' penetration depth, ``normal`` the unit
      direction in which to move the first-named object by ``depth`` to separate them, ``point``
      the midpoint of the two surface points that meet after that move (convex), or a point inside
      both (nested). ``index`` is -1 for both names.
    - Otherwise one contact per colliding triangle pair: ``point`` a point both triangles share
      (or, with a collision threshold, the midpoint of their closest points), ``normal`` the unit
      normal of the first object's triangle (its winding order), ``depth`` that TRIANGLE PAIR's
      penetration depth (FCL's mesh semantics; not the solids' depth), ``distance`` 0 when they
      intersect.

    A self pair (an object added with ``self_collision=True`` that intersects itself) is the
    second kind with both names the object's: ``names`` is ``{name}``, ``triangles`` the pair
    ``(i, j)``, i < j, and ``index(name)`` is i.
    """

    __slots__ = ("names", "_inds", "_triangles", "_point", "_normal", "_distance", "_depth")

    def __init__(self, names: tuple[str, str], triangles: tuple[int, int], point: np.ndarray,
                 normal: np.ndarray, distance: float, depth: float = math.nan) -> None:
        self.names = set(names)
        self._triangles = (int(triangles[0]), int(triangles[1]))
        # names[0] last: a self pair's index(name) is its first triangle.
        self._inds = {names[1]: self._triangles[1], names[0]: self._triangles[0]}
        self._point = point
        self._normal = normal
        self._distance = float(distance)
        self._depth = float(depth)

    @property
    def point(self) -> np.ndarray:
        """(3,) float: the contact point, world frame."""
        return self._point

    @property
    def normal(self) -> np.ndarray:
        """(3,) float: unit normal, world frame (see the class documentation)."""
        return self._normal

    @property
    def depth(self) -> float:
        """Penetration depth: of the solids (convex or nested pair) or of the triangle pair."""
        return self._depth

    @property
    def distance(self) -> float:
        """Distance between the two triangles (0 when they intersect or for a solid contact)."""
        return self._distance

    @property
    def triangles(self) -> tuple[int, int]:
        """The face indices of the two triangles, first name's first ((-1, -1): solid)."""
        return self._triangles

    def index(self, name: str) -> int:
        """Face index of the triangle in contact on the object called ``name`` (-1: solid)."""
        return self._inds[name]

    def __repr__(self) -> str:
        return f"<antcd.ContactData {sorted(self.names)} point={self._point.tolist()}>"


class DistanceData:
    """The closest pair of a minimum-distance query: two named objects.

    ``names`` is the set of the two names; ``index(name)`` the face index of that object's closest
    triangle; ``point(name)`` the world-frame closest point on it; ``distance`` the query's
    distance: for two closed meshes the signed distance (minus the penetration depth when the
    solids overlap, nested ones included; the points are then antcd.penetration's witness points),
    otherwise the distance between the two surface points (0 when the surfaces meet);
    ``intersecting`` whether the surfaces share a point.
    """

    __slots__ = ("names", "_inds", "_points", "_distance", "_intersecting")

    def __init__(self, names: tuple[str, str], result: DistanceResult) -> None:
        self.names = set(names)
        self._inds = {names[0]: int(result.triangle_a), names[1]: int(result.triangle_b)}
        self._points = {names[0]: result.point_a, names[1]: result.point_b}
        self._distance = float(result.distance)
        self._intersecting = bool(result.intersecting)

    @property
    def distance(self) -> float:
        """The minimum distance: signed for two closed meshes (< 0: they overlap), else the
        Euclidean distance between the two surfaces."""
        return self._distance

    @property
    def intersecting(self) -> bool:
        """Whether the two surfaces share a point (distance 0)."""
        return self._intersecting

    def index(self, name: str) -> int:
        """Face index of the closest triangle on the object called ``name``."""
        return self._inds[name]

    def point(self, name: str) -> np.ndarray:
        """(3,) float: the closest point on the object called ``name``, world frame."""
        return self._points[name]

    def __repr__(self) -> str:
        return f"<antcd.DistanceData {sorted(self.names)} distance={self._distance!r}>"


class MotionToi:
    """One pair of a continuous motion (CollisionManager.sweep_motion): two objects, or one
    against itself, that come within min_separation while the objects move and deform.

    ``names``: (a, b) in the order the objects were added (a self pair: (name, name)); ``kind``:
    ``'rigid_sweep'`` (two rigid objects: antcd.sweep, ``sweep`` its SweepResult),
    ``'start_contact'`` (a pair with a deforming object, or a self pair, already in contact at
    t = 0: exact discrete test) or ``'deform'`` (found by antcd.deform_sweep: ``primitive`` its
    DeformPair, a's mesh first); ``toi`` in [0, 1], never after the first contact;
    ``tolerance_decided``: the hit rests on the time tolerance, not a proof (False for
    start_contact); ``point``: world point at toi (for display); ``triangles``: (triangle of a,
    triangle of b) for start_contact (self: (i, j), i < j) and rigid_sweep (the sweep's contact),
    None for deform; ``primitive`` / ``sweep``: None for the other kinds.
    """

    __slots__ = ("names", "kind", "toi", "tolerance_decided", "point", "triangles", "primitive",
                 "sweep")

    def __init__(self, names: tuple[str, str], kind: str, toi: float, tolerance_decided: bool,
                 point: np.ndarray, triangles: Any, primitive: Any, sweep: Any) -> None:
        self.names = names
        self.kind = kind
        self.toi = float(toi)
        self.tolerance_decided = bool(tolerance_decided)
        self.point = point
        self.triangles = triangles
        self.primitive = primitive
        self.sweep = sweep

    def __repr__(self) -> str:
        how = "tolerance" if self.tolerance_decided else "proven"
        return f"<antcd.MotionToi {self.names} {self.kind} toi={self.toi!r} ({how})>"


def _contacts(names: tuple[str, str], model: Model, pose: Any, other: Model, other_pose: Any,
              result: CollisionResult, self_pair: bool = False) -> Iterable[ContactData]:
    """The contacts of a colliding pair (see ContactData): one solid contact for a convex pair or
    a nested one (no surface contact), else one per triangle pair (always for a self pair)."""
    if not self_pair and (len(result) == 0 or (_antcd.is_convex(model) and
                                               _antcd.is_convex(other))):
        yield _solid_contact(names, model, pose, other, other_pose)
        return
    ta, tb = result.triangles_a, result.triangles_b
    points, distances, depths = result.points, result.distances, result.depths
    normals = _unit_normals(model, _as_matrix(pose), ta)
    for k in range(len(ta)):
        yield ContactData(names, (ta[k], tb[k]), points[k], normals[k], distances[k], depths[k])


def _solid_contact(names: tuple[str, str], model: Model, pose: Any, other: Model,
                   other_pose: Any) -> ContactData:
    r = _antcd.penetration(model, pose, other, other_pose)
    point = 0.5 * (r.point_a + r.point_b) if r.exact else r.witness
    return ContactData(names, (-1, -1), point, r.direction, 0.0, r.upper)


def _as_matrix(pose: Any) -> np.ndarray:
    if pose is None:
        return np.eye(4)
    if isinstance(pose, (tuple, list)) and len(pose) == 2:
        m = np.eye(4)
        m[:3, :3] = np.asarray(pose[0], dtype=float)
        m[:3, 3] = np.asarray(pose[1], dtype=float)
        return m
    return np.asarray(pose, dtype=float)


def _answer(result: Any, names: Any, data: Any, return_names: bool, return_data: bool) -> Any:
    if return_names and return_data:
        return result, names, data
    if return_names:
        return result, names
    if return_data:
        return result, data
    return result


def _mode(return_names: bool, return_data: bool) -> str:
    return "contacts" if return_data else ("pairs" if return_names else "verdict")


def _distance_of(nearest: Any) -> float:
    return math.inf if nearest is None else float(nearest[2].distance)


def _motion_entries(ids: dict, values: Any, argument: str, function: str) -> list:
    """[(id, name, value)] of a {name: value} argument of sweep_motion / set_motion_continuous."""
    if values is None:
        return []
    if not isinstance(values, Mapping):
        raise TypeError(f"{function}: {argument} must be a dict {{name: value}} or None, got "
                        f"{type(values).__name__}")
    entries = []
    for name, value in values.items():
        if name not in ids:
            raise ValueError(f"{function}: {argument}: {name} not in collision manager!")
        entries.append((ids[name], str(name), value))
    return entries


def _check_manager(other_manager: Any) -> None:
    if not isinstance(other_manager, CollisionManager):
        raise TypeError("other_manager must be an antcd.CollisionManager, got "
                        f"{type(other_manager).__name__}")


class CollisionManager:
    """A set of named, posed meshes checked for collisions (trimesh's CollisionManager interface).

    Backed by an antcd World (dynamic AABB tree broad phase, exact triangle-level queries) and
    antcd's exact mesh distance. Queries release the GIL; objects may be moved or deformed by one
    thread while another queries.
    """

    def __init__(self) -> None:
        self._world = _antcd._World()
        self._ids: dict[str, int] = {}
        # id -> name. Ids are never reused and entries are kept after removal, so a query racing a
        # removal in another thread can still name what it found.
        self._names: dict[int, str] = {}
        # name -> (transform as given, self_collision, rebuild_above), for pickling.
        self._added: dict[str, tuple[Any, bool, float]] = {}

    def add_object(self, name: str, mesh: Any, transform: Any = None, *,
                   self_collision: bool = False, rebuild_above: float = 0.0) -> Model:
        """Adds (or, for a name already present, replaces) an object.

        mesh: an antcd.Model (shared, not copied), a trimesh.Trimesh or any object with
        .vertices and .faces, or a (vertices, faces) pair. transform: 4x4 homogeneous matrix,
        (rotation, translation) pair or None (identity); rigid only (ValueError otherwise).
        self_collision: in_collision_internal (and sweep_motion) also test the object against
        itself. rebuild_above: set_vertices rebuilds the object's hierarchy when refitting made it
        looser than this (Model.refit_growth; 0: never). Returns the object's Model.
        """
        model = _as_model(mesh)
        new_id = self._world.add(model, transform, str(name), bool(self_collision),
                                 rebuild_above)
        old_id = self._ids.get(name)
        if old_id is not None:
            self._world.remove(old_id)
        self._ids[name] = new_id
        self._names[new_id] = name
        self._added[name] = (np.eye(4) if transform is None else transform, bool(self_collision),
                             float(rebuild_above))
        return model

    def remove_object(self, name: str) -> None:
        """Removes an object; ValueError if there is none by that name."""
        if name not in self._ids:
            raise ValueError(f"{name} not in collision manager!")
        self._world.remove(self._ids.pop(name))
        del self._added[name]

    def set_transform(self, name: str, transform: Any) -> None:
        """Replaces an object's pose; ValueError if there is none by that name or the transform
        is not a rigid motion."""
        if name not in self._ids:
            raise ValueError(f"{name} not in collision manager!")
        self._world.set_pose(self._ids[name], transform)
        self._added[name] = (transform, *self._added[name][1:])

    def set_vertices(self, name: str, vertices: Any) -> None:
        """New model-frame positions for the vertices of the object called ``name`` (same count
        and order; its faces are fixed): a deforming object.

        The first call copies the object's Model (the one given to add_object is never changed,
        and is again free for Model.set_vertices); later calls refit that copy in place, or copy
        again while a Model of an earlier result is held (a held Model never changes). Queries
        then answer on the new vertices; ``model(name)`` and the Models in results are the
        object's current ones. ValueError (the object unchanged) for an unknown name, a wrong
        shape, dtype or row count, a non-finite entry, or a zero-area triangle of the build that
        has an area now. Waits for queries in flight; the GIL is released.
        """
        if name not in self._ids or not self._world.set_vertices(self._ids[name], vertices,
                                                                 str(name)):
            raise ValueError(f"set_vertices: {name} not in collision manager!")

    def model(self, name: str) -> Model:
        """The Model the object called ``name`` uses now (after set_vertices: its own copy).
        ValueError if there is none by that name."""
        found = self._world.model(self._ids[name]) if name in self._ids else None
        if found is None:
            raise ValueError(f"{name} not in collision manager!")
        return found

    def sweep_motion(self, poses: Any = None, vertices: Any = None, *,
                     min_separation: float = 0.0, time_tolerance: float = 1e-6,
                     max_iterations: int = 100000) -> list[MotionToi]:
        """Continuous collision of one step: over t in [0, 1] the objects named in ``poses``
        ({name: pose}) move from their current poses to those, the objects named in
        ``vertices`` ({name: (n, 3) model-frame positions}) deform to those (their WORLD vertices
        move linearly; a new pose may be given too), the others stay (antcd::World::sweep_motion,
        include/antcd/world.hpp). Returns a MotionToi for every pair of objects, and every
        self_collision object against itself, that comes within min_separation, sorted by the
        objects' add order. Conservative: no such pair is missed and each toi is never after its
        first contact. The manager is not changed. ValueError / TypeError naming the argument and
        the object for bad input; the GIL is released while it runs (a shared lock, as queries).
        """
        return self._motion(self._world.sweep_motion, "sweep_motion", poses, vertices,
                            min_separation, time_tolerance, max_iterations)

    def set_motion_continuous(self, poses: Any = None, vertices: Any = None, *,
                              min_separation: float = 0.0, time_tolerance: float = 1e-6,
                              max_iterations: int = 100000) -> list[MotionToi]:
        """sweep_motion, then the poses and vertices applied (set_transform / set_vertices); on
        error nothing is changed. Returns sweep_motion's records."""
        out = self._motion(self._world.set_motion_continuous, "set_motion_continuous", poses,
                           vertices, min_separation, time_tolerance, max_iterations)
        for name, pose in (poses or {}).items():
            if name in self._added:
                self._added[name] = (pose, *self._added[name][1:])
        return out

    def _motion(self, call: Any, function: str, poses: Any, vertices: Any, min_separation: float,
                time_tolerance: float, max_iterations: int) -> list[MotionToi]:
        pose_entries = _motion_entries(self._ids, poses, "poses", function)
        vertex_entries = _motion_entries(self._ids, vertices, "vertices", function)
        records = call(pose_entries, vertex_entries, min_separation, time_tolerance,
                       max_iterations)
        return [MotionToi((self._names[a], self._names[b]), *rest) for a, b, *rest in records]

    def __getstate__(self) -> dict:
        """Pickling: the objects as (name, Model, transform, {"self_collision",
        "rebuild_above"}) in the order they were added, each with its current Model. Each Model
        pickles as its model-file bytes (Model.to_bytes), once however many objects share it
        (pickle's memo), and unpickles without building anything."""
        order = sorted(self._ids.items(), key=lambda item: item[1])
        objects = []
        for name, object_id in order:
            transform, self_collision, rebuild_above = self._added[name]
            objects.append((name, self._world.model(object_id), transform,
                            {"self_collision": self_collision, "rebuild_above": rebuild_above}))
        return {"objects": objects}

    def __setstate__(self, state: dict) -> None:
        objects = state.get("objects") if isinstance(state, dict) else None
        if not isinstance(objects, list):
            raise ValueError("antcd.CollisionManager pickle state must be a dict with an "
                             "'objects' list")
        self.__init__()
        for entry in objects:
            if not (isinstance(entry, tuple) and len(entry) in (3, 4) and
                    isinstance(entry[1], Model) and (len(entry) == 3 or isinstance(entry[3], dict))):
                raise ValueError("antcd.CollisionManager pickle state: each object must be a "
                                 "(name, Model, transform[, options dict]) tuple")
            self.add_object(*entry[:3], **(entry[3] if len(entry) == 4 else {}))

    def in_collision_single(self, mesh: Any, transform: Any = None, return_names: bool = False,
                            return_data: bool = False) -> Any:
        """Checks one mesh (not added) against every object.

        Returns is_collision, plus (return_names) the set of names of the objects it touches and
        (return_data) a list of ContactData whose names are (object name, '__external').
        """
        model = _as_model(mesh)
        hits = self._world.collide_single(model, transform, _mode(return_names, return_data))
        names: set = set()
        data: list = []
        for object_id, _, result, object_model, object_pose, _, _ in hits:
            name = self._names[object_id]
            names.add(name)
            if return_data:
                data.extend(_contacts((name, "__external"), object_model, object_pose, model,
                                      transform, result))
        return _answer(bool(hits), names, data, return_names, return_data)

    def in_collision_internal(self, return_names: bool = False, return_data: bool = False) -> Any:
        """Checks every pair of objects, and each object added with self_collision=True against
        itself (antcd.self_intersections of its current mesh).

        Returns is_collision, plus (return_names) a set of 2-tuples of names in alphabetical order
        (a self-intersecting object: (name, name)) and (return_data) a list of ContactData, one per
        colliding triangle pair.
        """
        hits = self._world.collide_internal(_mode(return_names, return_data))
        return self._pairs(hits, self, return_names, return_data, sort_names=True)

    def in_collision_other(self, other_manager: "CollisionManager", return_names: bool = False,
                           return_data: bool = False) -> Any:
        """Checks every object of this manager against every object of another.

        Returns is_collision, plus (return_names) a set of (name in this manager, name in the
        other) tuples and (return_data) a list of ContactData.
        """
        _check_manager(other_manager)
        hits = self._world.collide_other(other_manager._world, _mode(return_names, return_data))
        return self._pairs(hits, other_manager, return_names, return_data, sort_names=False)

    def min_distance_single(self, mesh: Any, transform: Any = None, return_name: bool = False,
                            return_data: bool = False) -> Any:
        """Minimum distance between one mesh (not added) and any object.

        Returns the distance, plus (return_name) the name of the closest object and (return_data)
        a DistanceData whose names are (object name, '__external'). With no objects: inf and None.
        """
        model = _as_model(mesh)
        nearest = self._world.distance_single(model, transform)
        name = data = None
        if nearest is not None:
            object_id, _, result = nearest
            name = self._names[object_id]
            if return_data:
                data = DistanceData((name, "__external"), result)
        return _answer(_distance_of(nearest), name, data, return_name, return_data)

    def min_distance_internal(self, return_names: bool = False, return_data: bool = False,
                              name: str | None = None) -> Any:
        """Minimum distance between any two objects, or (name, as trimesh >= 4.10) between the
        object called ``name`` and any other (ValueError if there is none by that name).

        Signed for two closed meshes: minus their penetration depth when the solids overlap
        (``antcd.penetration``; nested ones included). Returns the distance, plus (return_names)
        the 2-tuple of the closest objects' names in alphabetical order and (return_data) a
        DistanceData. Fewer than two objects: inf and None.
        """
        if name is not None:
            return self._min_distance_named(name, return_names, return_data)
        nearest = self._world.distance_internal()
        return self._closest(nearest, self, return_names, return_data, sort_names=True)

    def _min_distance_named(self, name: str, return_names: bool, return_data: bool) -> Any:
        if name not in self._ids:
            raise ValueError(f"{name} not in collision manager!")
        nearest = self._world.distance_object(self._ids[name])
        if nearest is None:
            return _answer(math.inf, None, None, return_names, return_data)
        _, other_id, result = nearest
        other = self._names[other_id]
        names = tuple(sorted((name, other)))
        data = DistanceData((name, other), result) if return_data else None
        return _answer(float(result.distance), names, data, return_names, return_data)

    def min_distance_other(self, other_manager: "CollisionManager", return_names: bool = False,
                           return_data: bool = False) -> Any:
        """Minimum distance between any object of this manager and any object of another.

        Returns the distance, plus (return_names) the (name in this manager, name in the other)
        tuple of the closest pair and (return_data) a DistanceData. Either manager empty: inf and
        None.
        """
        _check_manager(other_manager)
        nearest = self._world.distance_other(other_manager._world)
        return self._closest(nearest, other_manager, return_names, return_data, sort_names=False)

    def _closest(self, nearest: Any, other: "CollisionManager", return_names: bool,
                 return_data: bool, sort_names: bool) -> Any:
        names = data = None
        if nearest is not None:
            id_a, id_b, result = nearest
            pair = (self._names[id_a], other._names[id_b])
            names = tuple(sorted(pair)) if sort_names else pair
            if return_data:
                data = DistanceData(pair, result)
        return _answer(_distance_of(nearest), names, data, return_names, return_data)

    def _pairs(self, hits: list, other: "CollisionManager", return_names: bool, return_data: bool,
               sort_names: bool) -> Any:
        names: set = set()
        data: list = []
        for id_a, id_b, result, model_a, pose_a, model_b, pose_b in hits:
            pair = (self._names[id_a], other._names[id_b])
            names.add(tuple(sorted(pair)) if sort_names else pair)
            if return_data:
                self_pair = sort_names and id_a == id_b  # internal only: other's (b, b) is not
                data.extend(_contacts(pair, model_a, pose_a, model_b, pose_b, result, self_pair))
        return _answer(bool(hits), names, data, return_names, return_data)

    def __len__(self) -> int:
        return len(self._ids)

    def __contains__(self, name: object) -> bool:
        return name in self._ids
