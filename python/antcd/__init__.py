"""antcd: exact and random (ant colony) mesh-vs-mesh collision detection.

Meshes are numpy arrays in and out: ``load_mesh`` gives ``(vertices float64[n, 3], faces int64[m, 3])``,
``Model(vertices, faces)`` builds the Sphere-OBB hierarchy once, ``collide`` answers exactly,
``distance`` gives the exact minimum surface distance with its closest points, ``sweep`` the
first time two moving models touch (continuous collision, never missing a contact),
``random_collide`` runs the paper's improved ant colony (MACO) and its baselines,
``self_intersections`` / ``self_proximity`` find where one (deforming: ``Model.set_vertices``)
mesh meets or nears itself, ``deform_sweep`` / ``collision_free_step`` the first contact and
the collision-free step of meshes whose vertices move one by one (cloth), ``Scene`` /
``run_scene`` play an antcd-scene/1 file, and ``CollisionManager`` is a drop-in for
``trimesh.collision.CollisionManager`` (with deforming objects and continuous motion:
``MotionToi``).

Poses are 4x4 homogeneous matrices or ``(rotation 3x3, translation 3)`` pairs (rigid motions
only); contact points are in world coordinates. Queries release the GIL and Models may be shared
by any number of threads (``Model.set_vertices`` waits for the queries reading the Model).
"""
from ._antcd import (
    CollisionResult,
    DeformPair,
    DeformSweepResult,
    DistanceResult,
    Model,
    PenetrationResult,
    RandomResult,
    Scene,
    SceneRun,
    SelfIntersectionResult,
    SelfProximityResult,
    SweepContact,
    SweepResult,
    __version__,
    collide,
    collide_batch,
    collision_free_step,
    deform_sweep,
    distance,
    distance_batch,
    is_convex,
    load_mesh,
    penetration,
    random_collide,
    run_scene,
    self_intersections,
    self_proximity,
    sweep,
)
from .collision import CollisionManager, ContactData, DistanceData, MotionToi

__all__ = [
    "CollisionManager",
    "CollisionResult",
    "DeformPair",
    "DeformSweepResult",
    "ContactData",
    "DistanceData",
    "DistanceResult",
    "Model",
    "MotionToi",
    "PenetrationResult",
    "RandomResult",
    "Scene",
    "SceneRun",
    "SelfIntersectionResult",
    "SelfProximityResult",
    "SweepContact",
    "SweepResult",
    "__version__",
    "collide",
    "collide_batch",
    "collision_free_step",
    "deform_sweep",
    "distance",
    "distance_batch",
    "is_convex",
    "load_mesh",
    "penetration",
    "random_collide",
    "run_scene",
    "self_intersections",
    "self_proximity",
    "sweep",
]
