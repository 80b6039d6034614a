"""The Python bindings (python/wideray): hits against brute force, shapes and dtypes, errors, render."""
import os
import threading
import unittest

import numpy as np

import wideray


def grid_mesh(n=12, seed=0):
    """A bumpy height field over [-1, 1]^2 in the xz plane: (n+1)^2 vertices, 2 n^2 triangles."""
    rng = np.random.default_rng(seed)
    xs = np.linspace(-1, 1, n + 1)
    x, z = np.meshgrid(xs, xs)
    y = 0.2 * rng.random(x.shape)
    vertices = np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1)
    faces = []
    for i in range(n):
        for j in range(n):
            a, b, c, d = i * (n + 1) + j, i * (n + 1) + j + 1, (i + 1) * (n + 1) + j, (i + 1) * (n + 1) + j + 1
            faces += [[a, c, b], [b, c, d]]
    return vertices, np.array(faces)


def brute_force(vertices, faces, origins, directions):
    """Möller-Trumbore in float64 over every triangle: closest t, its face, and the smallest
    barycentric coordinate of that hit (how far it is from an edge)."""
    v0, v1, v2 = (vertices[faces[:, k]] for k in range(3))
    e1, e2 = v1 - v0, v2 - v0
    t_best = np.full(len(origins), np.inf)
    prim = np.full(len(origins), -1)
    margin = np.zeros(len(origins))
    for i, (o, d) in enumerate(zip(origins, directions)):
        p = np.cross(d, e2)
        det = np.einsum("ij,ij->i", e1, p)
        with np.errstate(divide="ignore", invalid="ignore"):
            s = o - v0
            u = np.einsum("ij,ij->i", s, p) / det
            q = np.cross(s, e1)
            v = q @ d / det
            t = np.einsum("ij,ij->i", e2, q) / det
        ok = (det != 0) & (u >= 0) & (v >= 0) & (u + v <= 1) & (t >= 0)
        if ok.any():
            k = np.argmin(np.where(ok, t, np.inf))
            t_best[i], prim[i] = t[k], k
            margin[i] = min(u[k], v[k], 1 - u[k] - v[k])
    return t_best, prim, margin


def rays_down(count, seed=1):
    rng = np.random.default_rng(seed)
    origins = np.column_stack([rng.uniform(-1.2, 1.2, count), np.full(count, 2.0), rng.uniform(-1.2, 1.2, count)])
    directions = np.column_stack([rng.uniform(-0.3, 0.3, count), -np.ones(count), rng.uniform(-0.3, 0.3, count)])
    return origins, directions


class Intersect(unittest.TestCase):
    def test_equals_brute_force(self):
        vertices, faces = grid_mesh()
        origins, directions = rays_down(600)
        for dtype in (np.float32, np.float64):
            scene = wideray.Scene(vertices.astype(dtype), faces.astype(np.int32))
            t, prim_id, u, v = scene.intersect(origins.astype(dtype), directions.astype(dtype))
            self.assertEqual(t.dtype, np.float32)
            self.assertEqual(prim_id.dtype, np.int64)
            want_t, want_prim, margin = brute_force(vertices.astype(np.float32).astype(np.float64), faces,
                                                    origins.astype(np.float32).astype(np.float64),
                                                    directions.astype(np.float32).astype(np.float64))
            clear = (margin > 1e-5) | (want_prim == -1)  # rays through an edge may take either triangle
            self.assertGreater(clear.sum(), 550)
            np.testing.assert_array_equal(prim_id[clear], want_prim[clear])
            hit = clear & (want_prim >= 0)
            self.assertGreater(hit.sum(), 250)
            np.testing.assert_allclose(t[hit], want_t[hit], rtol=1e-5)
            self.assertTrue(np.all(np.isinf(t[prim_id == -1])))
            self.assertTrue(np.all((u[hit] >= 0) & (v[hit] >= 0) & (u[hit] + v[hit] <= 1 + 1e-6)))

    def test_tnear_tfar_and_occluded(self):
        vertices, faces = grid_mesh()
        scene = wideray.Scene(vertices, faces)
        origins, directions = rays_down(300)
        t, prim_id, _, _ = scene.intersect(origins, directions)
        hit = prim_id >= 0
        np.testing.assert_array_equal(scene.occluded(origins, directions), hit)
        # tfar just short of each hit: nothing in the way; per-ray arrays and scalars both work.
        short = np.where(hit, t * 0.999, np.inf)
        self.assertFalse(scene.occluded(origins, directions, tfar=short).any())
        _, beyond, _, _ = scene.intersect(origins, directions, tnear=10.0)
        self.assertTrue(np.all(beyond == -1))
        self.assertEqual(scene.occluded(origins, directions).dtype, np.bool_)

    def test_instances_and_spheres(self):
        vertices, faces = grid_mesh(4)
        scene = wideray.Scene()
        mesh = scene.add_mesh(vertices, faces)
        moved = scene.add_instance(mesh, [[1, 0, 0, 5], [0, 1, 0, 0], [0, 0, 1, 0]])
        balls = scene.add_spheres([[10, 0, 0], [15, 0, 0]], 0.5)
        origins = np.array([[0.1, 2, 0.1], [5.1, 2, 0.1], [15, 2, 0]], dtype=np.float32)
        hits = scene.intersect(origins, np.tile([0, -1, 0], (3, 1)))
        np.testing.assert_array_equal(hits.geom_id, [mesh, moved, balls])
        self.assertEqual(hits.prim_id[0], hits.prim_id[1])
        self.assertEqual(hits.prim_id[2], 1)
        self.assertAlmostEqual(float(hits.t[2]), 1.5, places=5)
        low, high = scene.bounds
        self.assertAlmostEqual(high[0], 15.5, places=5)

    def test_many_rays_in_parallel_agree_with_few(self):
        vertices, faces = grid_mesh(40)
        scene = wideray.Scene(vertices, faces, quality="high")
        origins, directions = rays_down(100_000, seed=3)
        t, prim_id, _, _ = scene.intersect(origins, directions)
        for k in range(0, 100_000, 9973):
            t1, p1, _, _ = scene.intersect(origins[k:k + 1], directions[k:k + 1])
            self.assertEqual(p1[0], prim_id[k])
            self.assertEqual(t1[0], t[k])

    def test_threads_share_a_scene(self):
        vertices, faces = grid_mesh(20)
        scene = wideray.Scene(vertices, faces)
        origins, directions = rays_down(20_000, seed=4)
        want = scene.intersect(origins, directions).prim_id
        results = [None] * 4

        def trace(i):
            results[i] = scene.intersect(origins, directions).prim_id

        threads = [threading.Thread(target=trace, args=(i,)) for i in range(4)]
        for th in threads:
            th.start()
        for th in threads:
            th.join()
        for r in results:
            np.testing.assert_array_equal(r, want)


    def test_threads_add_while_others_trace(self):
        # Additions (here instances far from the rays) rebuild the scene between traces, never under one.
        vertices, faces = grid_mesh(20)
        scene = wideray.Scene(vertices, faces)
        origins, directions = rays_down(20_000, seed=5)
        want = scene.intersect(origins, directions).prim_id
        results, errors = [], []

        def trace():
            try:
                for _ in range(5):
                    results.append(scene.intersect(origins, directions).prim_id)
            except Exception as e:  # reported below: a thread's exception would otherwise vanish
                errors.append(e)

        def add():
            try:
                for k in range(5):
                    scene.add_instance(0, [[1, 0, 0, 100 + 10 * k], [0, 1, 0, 0], [0, 0, 1, 0]])
                    scene.build()
            except Exception as e:
                errors.append(e)

        threads = [threading.Thread(target=trace) for _ in range(3)] + [threading.Thread(target=add)]
        for th in threads:
            th.start()
        for th in threads:
            th.join()
        self.assertEqual(errors, [])
        self.assertEqual(len(results), 15)
        for r in results:
            np.testing.assert_array_equal(r, want)
        self.assertEqual(scene.primitive_count, 6 * len(faces))


class BadInput(unittest.TestCase):
    def setUp(self):
        self.vertices, self.faces = grid_mesh(2)

    def test_shapes_and_dtypes(self):
        with self.assertRaisesRegex(ValueError, r"vertices must have shape \(n, 3\), not \(9, 2\)"):
            wideray.Scene(self.vertices[:, :2], self.faces)
        with self.assertRaisesRegex(TypeError, "faces must be an integer array"):
            wideray.Scene(self.vertices, self.faces.astype(np.float32))
        with self.assertRaisesRegex(ValueError, "faces\\[1\\] refers to vertex 99"):
            faces = self.faces.copy()
            faces[1, 2] = 99
            wideray.Scene(self.vertices, faces)
        with self.assertRaisesRegex(ValueError, "refers to vertex -1"):
            wideray.Scene(self.vertices, -np.ones((1, 3), dtype=np.int64))
        scene = wideray.Scene(self.vertices, self.faces)
        with self.assertRaisesRegex(ValueError, "origins has 2 rows but directions has 3"):
            scene.intersect(np.zeros((2, 3)), np.ones((3, 3)))
        with self.assertRaisesRegex(TypeError, "origins must be an array of real numbers"):
            scene.intersect(np.array([["a", "b", "c"]]), np.ones((1, 3)))
        with self.assertRaisesRegex(ValueError, r"tfar must be a number or have shape \(2,\)"):
            scene.occluded(np.zeros((2, 3)), np.ones((2, 3)), tfar=np.ones(3))
        with self.assertRaisesRegex(ValueError, "give both vertices and faces"):
            wideray.Scene(self.vertices)

    def test_library_errors(self):
        with self.assertRaisesRegex(wideray.Error, "positions\\[4\\] \\(vertex 1\\) is nan"):
            vertices = self.vertices.copy()
            vertices[1, 1] = np.nan
            wideray.Scene(vertices, self.faces)
        with self.assertRaisesRegex(wideray.Error, "SceneOptions::kernel: no kernel is named 'warp'"):
            wideray.Scene(self.vertices, self.faces, kernel="warp").build()
        with self.assertRaisesRegex(ValueError, "quality must be 'fast' or 'high'"):
            wideray.Scene(self.vertices, self.faces, quality="best")
        self.assertTrue(issubclass(wideray.Error, ValueError))


class Render(unittest.TestCase):
    def test_render_scene_file(self):
        scene_file = os.path.join(os.environ.get("WIDERAY_SOURCE_DIR", "."), "scenes", "default.json")
        image = wideray.render(scene_file, width=40, height=30, spp=1)
        self.assertEqual(image.shape, (30, 40, 3))
        self.assertEqual(image.dtype, np.float32)
        self.assertTrue(np.isfinite(image).all())
        self.assertGreater(image.mean(), 0.0)
        with self.assertRaisesRegex(wideray.Error, "missing.json"):
            wideray.render("missing.json")


if __name__ == "__main__":
    unittest.main()
