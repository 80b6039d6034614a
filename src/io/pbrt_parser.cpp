// pbrt scene files -> SceneDescription (io/pbrt_parser.h). The reader walks the directives with
// pbrt's graphics state (transform, material, area light) and stacks; pbrt_materials.cpp maps the
// materials and textures.
#include "io/pbrt_parser.h"

#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <fmt/core.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "core/error.h"
#include "core/ray.h"
#include "io/image_io.h"
#include "io/mesh_io.h"
#include "io/pbrt_materials.h"
#include "io/pbrt_params.h"
#include "io/pbrt_tokenizer.h"
#include "io/scene_parser.h"

namespace wideray {
namespace {

constexpr int kMaxIncludeDepth = 32;
constexpr size_t kMaxIncludes = 100000;          // files read by Include/Import in one scene
constexpr size_t kMaxInstances = 10'000'000;     // placed meshes, ObjectInstance copies included
constexpr size_t kMaxTriangleLights = 32;        // triangles of one mesh under an AreaLightSource

const std::set<std::string> kParamTypes = {"integer", "float",   "point",  "point2", "point3", "vector", "vector2",
                                           "vector3", "normal",  "normal3", "rgb",   "color",  "spectrum",
                                           "blackbody", "bool", "string", "texture"};

class PbrtReader {
public:
    explicit PbrtReader(const std::filesystem::path& file) : mainFile_(file) {}

    SceneDescription read(const std::string& text) {
        scene_.file = mainFile_;
        scene_.image = {1280, 720, 16};
        scene_.render.integrator = Integrator::Path;
        scene_.render.maxDepth = 5;
        scene_.materials.push_back(pbrtDefaultMaterial());
        state_.material = 0;
        files_.emplace_back(text, mainFile_.string(), mainFile_.parent_path());
        while (!files_.empty()) {
            PbrtToken t = tokens().next();
            if (t.kind == PbrtToken::Kind::End) {
                files_.pop_back();
                continue;
            }
            if (t.kind != PbrtToken::Kind::Identifier) fail(t.line, "expected a directive, got '" + t.text + "'");
            try {
                directive(t);
            } catch (const PbrtLineError& e) {
                fail(e.line, e.message);
            }
        }
        if (!sawCamera_) warn(0, "camera", "no Camera directive: the default camera (at the origin, looking down +z)");
        finishCamera();
        return std::move(scene_);
    }

private:
    struct File {
        File(std::string text, std::string name, std::filesystem::path dir)
            : tokenizer(std::move(text), std::move(name)), folder(std::move(dir)) {}
        PbrtTokenizer tokenizer;
        std::filesystem::path folder;
    };
    struct AreaLight {
        glm::vec3 radiance{1.0f};
        bool twoSided = false;
        int line = 0;
    };
    struct State {
        glm::mat4 ctm{1.0f};
        uint32_t material = 0;
        std::optional<AreaLight> areaLight;
        bool reverseOrientation = false;
    };
    struct ObjectShape {
        uint32_t mesh;
        glm::mat4 transform;
        uint32_t material;
    };

    PbrtTokenizer& tokens() { return files_.back().tokenizer; }
    const std::string& fileName() { return files_.back().tokenizer.file(); }

    [[noreturn]] void fail(int line, const std::string& message) {
        throw InputError(fileName(), "line " + std::to_string(line), message);
    }
    /// Reported once per `key`: "FILE:LINE: message".
    void warn(int line, const std::string& key, const std::string& message) {
        if (!warned_.insert(key).second) return;
        scene_.warnings.push_back(line > 0 ? fmt::format("{}:line {}: {}", fileName(), line, message)
                                           : fmt::format("{}: {}", mainFile_.string(), message));
    }
    void reportUnused(const PbrtParams& params, const std::string& what) {
        for (const PbrtParam* p : params.unused())
            warn(p->line, what + "/" + p->name, fmt::format("{}: parameter \"{} {}\" is not supported; ignored", what, p->type, p->name));
    }

    std::string string(int line) {
        PbrtToken t = tokens().next();
        if (t.kind != PbrtToken::Kind::String) fail(line, "expected a quoted string, got '" + t.text + "'");
        return t.text;
    }
    /// n numbers, bare or in one pair of brackets.
    std::vector<double> numbers(int line, size_t n) {
        const bool bracketed = tokens().peek().kind == PbrtToken::Kind::OpenBracket;
        if (bracketed) tokens().next();
        std::vector<double> values;
        for (size_t i = 0; i < n; ++i) {
            PbrtToken t = tokens().next();
            if (t.kind != PbrtToken::Kind::Number)
                fail(t.line ? t.line : line, fmt::format("expected {} numbers, got '{}' after {}", n, t.text, i));
            values.push_back(t.number);
        }
        if (bracketed && tokens().next().kind != PbrtToken::Kind::CloseBracket) fail(line, "expected ']'");
        return values;
    }

    PbrtParams params() {
        PbrtParams out;
        while (tokens().peek().kind == PbrtToken::Kind::String) {
            PbrtToken decl = tokens().next();
            std::istringstream words(decl.text);
            PbrtParam p;
            p.line = decl.line;
            std::string extra;
            if (!(words >> p.type >> p.name) || (words >> extra))
                fail(decl.line, "expected a parameter declaration \"type name\", got \"" + decl.text + "\"");
            if (!kParamTypes.count(p.type)) fail(decl.line, "unknown parameter type '" + p.type + "' in \"" + decl.text + "\"");
            auto value = [&](const PbrtToken& t) {
                if (t.kind == PbrtToken::Kind::Number) p.numbers.push_back(t.number);
                else if (t.kind == PbrtToken::Kind::String || (t.kind == PbrtToken::Kind::Identifier && (t.text == "true" || t.text == "false")))
                    p.strings.push_back(t.text);
                else fail(t.line, "parameter \"" + decl.text + "\": unexpected '" + t.text + "'");
            };
            if (tokens().peek().kind == PbrtToken::Kind::OpenBracket) {
                tokens().next();
                for (;;) {
                    PbrtToken t = tokens().next();
                    if (t.kind == PbrtToken::Kind::CloseBracket) break;
                    if (t.kind == PbrtToken::Kind::End) fail(decl.line, "parameter \"" + decl.text + "\": '[' not closed");
                    value(t);
                }
            } else {
                value(tokens().next());
            }
            const bool textual = p.type == "string" || p.type == "texture" || p.type == "bool";
            if (textual ? !p.numbers.empty() : (!p.strings.empty() && p.type != "spectrum"))
                fail(decl.line, "parameter \"" + decl.text + "\" has values of the wrong kind");
            out.list.push_back(std::move(p));
        }
        return out;
    }

    /// Skips a directive wideray has no use for: its arguments up to the next directive.
    void skipArguments() {
        for (;;) {
            const PbrtToken& t = tokens().peek();
            const bool value = t.kind == PbrtToken::Kind::Identifier && (t.text == "true" || t.text == "false");
            if (t.kind == PbrtToken::Kind::End || (t.kind == PbrtToken::Kind::Identifier && !value)) return;
            tokens().next();
        }
    }

    void directive(const PbrtToken& t) {
        const std::string& d = t.text;
        const int line = t.line;
        if (d == "AttributeBegin" || d == "TransformBegin") stack_.push_back(state_);
        else if (d == "AttributeEnd" || d == "TransformEnd") {
            if (stack_.empty()) fail(line, d + " without a matching begin");
            const State saved = stack_.back();
            stack_.pop_back();
            if (d == "TransformEnd") state_.ctm = saved.ctm;
            else state_ = saved;
        } else if (d == "Identity") state_.ctm = glm::mat4(1.0f);
        else if (d == "Translate") {
            const auto v = numbers(line, 3);
            state_.ctm = glm::translate(state_.ctm, glm::vec3(v[0], v[1], v[2]));
        } else if (d == "Scale") {
            const auto v = numbers(line, 3);
            state_.ctm = glm::scale(state_.ctm, glm::vec3(v[0], v[1], v[2]));
        } else if (d == "Rotate") {
            const auto v = numbers(line, 4);
            const glm::vec3 axis(v[1], v[2], v[3]);
            if (glm::length(axis) == 0.0f) fail(line, "Rotate about a zero axis");
            state_.ctm = glm::rotate(state_.ctm, glm::radians(float(v[0])), axis);
        } else if (d == "LookAt") {
            const auto v = numbers(line, 9);
            state_.ctm = state_.ctm * lookAt(line, {v[0], v[1], v[2]}, {v[3], v[4], v[5]}, {v[6], v[7], v[8]});
        } else if (d == "Transform" || d == "ConcatTransform") {
            const auto v = numbers(line, 16);
            float m[16];
            for (int i = 0; i < 16; ++i) m[i] = float(v[size_t(i)]);
            // pbrt lists the matrix column by column, as glm stores it.
            const glm::mat4 matrix = glm::make_mat4(m);
            state_.ctm = d == "Transform" ? matrix : state_.ctm * matrix;
        } else if (d == "CoordinateSystem") namedSpaces_[string(line)] = state_.ctm;
        else if (d == "CoordSysTransform") {
            const std::string name = string(line);
            if (name == "camera") state_.ctm = glm::inverse(cameraFromWorld_);
            else if (auto it = namedSpaces_.find(name); it != namedSpaces_.end()) state_.ctm = it->second;
            else warn(line, "coordsys/" + name, "CoordSysTransform: no coordinate system named '" + name + "'; ignored");
        } else if (d == "ReverseOrientation") state_.reverseOrientation = !state_.reverseOrientation;
        else if (d == "Camera") camera(line);
        else if (d == "Film") film(line);
        else if (d == "Sampler") sampler(line);
        else if (d == "Integrator") integrator(line);
        else if (d == "WorldBegin") {
            // pbrt's world starts with an identity transform; ours adds the mirror that makes pbrt's
            // left-handed camera image ours (finishCamera).
            namedSpaces_["camera"] = glm::inverse(cameraFromWorld_);
            state_.ctm = glm::mat4(1.0f);
        } else if (d == "WorldEnd") {
            // pbrt-v3 closes the world here; everything before it is already in the scene.
        }
        else if (d == "Include" || d == "Import") include(line, d);
        else if (d == "Texture") texture(line);
        else if (d == "Material") {
            const std::string type = string(line);
            state_.material = addMaterial(type, "", params(), line);
        } else if (d == "MakeNamedMaterial") {
            const std::string name = string(line);
            PbrtParams p = params();
            const PbrtParam* type = p.find("type");
            if (!type || type->strings.size() != 1) fail(line, "MakeNamedMaterial \"" + name + "\" needs \"string type\"");
            namedMaterials_[name] = addMaterial(type->strings[0], name, p, line);
        } else if (d == "NamedMaterial") {
            const std::string name = string(line);
            auto it = namedMaterials_.find(name);
            if (it == namedMaterials_.end()) fail(line, "NamedMaterial \"" + name + "\" was not defined by MakeNamedMaterial");
            state_.material = it->second;
        } else if (d == "Shape") shape(line);
        else if (d == "LightSource") lightSource(line);
        else if (d == "AreaLightSource") areaLightSource(line);
        else if (d == "ObjectBegin") {
            const std::string name = string(line);
            if (currentObject_) fail(line, "ObjectBegin \"" + name + "\" inside another ObjectBegin");
            stack_.push_back(state_);
            currentObject_ = &objects_[name];
            currentObject_->clear();
        } else if (d == "ObjectEnd") {
            if (!currentObject_ || stack_.empty()) fail(line, "ObjectEnd without ObjectBegin");
            currentObject_ = nullptr;
            state_ = stack_.back();
            stack_.pop_back();
        } else if (d == "ObjectInstance") {
            const std::string name = string(line);
            auto it = objects_.find(name);
            if (it == objects_.end()) fail(line, "ObjectInstance \"" + name + "\" names no object");
            // pbrt has no nested instancing; allowing it here would also let an object grow by copies
            // of itself.
            if (currentObject_) fail(line, "ObjectInstance \"" + name + "\" inside ObjectBegin (nested instancing is not supported)");
            for (const ObjectShape& s : it->second) place(line, s.mesh, state_.ctm * s.transform, s.material);
        } else if (d == "PixelFilter" || d == "Accelerator" || d == "MakeNamedMedium" || d == "MediumInterface" ||
                   d == "ColorSpace" || d == "Option" || d == "Attribute" || d == "ActiveTransform" ||
                   d == "TransformTimes") {
            skipArguments();
            warn(line, "directive/" + d, d + " is not supported; skipped");
        } else {
            fail(line, "unknown directive '" + d + "'");
        }
    }

    /// pbrt's LookAt: the world-to-camera transform of an eye looking at a point.
    glm::mat4 lookAt(int line, glm::vec3 eye, glm::vec3 at, glm::vec3 up) {
        const glm::vec3 dir = at - eye;
        if (glm::length(dir) == 0.0f || glm::length(glm::cross(up, dir)) == 0.0f)
            fail(line, "LookAt: the eye and the point coincide, or up is parallel to the view");
        const glm::vec3 d = glm::normalize(dir), right = glm::normalize(glm::cross(glm::normalize(up), d));
        const glm::vec3 newUp = glm::cross(d, right);
        glm::mat4 cameraToWorld(glm::vec4(right, 0), glm::vec4(newUp, 0), glm::vec4(d, 0), glm::vec4(eye, 1));
        return glm::inverse(cameraToWorld);
    }

    void include(int line, const std::string& directive) {
        const std::string name = string(line);
        if (files_.size() >= size_t(kMaxIncludeDepth)) fail(line, "Include nested more than 32 deep");
        if (++includeCount_ > kMaxIncludes) fail(line, fmt::format("more than {} files included", kMaxIncludes));
        std::filesystem::path path = name;
        if (path.is_relative()) path = files_.back().folder / path;
        std::error_code ec;
        if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
            fail(line, directive + ": cannot open " + path.string() + " (not a regular file)");
        std::ifstream in(path, std::ios::binary);
        if (!in) fail(line, directive + ": cannot open " + path.string());
        std::ostringstream text;
        text << in.rdbuf();
        files_.emplace_back(text.str(), path.string(), path.parent_path());
    }

    void camera(int line) {
        const std::string type = string(line);
        PbrtParams p = params();
        sawCamera_ = true;
        cameraFromWorld_ = state_.ctm;
        if (type != "perspective") warn(line, "camera/" + type, "Camera \"" + type + "\" is not supported; a perspective camera instead");
        fov_ = p.number("fov", fov_);
        if (!(fov_ > 0.0f && fov_ < 180.0f)) fail(line, "Camera \"fov\" must be between 0 and 180 degrees");
        scene_.camera.aperture = std::max(0.0f, p.number("lensradius", 0.0f));
        scene_.camera.focusDistance = std::max(0.0f, p.number("focaldistance", 0.0f));
        reportUnused(p, "Camera");
    }

    void film(int line) {
        string(line);
        PbrtParams p = params();
        auto resolution = [&](const char* name, int& out) {
            if (const PbrtParam* r = p.find(name)) {
                if (r->numbers.size() != 1 || r->numbers[0] < 1 || r->numbers[0] > 65536)
                    fail(r->line, fmt::format("Film \"{}\" must be one number from 1 to 65536", name));
                out = int(r->numbers[0]);
            }
        };
        resolution("xresolution", scene_.image.width);
        resolution("yresolution", scene_.image.height);
        p.find("filename");  // the output is named on wideray's command line
        reportUnused(p, "Film");
    }

    void sampler(int line) {
        string(line);
        PbrtParams p = params();
        if (const PbrtParam* n = p.find("pixelsamples")) {
            if (n->numbers.size() != 1 || n->numbers[0] < 1 || n->numbers[0] > 1 << 20)
                fail(n->line, "Sampler \"pixelsamples\" must be one number from 1 to 2^20");
            scene_.image.samplesPerPixel = int(n->numbers[0]);
        }
        reportUnused(p, "Sampler");
    }

    void integrator(int line) {
        const std::string type = string(line);
        PbrtParams p = params();
        if (type == "whitted" || type == "directlighting") scene_.render.integrator = Integrator::Whitted;
        else {
            scene_.render.integrator = Integrator::Path;
            if (type != "path" && type != "volpath")
                warn(line, "integrator/" + type, "Integrator \"" + type + "\" is not supported; the path tracer instead");
        }
        if (const PbrtParam* depth = p.find("maxdepth")) {
            if (depth->numbers.size() != 1 || depth->numbers[0] < 0 || depth->numbers[0] > 1000)
                fail(depth->line, "Integrator \"maxdepth\" must be one number from 0 to 1000");
            scene_.render.maxDepth = std::max(1, int(depth->numbers[0]));
        }
        reportUnused(p, "Integrator");
    }

    void texture(int line) {
        const std::string name = string(line), valueType = string(line), type = string(line);
        PbrtParams p = params();
        textures_[name] = pbrtTexture(type, valueType, p, files_.back().folder, line, textureImages_,
                                      [&](int l, const std::string& key, const std::string& m) { warn(l, key, m); });
        reportUnused(p, "Texture \"" + type + "\"");
    }

    uint32_t addMaterial(const std::string& type, const std::string& name, const PbrtParams& p, int line) {
        PbrtMaterialContext context{textures_, [&](int l, const std::string& key, const std::string& m) { warn(l, key, m); }};
        std::optional<Material> material = pbrtMaterial(type, p, line, context);
        reportUnused(p, "Material \"" + type + "\"");
        if (!material) return kInvalidId;  // invisible: shapes with it are left out
        material->name = name.empty() ? fmt::format("{}@{}", type, line) : name;
        scene_.materials.push_back(std::move(*material));
        return uint32_t(scene_.materials.size() - 1);
    }

    /// A shape's triangles placed in the world (or recorded in the object being defined).
    void place(int line, uint32_t mesh, const glm::mat4& transform, uint32_t material) {
        if (scene_.instances.size() + (currentObject_ ? currentObject_->size() : 0) >= kMaxInstances)
            fail(line, fmt::format("more than {} shapes and object instances", kMaxInstances));
        if (currentObject_) {
            currentObject_->push_back({mesh, transform, material});
            return;
        }
        if (material == kInvalidId) return;
        scene_.instances.push_back({mesh, transform, material});
    }

    void shape(int line) {
        const std::string type = string(line);
        PbrtParams p = params();
        if (state_.material == kInvalidId) {
            for (const PbrtParam& param : p.list) param.used = true;
            warn(line, "shape/invisible", "shapes of invisible materials (pbrt-v4 \"interface\", uber with opacity 0) are left out");
            return;
        }
        if (type == "sphere") {
            const float radius = p.number("radius", 1.0f);
            if (!(radius > 0.0f)) fail(line, "Shape \"sphere\": radius must be positive");
            for (const char* partial : {"zmin", "zmax", "phimax"})
                if (p.has(partial)) warn(line, std::string("sphere/") + partial, "Shape \"sphere\": partial spheres are not supported; whole spheres instead");
            if (state_.areaLight) sphereLight(line, radius);
            else if (currentObject_) {
                warn(line, "object/analytic", "spheres and cylinders inside ObjectBegin are not supported; skipped");
            } else {
                AnalyticObject ball;
                ball.shape = AnalyticShape::Ellipsoid;
                ball.transform = state_.ctm * glm::scale(glm::mat4(1.0f), glm::vec3(radius));
                ball.material = state_.material;
                scene_.analytics.push_back(ball);
            }
            reportUnused(p, "Shape \"sphere\"");
            return;
        }
        if (type == "cylinder") {
            // pbrt's open cylinder about z from zmin to zmax; ours is about y from -1 to 1.
            const float radius = p.number("radius", 1.0f), zmin = p.number("zmin", -1.0f), zmax = p.number("zmax", 1.0f);
            if (!(radius > 0.0f) || !(zmax > zmin)) fail(line, "Shape \"cylinder\": radius must be positive and zmax above zmin");
            if (p.has("phimax")) warn(line, "cylinder/phimax", "Shape \"cylinder\": partial cylinders are not supported; whole ones instead");
            p.find("phimax");
            if (state_.areaLight) warn(line, "arealight/cylinder", "AreaLightSource on a cylinder: wideray's area lights are quads and spheres; the cylinder is kept, not emitting");
            AnalyticObject tube;
            tube.shape = AnalyticShape::Cylinder;
            tube.capped = false;
            tube.transform = state_.ctm * glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 0.5f * (zmin + zmax))) *
                             glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(1, 0, 0)) *
                             glm::scale(glm::mat4(1.0f), glm::vec3(radius, 0.5f * (zmax - zmin), radius));
            tube.material = state_.material;
            if (!currentObject_) scene_.analytics.push_back(tube);
            else warn(line, "object/analytic", "spheres and cylinders inside ObjectBegin are not supported; skipped");
            reportUnused(p, "Shape \"cylinder\"");
            return;
        }
        TriangleMesh mesh;
        uint32_t meshIndex = kInvalidId;
        if (type == "trianglemesh") {
            mesh = triangleMesh(p, line);
        } else if (type == "plymesh") {
            const PbrtParam* f = p.find("filename");
            if (!f || f->strings.size() != 1) fail(line, "Shape \"plymesh\" needs \"string filename\"");
            std::filesystem::path path = f->strings[0];
            if (path.is_relative()) path = files_.back().folder / path;
            if (auto it = plyMeshes_.find(path); it != plyMeshes_.end()) meshIndex = it->second;
            else try {
                mesh = loadMesh(path);
            } catch (const InputError& e) {
                fail(line, std::string("Shape \"plymesh\": ") + e.what());
            }
            for (const char* displacement : {"displacement", "edgelength"}) p.find(displacement);
            if (p.has("displacement")) warn(line, "plymesh/displacement", "Shape \"plymesh\": displacement is not supported; ignored");
        } else {
            skipShape(line, type, p);
            return;
        }
        if (meshIndex == kInvalidId) {
            if (state_.areaLight && meshLights(mesh)) {
                reportUnused(p, "Shape \"" + type + "\"");
                return;
            }
            mesh.faceMaterial.clear();
            mesh.materials.clear();
            meshIndex = uint32_t(scene_.meshes.size());
            scene_.meshes.push_back(std::move(mesh));
            if (type == "plymesh") plyMeshes_[std::filesystem::path(files_.back().folder / p.find("filename")->strings[0])] = meshIndex;
        }
        if (state_.areaLight)
            warn(line, "arealight/mesh", fmt::format("AreaLightSource on a mesh of more than {} triangles (or an instanced "
                                                     "one): wideray samples every light at every point; the mesh is kept, not emitting",
                                                     kMaxTriangleLights));
        place(line, meshIndex, state_.ctm, state_.material);
        reportUnused(p, "Shape \"" + type + "\"");
    }

    void skipShape(int line, const std::string& type, const PbrtParams& p) {
        for (const PbrtParam& param : p.list) param.used = true;
        warn(line, "shape/" + type, "Shape \"" + type + "\" is not supported; skipped");
    }

    TriangleMesh triangleMesh(const PbrtParams& p, int line) {
        const PbrtParam* indices = p.find("indices");
        const PbrtParam* points = p.find("P");
        if (!points || points->numbers.size() % 3 != 0 || points->numbers.empty())
            fail(line, "Shape \"trianglemesh\" needs \"point3 P\" with 3 numbers per vertex");
        TriangleMesh mesh;
        for (size_t i = 0; i < points->numbers.size(); i += 3)
            mesh.positions.emplace_back(points->numbers[i], points->numbers[i + 1], points->numbers[i + 2]);
        if (!indices) {
            if (mesh.positions.size() != 3) fail(line, "Shape \"trianglemesh\" without \"indices\" must have 3 vertices");
            mesh.triangles.push_back({0, 1, 2});
        } else {
            if (indices->numbers.size() % 3 != 0) fail(indices->line, "\"indices\" must hold 3 numbers per triangle");
            for (size_t i = 0; i < indices->numbers.size(); i += 3) {
                glm::uvec3 tri;
                for (int k = 0; k < 3; ++k) {
                    const double index = indices->numbers[i + size_t(k)];
                    if (index < 0 || index >= double(mesh.positions.size()) || index != std::floor(index))
                        fail(indices->line, fmt::format("\"indices\"[{}] is {}, but there are {} vertices", i + size_t(k), index, mesh.positions.size()));
                    tri[k] = uint32_t(index);
                }
                mesh.triangles.push_back(tri);
            }
        }
        if (const PbrtParam* n = p.find("N"); n && n->numbers.size() == points->numbers.size())
            for (size_t i = 0; i < n->numbers.size(); i += 3) mesh.normals.emplace_back(n->numbers[i], n->numbers[i + 1], n->numbers[i + 2]);
        const PbrtParam* uv = p.find("uv");
        if (!uv) uv = p.find("st");
        if (uv && uv->numbers.size() == 2 * mesh.positions.size())
            for (size_t i = 0; i < uv->numbers.size(); i += 2) mesh.uvs.emplace_back(uv->numbers[i], uv->numbers[i + 1]);
        validateMesh(mesh, fmt::format("{}:{}", fileName(), line));
        return mesh;
    }

    void lightSource(int line) {
        const std::string type = string(line);
        PbrtParams p = params();
        PbrtMaterialContext context{textures_, [&](int l, const std::string& key, const std::string& m) { warn(l, key, m); }};
        const float scale = p.number("scale", 1.0f);
        Light light;
        if (type == "point") {
            light.type = LightType::Point;
            light.color = pbrtColor(p, "I", glm::vec3(1.0f), context) * scale;
            const PbrtParam* from = p.find("from");
            const glm::vec3 at = from && from->numbers.size() == 3 ? glm::vec3(from->numbers[0], from->numbers[1], from->numbers[2]) : glm::vec3(0.0f);
            light.position = glm::vec3(state_.ctm * glm::vec4(at, 1.0f));
        } else if (type == "distant") {
            light.type = LightType::Directional;
            light.color = pbrtColor(p, "L", glm::vec3(1.0f), context) * scale;
            auto point = [&](const char* name, glm::vec3 fallback) {
                const PbrtParam* q = p.find(name);
                return q && q->numbers.size() == 3 ? glm::vec3(q->numbers[0], q->numbers[1], q->numbers[2]) : fallback;
            };
            const glm::vec3 dir = point("to", glm::vec3(0, 0, 1)) - point("from", glm::vec3(0.0f));
            if (glm::length(dir) == 0.0f) fail(line, "LightSource \"distant\": from and to coincide");
            light.direction = glm::normalize(glm::vec3(state_.ctm * glm::vec4(dir, 0.0f)));
        } else if (type == "infinite") {
            // pbrt-v3 names the image "mapname" and multiplies it by L; pbrt-v4 names it "filename".
            const glm::vec3 radiance = pbrtColor(p, "L", glm::vec3(1.0f), context) * scale;
            if (sawInfiniteLight_)
                warn(line, "infinite/several", "several infinite lights; only the last one lights the scene");
            sawInfiniteLight_ = true;
            scene_.environment.reset();
            const PbrtParam* map = p.find("filename");
            if (!map) map = p.find("mapname");
            if (map && map->strings.size() == 1) scene_.environment = environmentMap(line, map->strings[0], radiance);
            scene_.background = radiance;
            reportUnused(p, "LightSource \"infinite\"");
            return;
        } else {
            for (const PbrtParam& param : p.list) param.used = true;
            warn(line, "light/" + type, "LightSource \"" + type + "\" is not supported; skipped");
            return;
        }
        light.intensity = 1.0f;
        scene_.lights.push_back(light);
        reportUnused(p, "LightSource \"" + type + "\"");
    }

    /// pbrt's infinite light with an image: pbrt-v4 reads square images with its equal-area mapping,
    /// pbrt-v3 any image as latitude-longitude. None where the image cannot be read.
    std::optional<EnvironmentMap> environmentMap(int line, const std::string& name, glm::vec3 scale) {
        std::filesystem::path path = name;
        if (path.is_relative()) path = files_.back().folder / path;
        const glm::mat3 toWorld(state_.ctm);
        if (!(std::abs(glm::determinant(toWorld)) > 0.0f)) {
            warn(line, "infinite/singular", "LightSource \"infinite\": its transform is singular; a constant environment instead");
            return std::nullopt;
        }
        try {
            EnvironmentMap map;
            map.file = path;
            map.image = std::make_shared<const Image>(readImage(path, true));
            map.mapping = map.image->width == map.image->height ? EnvironmentMapping::EqualArea : EnvironmentMapping::LatLong;
            map.orient(toWorld);
            map.scale = scale;
            return map;
        } catch (const InputError& e) {
            warn(line, "infinite/missing", std::string("LightSource \"infinite\": ") + e.what() + "; a constant environment of its L instead");
            return std::nullopt;
        }
    }

    void areaLightSource(int line) {
        const std::string type = string(line);
        PbrtParams p = params();
        if (type != "diffuse") {
            for (const PbrtParam& param : p.list) param.used = true;
            warn(line, "arealight/" + type, "AreaLightSource \"" + type + "\" is not supported; skipped");
            return;
        }
        PbrtMaterialContext context{textures_, [&](int l, const std::string& key, const std::string& m) { warn(l, key, m); }};
        AreaLight light;
        light.radiance = pbrtColor(p, "L", glm::vec3(1.0f), context) * p.number("scale", 1.0f);
        const PbrtParam* twoSided = p.find("twosided");
        light.twoSided = twoSided && !twoSided->strings.empty() && twoSided->strings[0] == "true";
        light.line = line;
        state_.areaLight = light;
        reportUnused(p, "AreaLightSource \"diffuse\"");
    }

    /// A mesh under an AreaLightSource as lights: one parallelogram (two triangles, four corners) as a
    /// quad light, a few triangles as a triangle light each; false for larger meshes (every light is
    /// sampled at every shading point).
    bool meshLights(const TriangleMesh& mesh) {
        std::vector<glm::vec3> world;
        for (const glm::vec3& v : mesh.positions) world.push_back(glm::vec3(state_.ctm * glm::vec4(v, 1.0f)));
        if (mesh.triangles.size() == 2 && mesh.positions.size() == 4) {
            // The corner shared by neither triangle's diagonal: its two neighbours span the rest.
            const glm::uvec3 a = mesh.triangles[0];
            for (int k = 0; k < 3; ++k) {
                const uint32_t corner = a[k], u = a[(k + 1) % 3], v = a[(k + 2) % 3];
                const glm::vec3 edgeU = world[u] - world[corner], edgeV = world[v] - world[corner];
                const uint32_t fourth = 6 - corner - u - v;
                const float size = glm::length(edgeU) + glm::length(edgeV);
                if (glm::length(world[corner] + edgeU + edgeV - world[fourth]) > 1e-4f * size) continue;
                addPlanarLight(LightType::Quad, world[corner], edgeU, edgeV, emittingNormal(mesh, world, a), 4);
                return true;
            }
        }
        if (mesh.triangles.size() > kMaxTriangleLights) return false;
        for (const glm::uvec3& t : mesh.triangles) {
            const glm::vec3 edgeU = world[t.y] - world[t.x], edgeV = world[t.z] - world[t.x];
            if (glm::length(glm::cross(edgeU, edgeV)) == 0.0f) continue;
            addPlanarLight(LightType::Triangle, world[t.x], edgeU, edgeV, emittingNormal(mesh, world, t), 1);
        }
        return true;
    }

    /// The side pbrt's area light on a triangle emits toward: its geometric normal, turned toward the
    /// shading normals where the mesh has them, else flipped by ReverseOrientation and by transforms
    /// that mirror.
    glm::vec3 emittingNormal(const TriangleMesh& mesh, const std::vector<glm::vec3>& world, glm::uvec3 t) const {
        glm::vec3 normal = glm::cross(world[t.x] - world[t.z], world[t.y] - world[t.z]);
        const bool swaps = glm::determinant(glm::mat3(state_.ctm)) < 0.0f;
        if (!mesh.normals.empty()) {
            const glm::vec3 shading = glm::transpose(glm::inverse(glm::mat3(state_.ctm))) *
                                      (mesh.normals[t.x] + mesh.normals[t.y] + mesh.normals[t.z]);
            if (glm::dot(normal, shading) < 0.0f) normal = -normal;
        } else if (state_.reverseOrientation != swaps) {
            normal = -normal;
        }
        return normal;
    }

    /// A quad or triangle light emitting toward `normal`, and toward the other side too for a
    /// two-sided light (a second light with its edges swapped).
    void addPlanarLight(LightType type, glm::vec3 corner, glm::vec3 edgeU, glm::vec3 edgeV, glm::vec3 normal, int samples) {
        Light light;
        light.type = type;
        light.position = corner;
        light.edgeU = edgeU;
        light.edgeV = edgeV;
        if (glm::dot(glm::cross(edgeU, edgeV), normal) < 0.0f) std::swap(light.edgeU, light.edgeV);
        light.color = state_.areaLight->radiance;
        light.intensity = 1.0f;
        light.samples = samples;
        scene_.lights.push_back(light);
        if (!state_.areaLight->twoSided) return;
        std::swap(light.edgeU, light.edgeV);
        scene_.lights.push_back(light);
    }

    void sphereLight(int line, float radius) {
        if (state_.areaLight->twoSided) warn(line, "arealight/twosided", "AreaLightSource: a two-sided sphere light emits outward only");
        const glm::mat3 m(state_.ctm);
        const float sx = glm::length(m[0]), sy = glm::length(m[1]), sz = glm::length(m[2]);
        if (std::abs(sx - sy) > 1e-4f * sx || std::abs(sx - sz) > 1e-4f * sx)
            warn(line, "arealight/ellipsoid", "AreaLightSource on a non-uniformly scaled sphere: a sphere light of the mean radius");
        Light light;
        light.type = LightType::Sphere;
        light.position = glm::vec3(state_.ctm * glm::vec4(0, 0, 0, 1));
        light.radius = radius * (sx + sy + sz) / 3.0f;
        light.color = state_.areaLight->radiance;
        light.intensity = 1.0f;
        light.samples = 4;
        scene_.lights.push_back(light);
    }

    /// pbrt's camera looks down +z with +x to the image's right and +y up, a left-handed frame; ours
    /// takes right = forward x up. Where the two disagree the world is mirrored about the camera's
    /// vertical plane, so that the image is pbrt's.
    void finishCamera() {
        const glm::mat4 cameraToWorld = glm::inverse(cameraFromWorld_);
        const glm::vec3 position(cameraToWorld * glm::vec4(0, 0, 0, 1));
        const glm::vec3 forward = glm::normalize(glm::vec3(cameraToWorld * glm::vec4(0, 0, 1, 0)));
        const glm::vec3 up = glm::normalize(glm::vec3(cameraToWorld * glm::vec4(0, 1, 0, 0)));
        const glm::vec3 right = glm::normalize(glm::vec3(cameraToWorld * glm::vec4(1, 0, 0, 0)));
        scene_.camera.position = position;
        scene_.camera.lookAt = position + forward;
        scene_.camera.up = up;
        // pbrt's fov spans the shorter side of the image.
        const float aspect = float(scene_.image.width) / float(scene_.image.height);
        scene_.camera.fovY = aspect >= 1.0f ? fov_
                                            : glm::degrees(2.0f * std::atan(std::tan(glm::radians(fov_) * 0.5f) / aspect));
        if (glm::dot(glm::cross(forward, up), right) >= 0.0f) return;
        const glm::mat4 mirror = glm::translate(glm::mat4(1.0f), position) *
                                 (glm::mat4(1.0f) - 2.0f * glm::mat4(glm::outerProduct(glm::vec4(right, 0), glm::vec4(right, 0)))) *
                                 glm::translate(glm::mat4(1.0f), -position);
        for (MeshInstance& instance : scene_.instances) instance.transform = mirror * instance.transform;
        for (AnalyticObject& object : scene_.analytics) object.transform = mirror * object.transform;
        if (scene_.environment) scene_.environment->orient(glm::mat3(mirror) * scene_.environment->toWorld);
        for (Light& light : scene_.lights) {
            light.position = glm::vec3(mirror * glm::vec4(light.position, 1.0f));
            light.direction = glm::vec3(mirror * glm::vec4(light.direction, 0.0f));
            const glm::vec3 u = glm::vec3(mirror * glm::vec4(light.edgeU, 0.0f)), v = glm::vec3(mirror * glm::vec4(light.edgeV, 0.0f));
            // A reflection turns u x v around: swapping the edges keeps the emitting side.
            light.edgeU = v;
            light.edgeV = u;
        }
    }

    std::filesystem::path mainFile_;
    SceneDescription scene_;
    std::vector<File> files_;
    std::vector<State> stack_;
    State state_;
    glm::mat4 cameraFromWorld_{1.0f};
    float fov_ = 90.0f;
    bool sawCamera_ = false;
    bool sawInfiniteLight_ = false;
    std::map<std::string, glm::mat4> namedSpaces_;
    std::map<std::string, uint32_t> namedMaterials_;
    std::map<std::string, PbrtTexture> textures_;
    PbrtTextureImages textureImages_;
    std::map<std::filesystem::path, uint32_t> plyMeshes_;
    std::map<std::string, std::vector<ObjectShape>> objects_;
    std::vector<ObjectShape>* currentObject_ = nullptr;
    size_t includeCount_ = 0;
    std::set<std::string> warned_;
};

} // namespace

SceneDescription parsePbrt(const std::string& text, const std::filesystem::path& file) {
    return PbrtReader(file).read(text);
}

SceneDescription loadPbrt(const std::filesystem::path& file) { return parsePbrt(readSceneText(file), file); }

} // namespace wideray
