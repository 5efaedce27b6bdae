"""A collision manager with trimesh's interface, on antcd's exact mesh-vs-mesh query.

``antcd.CollisionManager`` keeps the method names, arguments and return conventions of
``trimesh.collision.CollisionManager`` so that a script using trimesh's manager runs after
changing its import: ``add_object(name, mesh, transform=None)`` (same name replaces),
``remove_object`` / ``set_transform`` (ValueError for an unknown name), ``in_collision_single`` /
``in_collision_internal`` / ``in_collision_other`` returning ``is_collision`` and, on request, the
names (a set of names; a set of 2-tuples sorted alphabetically; a set of (this, other) tuples) and
a list of ``ContactData``, one per colliding triangle pair.

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
from typing import Any, Iterable

import numpy as np

from . import _antcd
from ._antcd import CollisionResult, DistanceResult, Model

__all__ = ["CollisionManager", "ContactData", "DistanceData"]


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
    """

    __slots__ = ("names", "_inds", "_point", "_normal", "_distance", "_depth")

    def __init__(self, names: tuple[str, str], triangles: tuple[int, int], point: np.ndarray,
                 normal: np.ndarray, distance: float, depth: float = math.nan) -> None:
        self.names = set(names)
        self._inds = {names[0]: int(triangles[0]), names[1]: int(triangles[1])}
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


def _contacts(names: tuple[str, str], model: Model, pose: Any, other: Model, other_pose: Any,
              result: CollisionResult) -> Iterable[ContactData]:
    """The contacts of a colliding pair (see ContactData): one solid contact for a convex pair or
    a nested one (no surface contact), else one per triangle pair."""
    if len(result) == 0 or (_antcd.is_convex(model) and _antcd.is_convex(other)):
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


def _check_manager(other_manager: Any) -> None:
    if not isinstance(other_manager, CollisionManager):
        raise TypeError("other_manager must be an antcd.CollisionManager, got "
                        f"{type(other_manager).__name__}")


class CollisionManager:
    """A set of named, posed meshes checked for collisions (trimesh's CollisionManager interface).

    Backed by an antcd World (dynamic AABB tree broad phase, exact triangle-level queries) and
    antcd's exact mesh distance. Queries release the GIL; objects may be moved by one thread while
    another queries.
    """

    def __init__(self) -> None:
        self._world = _antcd._World()
        self._ids: dict[str, int] = {}
        # id -> name. Ids are never reused and entries are kept after removal, so a query racing a
        # removal in another thread can still name what it found.
        self._names: dict[int, str] = {}
        # name -> (model, pose): the other side of each contact reported by in_collision_*.
        self._posed: dict[str, tuple[Model, Any]] = {}

    def add_object(self, name: str, mesh: Any, transform: Any = None) -> Model:
        """Adds (or, for a name already present, replaces) an object.

        mesh: an antcd.Model (shared, not copied), a trimesh.Trimesh or any object with
        .vertices and .faces, or a (vertices, faces) pair. transform: 4x4 homogeneous matrix,
        (rotation, translation) pair or None (identity); rigid only (ValueError otherwise).
        Returns the object's Model.
        """
        model = _as_model(mesh)
        new_id = self._world.add(model, transform)
        old_id = self._ids.get(name)
        if old_id is not None:
            self._world.remove(old_id)
        self._ids[name] = new_id
        self._names[new_id] = name
        self._posed[name] = (model, np.eye(4) if transform is None else transform)
        return model

    def remove_object(self, name: str) -> None:
        """Removes an object; ValueError if there is none by that name."""
        if name not in self._ids:
            raise ValueError(f"{name} not in collision manager!")
        self._world.remove(self._ids.pop(name))
        del self._posed[name]

    def set_transform(self, name: str, transform: Any) -> None:
        """Replaces an object's pose; ValueError if there is none by that name or the transform
        is not a rigid motion."""
        if name not in self._ids:
            raise ValueError(f"{name} not in collision manager!")
        self._world.set_pose(self._ids[name], transform)
        self._posed[name] = (self._posed[name][0], transform)

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
        for object_id, _, result, object_model, object_pose in hits:
            name = self._names[object_id]
            names.add(name)
            if return_data:
                data.extend(_contacts((name, "__external"), object_model, object_pose, model,
                                      transform, result))
        return _answer(bool(hits), names, data, return_names, return_data)

    def in_collision_internal(self, return_names: bool = False, return_data: bool = False) -> Any:
        """Checks every pair of objects.

        Returns is_collision, plus (return_names) a set of 2-tuples of names in alphabetical order
        and (return_data) a list of ContactData, one per colliding triangle pair.
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
        for id_a, id_b, result, model_a, pose_a in hits:
            pair = (self._names[id_a], other._names[id_b])
            names.add(tuple(sorted(pair)) if sort_names else pair)
            if return_data:
                model_b, pose_b = other._posed[pair[1]]
                data.extend(_contacts(pair, model_a, pose_a, model_b, pose_b, result))
        return _answer(bool(hits), names, data, return_names, return_data)

    def __len__(self) -> int:
        return len(self._ids)

    def __contains__(self, name: object) -> bool:
        return name in self._ids
