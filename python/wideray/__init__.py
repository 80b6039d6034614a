"""wideray: wide-BVH ray tracing on the CPU, over numpy arrays.

    import numpy as np, wideray
    scene = wideray.Scene(vertices, faces)          # (n, 3) floats, (m, 3) integers
    t, prim_id, u, v = scene.intersect(origins, directions)
    blocked = scene.occluded(origins, directions, tfar=distances)
    image = wideray.render("scenes/default.json")   # (height, width, 3) float32, linear RGB
    vertices, faces = wideray.load_mesh("bunny.ply")  # OBJ, PLY, glTF/GLB

Misses have t = inf and prim_id = -1. Tracing releases the GIL and uses every core. Bad input raises
TypeError (dtype), ValueError (shape, values) or wideray.Error (a ValueError: what the library
refused, such as an unknown kernel name or an unreadable scene file). docs/library.md has the rest.
"""
import numpy as _np

from . import _wideray
from ._wideray import Error, best_isa

__version__ = _wideray.__version__
__all__ = ["Scene", "Hits", "render", "load_mesh", "Error", "best_isa", "__version__"]


class Hits(tuple):
    """(t, prim_id, u, v) of each ray's closest hit, as numpy arrays; geom_id names the mesh,
    instance or sphere set hit (the id add_mesh, add_instance or add_spheres returned; -1 on a miss)."""

    def __new__(cls, t, prim_id, u, v, geom_id):
        hits = super().__new__(cls, (t, prim_id, u, v))
        hits.geom_id = geom_id
        return hits

    t = property(lambda self: self[0])
    prim_id = property(lambda self: self[1])
    u = property(lambda self: self[2])
    v = property(lambda self: self[3])


class Scene:
    """Triangle meshes (and their instances and spheres) in a wide BVH, built on first use.
    Any number of threads may add to, build and trace one scene at once.

    Scene(vertices, faces) is a scene of one mesh, whose geom_id is 0. quality is "fast" or "high"
    (spatial splits); kernel and isa force a kernel ("single", "stream", ...) or an instruction set
    ("sse42", "avx2", "avx512") for tests and measurements.
    """

    def __init__(self, vertices=None, faces=None, *, quality="fast", bvh_width=8, kernel="", isa=""):
        self._scene = _wideray.Scene(quality, bvh_width, kernel, isa)
        if (vertices is None) != (faces is None):
            raise ValueError("give both vertices and faces, or neither")
        if vertices is not None:
            self.add_mesh(vertices, faces)

    def add_mesh(self, vertices, faces):
        """Adds a mesh of (n, 3) vertex positions and (m, 3) vertex indices; returns its geom_id."""
        return self._scene.add_mesh(_np.asarray(vertices), _np.asarray(faces))

    def add_instance(self, mesh_id, transform):
        """Places mesh mesh_id once more by a 3x4 or 4x4 object-to-world matrix; returns its geom_id."""
        return self._scene.add_instance(mesh_id, _np.asarray(transform))

    def add_spheres(self, centers, radii):
        """Adds spheres ((k, 3) centers, one radius or k); returns their geom_id (prim_id: the sphere)."""
        return self._scene.add_spheres(_np.asarray(centers), radii)

    def build(self):
        """Builds the BVH now (tracing builds it when needed)."""
        self._scene.build()

    def intersect(self, origins, directions, tnear=0.0, tfar=_np.inf):
        """Closest hits of rays o + t d with tnear <= t <= tfar: Hits (t, prim_id, u, v; .geom_id)."""
        return Hits(*self._scene.intersect(_np.asarray(origins), _np.asarray(directions), tnear, tfar))

    def occluded(self, origins, directions, tnear=0.0, tfar=_np.inf):
        """Whether anything lies within [tnear, tfar] of each ray: a bool array."""
        return self._scene.occluded(_np.asarray(origins), _np.asarray(directions), tnear, tfar)

    @property
    def bounds(self):
        """(min, max) corners of everything in the scene, as two arrays of 3."""
        b = self._scene.bounds
        return _np.array(b[:3]), _np.array(b[3:])

    @property
    def primitive_count(self):
        return self._scene.primitive_count

    @property
    def bytes(self):
        """Bytes of the acceleration structure."""
        return self._scene.bytes

    @property
    def description(self):
        return self._scene.description


def render(scene_file, width=0, height=0, spp=0, integrator="", threads=0):
    """Renders a scene file (wideray JSON, or an OBJ, PLY or glTF mesh, framed) as `wideray render`
    does, into a (height, width, 3) float32 array of linear RGB. 0 or "" keeps the file's setting."""
    return _wideray.render(str(scene_file), width, height, spp, integrator, threads)


def load_mesh(path):
    """Reads an OBJ, PLY or glTF/GLB mesh: (vertices (n, 3) float32, faces (m, 3) uint32)."""
    return _wideray.load_mesh(str(path))
