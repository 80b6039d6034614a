// wideray._wideray: the public C++ API (include/wideray/) over numpy arrays. python/wideray/__init__.py
// is the documented surface; this module checks shapes and dtypes, converts, and releases the GIL
// while building and tracing.
#include <functional>
#include <mutex>
#include <shared_mutex>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <tbb/parallel_for.h>

#include "wideray/wideray.h"

namespace py = pybind11;

namespace {

/// A wideray::Scene that Python threads may share: the C++ scene may be traced by many threads but
/// not while it is built or added to, and Python code has no reason to know that. Additions and builds
/// take the lock alone, tracing shares it; it is taken with the GIL released, so a thread waiting for
/// it never blocks one that holds it.
struct LockedScene {
    explicit LockedScene(const wideray::SceneOptions& options) : scene(options) {}
    wideray::Scene scene;
    mutable std::shared_mutex mutex;

    template <typename Change>
    auto change(const Change& f) {
        py::gil_scoped_release release;
        std::unique_lock lock(mutex);
        return f(scene);
    }
    /// Calls f(scene) on the built scene (building it first if an addition invalidated it).
    template <typename Read>
    auto read(const Read& f) {
        py::gil_scoped_release release;
        for (;;) {
            {
                std::shared_lock lock(mutex);
                if (scene.built()) return std::invoke(f, std::as_const(scene));
            }
            std::unique_lock lock(mutex);
            if (!scene.built()) scene.build();
        }
    }
};

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

/// `array` as float32 of shape (n, columns), checked: a real numeric dtype and that shape.
FloatArray floatRows(const py::array& array, const char* name, py::ssize_t columns) {
    const char kind = array.dtype().kind();
    if (kind != 'f' && kind != 'i' && kind != 'u')
        throw py::type_error(std::string(name) + " must be an array of real numbers, not dtype " +
                             std::string(py::str(array.dtype())));
    if (array.ndim() != 2 || array.shape(1) != columns)
        throw py::value_error(std::string(name) + " must have shape (n, " + std::to_string(columns) + "), not " +
                              std::string(py::str(py::getattr(array, "shape"))));
    return FloatArray::ensure(array);
}

/// Faces as uint32 triples, checked against the vertex count.
std::vector<uint32_t> faceIndices(const py::array& faces, py::ssize_t vertices) {
    const char kind = faces.dtype().kind();
    if (kind != 'i' && kind != 'u')
        throw py::type_error("faces must be an integer array, not dtype " + std::string(py::str(faces.dtype())));
    if (faces.ndim() != 2 || faces.shape(1) != 3)
        throw py::value_error("faces must have shape (m, 3), not " + std::string(py::str(py::getattr(faces, "shape"))));
    auto values = py::array_t<int64_t, py::array::c_style | py::array::forcecast>::ensure(faces);
    std::vector<uint32_t> indices(size_t(values.size()));
    const int64_t* v = values.data();
    for (size_t i = 0; i < indices.size(); ++i) {
        if (v[i] < 0 || v[i] >= vertices)
            throw py::value_error("faces[" + std::to_string(i / 3) + "] refers to vertex " + std::to_string(v[i]) +
                                  ", but there are " + std::to_string(vertices) + " vertices");
        indices[i] = uint32_t(v[i]);
    }
    return indices;
}

/// A number given once for all n items, or n numbers.
std::vector<float> broadcast(const py::object& value, size_t n, const char* name) {
    py::array array = py::array::ensure(value);
    if (!array || (array.dtype().kind() != 'f' && array.dtype().kind() != 'i' && array.dtype().kind() != 'u'))
        throw py::type_error(std::string(name) + " must be a number or an array of numbers");
    auto floats = FloatArray::ensure(array);
    if (floats.ndim() == 0) return std::vector<float>(n, *floats.data());
    if (floats.ndim() != 1 || size_t(floats.shape(0)) != n)
        throw py::value_error(std::string(name) + " must be a number or have shape (" + std::to_string(n) + ",)");
    return std::vector<float>(floats.data(), floats.data() + n);
}

/// Checked ray arrays: origins and directions (n, 3) as float32, tnear and tfar broadcast to n.
struct RayArrays {
    FloatArray origins, directions;
    std::vector<float> tnear, tfar;
    size_t size() const { return tnear.size(); }
    wideray::Ray ray(size_t i) const {
        const float *o = origins.data() + 3 * i, *d = directions.data() + 3 * i;
        return {o[0], o[1], o[2], d[0], d[1], d[2], tnear[i], tfar[i], 0.0f};
    }
};

RayArrays rayArrays(const py::array& origins, const py::array& directions, const py::object& tnear,
                    const py::object& tfar) {
    RayArrays rays{floatRows(origins, "origins", 3), floatRows(directions, "directions", 3), {}, {}};
    if (rays.origins.shape(0) != rays.directions.shape(0))
        throw py::value_error("origins has " + std::to_string(rays.origins.shape(0)) + " rows but directions has " +
                              std::to_string(rays.directions.shape(0)));
    const size_t n = size_t(rays.origins.shape(0));
    rays.tnear = broadcast(tnear, n, "tnear");
    rays.tfar = broadcast(tfar, n, "tfar");
    return rays;
}

/// Rays per task: each task makes its rays, traces them on its thread and writes its results, so
/// conversion runs in parallel and in cache like the tracing.
constexpr size_t kRaysPerTask = 4096;

/// Calls trace(scene, rays, first) for tasks of up to kRaysPerTask rays on every core, without the GIL.
template <typename Trace>
void traceInTasks(LockedScene& locked, const RayArrays& arrays, const Trace& trace) {
    locked.read([&](const wideray::Scene& scene) {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, arrays.size(), kRaysPerTask),
                          [&](const tbb::blocked_range<size_t>& r) {
                              thread_local std::vector<wideray::Ray> rays;
                              rays.resize(r.size());
                              for (size_t i = 0; i < r.size(); ++i) rays[i] = arrays.ray(r.begin() + i);
                              trace(scene, std::span<const wideray::Ray>(rays), r.begin());
                          });
    });
}

py::tuple intersect(LockedScene& scene, const py::array& origins, const py::array& directions,
                    const py::object& tnear, const py::object& tfar) {
    const RayArrays arrays = rayArrays(origins, directions, tnear, tfar);
    const py::ssize_t n = py::ssize_t(arrays.size());
    py::array_t<float> t(n), u(n), v(n);
    py::array_t<int64_t> prim(n), geom(n);
    float *pt = t.mutable_data(), *pu = u.mutable_data(), *pv = v.mutable_data();
    int64_t *pp = prim.mutable_data(), *pg = geom.mutable_data();
    traceInTasks(scene, arrays, [&](const wideray::Scene& scene, std::span<const wideray::Ray> rays, size_t first) {
        thread_local std::vector<wideray::Hit> hits;
        hits.resize(rays.size());
        scene.intersect(rays, hits, wideray::Coherence::Incoherent, wideray::Threading::Caller);
        for (size_t i = 0; i < rays.size(); ++i) {
            const wideray::Hit& h = hits[i];
            const size_t k = first + i;
            pt[k] = h.t, pu[k] = h.u, pv[k] = h.v;
            pp[k] = h.valid() ? int64_t(h.primId) : -1;
            pg[k] = h.valid() ? int64_t(h.geomId) : -1;
        }
    });
    return py::make_tuple(t, prim, u, v, geom);
}

py::array_t<bool> occluded(LockedScene& scene, const py::array& origins, const py::array& directions,
                           const py::object& tnear, const py::object& tfar) {
    const RayArrays arrays = rayArrays(origins, directions, tnear, tfar);
    py::array_t<bool> result(py::ssize_t(arrays.size()));
    bool* out = result.mutable_data();
    traceInTasks(scene, arrays, [&](const wideray::Scene& scene, std::span<const wideray::Ray> rays, size_t first) {
        thread_local std::vector<uint8_t> answers;
        answers.resize(rays.size());
        scene.occluded(rays, answers, wideray::Coherence::Incoherent, wideray::Threading::Caller);
        for (size_t i = 0; i < rays.size(); ++i) out[first + i] = answers[i] != 0;
    });
    return result;
}

wideray::SceneOptions sceneOptions(const std::string& quality, int bvhWidth, const std::string& kernel,
                                   const std::string& isa) {
    wideray::SceneOptions options;
    if (quality == "high") options.quality = wideray::BuildQuality::High;
    else if (quality != "fast") throw py::value_error("quality must be 'fast' or 'high', not '" + quality + "'");
    options.bvhWidth = bvhWidth;
    options.kernel = kernel;
    options.isa = isa;
    return options;
}

uint32_t addMesh(LockedScene& scene, const py::array& vertices, const py::array& faces) {
    const FloatArray v = floatRows(vertices, "vertices", 3);
    const std::vector<uint32_t> indices = faceIndices(faces, v.shape(0));
    const std::span<const float> positions(v.data(), size_t(v.size()));
    return scene.change([&](wideray::Scene& s) { return s.addTriangleMesh(positions, indices); });
}

py::array_t<float> render(const std::string& file, int width, int height, int spp, const std::string& integrator,
                          int threads) {
    wideray::RenderRequest request{width, height, spp, integrator, threads};
    wideray::RenderedImage image;
    {
        py::gil_scoped_release release;
        image = wideray::renderSceneFile(file, request);
    }
    py::array_t<float> pixels({py::ssize_t(image.height), py::ssize_t(image.width), py::ssize_t(3)});
    std::copy(image.rgb.begin(), image.rgb.end(), pixels.mutable_data());
    return pixels;
}

} // namespace

PYBIND11_MODULE(_wideray, m) {
    m.doc() = "wideray's C++ API over numpy arrays (use the wideray package)";
    py::register_exception<wideray::Error>(m, "Error", PyExc_ValueError);
    m.attr("__version__") = wideray::version();
    m.def("best_isa", &wideray::bestIsaName);

    py::class_<LockedScene>(m, "Scene")
        .def(py::init([](const std::string& quality, int bvhWidth, const std::string& kernel, const std::string& isa) {
                 return std::make_unique<LockedScene>(sceneOptions(quality, bvhWidth, kernel, isa));
             }),
             py::arg("quality"), py::arg("bvh_width"), py::arg("kernel"), py::arg("isa"))
        .def("add_mesh", &addMesh)
        .def("add_instance",
             [](LockedScene& scene, uint32_t mesh, const py::array& matrix) {
                 auto m = FloatArray::ensure(matrix);
                 if (!m || m.ndim() != 2 || m.shape(1) != 4 || (m.shape(0) != 3 && m.shape(0) != 4))
                     throw py::value_error("transform must be a 3x4 or 4x4 matrix of numbers");
                 wideray::Transform t;
                 for (int r = 0; r < 3; ++r)
                     for (int c = 0; c < 4; ++c) t.m[r][c] = m.at(r, c);
                 return scene.change([&](wideray::Scene& s) { return s.addInstance(mesh, t); });
             })
        .def("add_spheres",
             [](LockedScene& scene, const py::array& centers, const py::object& radii) {
                 const FloatArray c = floatRows(centers, "centers", 3);
                 const std::vector<float> r = broadcast(radii, size_t(c.shape(0)), "radii");
                 const std::span<const float> centerValues(c.data(), size_t(c.size()));
                 return scene.change([&](wideray::Scene& s) { return s.addSpheres(centerValues, r); });
             })
        .def("build", [](LockedScene& scene) { scene.change([](wideray::Scene& s) { s.build(); }); })
        .def("intersect", &intersect)
        .def("occluded", &occluded)
        .def_property_readonly("bounds", [](LockedScene& s) { return s.read(&wideray::Scene::bounds); })
        .def_property_readonly("primitive_count", [](LockedScene& s) { return s.read(&wideray::Scene::primitiveCount); })
        .def_property_readonly("bytes", [](LockedScene& s) { return s.read(&wideray::Scene::bytes); })
        .def_property_readonly("description", [](LockedScene& s) { return s.read(&wideray::Scene::description); });

    m.def("render", &render);
    m.def("load_mesh", [](const std::string& path) {
        wideray::MeshArrays mesh;
        {
            py::gil_scoped_release release;
            mesh = wideray::loadMeshFile(path);
        }
        py::array_t<float> vertices({py::ssize_t(mesh.positions.size() / 3), py::ssize_t(3)});
        py::array_t<uint32_t> faces({py::ssize_t(mesh.indices.size() / 3), py::ssize_t(3)});
        std::copy(mesh.positions.begin(), mesh.positions.end(), vertices.mutable_data());
        std::copy(mesh.indices.begin(), mesh.indices.end(), faces.mutable_data());
        return py::make_tuple(vertices, faces);
    });
}
