// JSON -> SceneDescription with every value checked (docs/scene-format.md).
#include "io/scene_parser.h"
#include "io/terrain.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <set>
#include <sstream>
#include <unordered_map>

#include <glm/gtc/matrix_access.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "core/camera_path.h"
#include "core/random.h"
#include "io/image_io.h"
#include "io/json_document.h"
#include "io/mesh_generators.h"
#include "io/mesh_io.h"
#include "io/scene_vocabulary.h"
#include "shading/material_model.h"

namespace wideray {
namespace {

class SceneReader : JsonReader {
public:
    explicit SceneReader(const std::filesystem::path& file) : JsonReader(file.string()), folder_(file.parent_path()) {
        scene_.file = file;
    }

    SceneDescription read(const Json& json) {
        const Node root{json, ""};
        checkKeys(root, {"camera", "animation", "image", "background", "environment", "fog", "render", "materials", "lights",
                         "meshes", "objects"});
        readCameraAndAnimation(root);
        if (root.has("image")) readImage(root["image"]);
        if (root.has("background")) scene_.background = color(root["background"]);
        if (root.has("environment")) readEnvironment(root["environment"]);
        if (root.has("fog")) readFog(root["fog"]);
        if (root.has("render")) readRender(root["render"]);
        if (root.has("materials")) readMaterials(root["materials"]);
        if (root.has("lights")) readLights(root["lights"]);
        if (root.has("meshes")) readNamedMeshes(root["meshes"]);
        if (!root.has("objects")) fail("", "scene has no objects");
        readObjects(root["objects"]);
        assignDefaultMaterial();
        return std::move(scene_);
    }

    /// The frames the scene's animation renders; none for a still scene. Reads "camera" and
    /// "animation" alone, checked as read() checks them.
    std::optional<FrameRange> readFrames(const Json& json) {
        const Node root{json, ""};
        expectObject(root);
        readCameraAndAnimation(root);
        if (!scene_.animation) return std::nullopt;
        return FrameRange{scene_.animation->firstFrame, scene_.animation->lastFrame};
    }

private:
    /// The value a table of the vocabulary gives the string at `n`.
    template <class T>
    T named(const Node& n, const std::vector<std::pair<std::string, T>>& table, const std::string& what) const {
        const std::string word = string(n);
        std::vector<std::string> names;
        for (const auto& [name, value] : table) {
            if (name == word) return value;
            names.push_back(name);
        }
        const std::string hint = suggestion(word, names);
        fail(n.path, "unknown " + what + " \"" + word + "\"" + (hint.empty() ? " (expected " + joined(names) + ")" : hint));
    }

    // ---- camera, image, fog, render settings

    void readCameraAndAnimation(const Node& root) {
        if (root.has("camera")) scene_.camera = camera(root["camera"], scene_.camera, {});
        if (root.has("animation")) readAnimation(root["animation"]);
    }

    /// The camera at `n`: `camera` with the keys `n` gives.
    Camera camera(const Node& n, Camera camera, const std::vector<std::string>& otherKeys) {
        std::vector<std::string> keys = {"position", "look_at", "up", "fov", "aperture", "focus_distance", "shutter"};
        keys.insert(keys.end(), otherKeys.begin(), otherKeys.end());
        checkKeys(n, keys);
        if (n.has("position")) camera.position = vec3(n["position"]);
        if (n.has("look_at")) camera.lookAt = vec3(n["look_at"]);
        if (n.has("up")) camera.up = nonZeroVec3(n["up"]);
        if (n.has("fov")) {
            camera.fovY = number(n["fov"]);
            if (!(camera.fovY > 0.0f && camera.fovY < 180.0f)) fail(n["fov"].path, "must be in (0, 180) degrees");
        }
        if (n.has("aperture")) camera.aperture = nonNegative(n["aperture"]);
        if (n.has("focus_distance")) camera.focusDistance = nonNegative(n["focus_distance"]);
        if (n.has("shutter")) {
            const glm::vec2 shutter = vector<2>(n["shutter"]);
            if (!(shutter.x >= 0.0f && shutter.x <= shutter.y && shutter.y <= 1.0f))
                fail(n["shutter"].path, "expected [open, close] with 0 <= open <= close <= 1");
            camera.shutterOpen = shutter.x;
            camera.shutterClose = shutter.y;
        }
        if (const char* problem = viewProblem(camera)) fail(n.path, problem);
        return camera;
    }

    static const char* viewProblem(const Camera& camera) {
        const glm::vec3 view = camera.lookAt - camera.position;
        if (!(glm::dot(view, view) > 0.0f)) return "look_at must differ from position";
        if (!(glm::length(glm::cross(glm::normalize(view), glm::normalize(camera.up))) >= 1e-6f))
            return "up must not be parallel to the viewing direction";
        return nullptr;
    }

    /// "animation": {"frames": [first, last], "keyframes": [{"frame": F, camera keys...}, ...]} or
    /// {"cameras": [camera, ...], "frames": ...}: one camera per frame.
    void readAnimation(const Node& n) {
        checkKeys(n, {"frames", "keyframes", "cameras"});
        if (n.has("keyframes") == n.has("cameras")) fail(n.path, "expected either \"keyframes\" or \"cameras\"");
        Animation animation;
        const bool keyframes = n.has("keyframes");
        const Node list = n[keyframes ? "keyframes" : "cameras"];
        expectArray(list);
        if (list.value.empty()) fail(list.path, "must not be empty");
        if (list.value.size() > size_t(kLastFrame) + 1) fail(list.path, "has more entries than there are frames");
        int first = 1;
        if (n.has("frames")) {
            const Node frames = n["frames"];
            if (!frames.value.is_array() || frames.value.size() != 2)
                fail(frames.path, "expected [first, last], got " + describe(frames.value));
            first = integer(frames[size_t(0)], 0, kLastFrame);
            animation.lastFrame = integer(frames[size_t(1)], first, kLastFrame);
        }
        animation.firstFrame = first;
        for (size_t i = 0; i < list.value.size(); ++i) {
            const Node entry = list[i];
            CameraKey key;
            if (keyframes) {
                require(entry, "frame");
                key.frame = integer(entry["frame"], 0, kLastFrame);
                if (!animation.keys.empty() && key.frame <= animation.keys.back().frame)
                    fail(entry["frame"].path, "keyframes must come in increasing frame order");
            } else {
                if (first + int64_t(i) > kLastFrame) fail(entry.path, "lies beyond frame " + std::to_string(kLastFrame));
                key.frame = first + int(i);
            }
            key.camera = camera(entry, scene_.camera, keyframes ? std::vector<std::string>{"frame"} : std::vector<std::string>{});
            animation.keys.push_back(key);
        }
        if (!n.has("frames")) {
            animation.firstFrame = animation.keys.front().frame;
            animation.lastFrame = animation.keys.back().frame;
        } else if (!keyframes && animation.keys.back().frame != animation.lastFrame) {
            fail(n["frames"].path, "covers " + std::to_string(animation.lastFrame - first + 1) + " frames but \"cameras\" lists " +
                                       std::to_string(animation.keys.size()));
        }
        // The spline between valid keys can still pass a camera through its look_at point.
        for (int frame = animation.firstFrame; frame <= animation.lastFrame; ++frame)
            if (const char* problem = viewProblem(cameraAtFrame(animation, frame)))
                fail(n.path, "the camera at frame " + std::to_string(frame) + ": " + problem);
        scene_.animation = std::move(animation);
    }

    void readImage(const Node& n) {
        checkKeys(n, {"width", "height", "spp"});
        if (n.has("width")) scene_.image.width = integer(n["width"], 1, 65536);
        if (n.has("height")) scene_.image.height = integer(n["height"], 1, 65536);
        if (n.has("spp")) scene_.image.samplesPerPixel = integer(n["spp"], 1, 1 << 20);
    }

    /// An environment map: its image, how directions map to it (by default equal-area for square
    /// images, latitude-longitude otherwise, with +z up), a scale, and a transform from map to world.
    void readEnvironment(const Node& n) {
        checkKeys(n, {"file", "mapping", "scale", "transform"});
        require(n, "file");
        EnvironmentMap map;
        map.image = textureImage(n["file"], true, map.file);
        map.mapping = n.has("mapping") ? named(n["mapping"], kEnvironmentMappings, "mapping")
                      : map.image->width == map.image->height ? EnvironmentMapping::EqualArea
                                                               : EnvironmentMapping::LatLong;
        if (n.has("scale")) map.scale = n["scale"].value.is_number() ? glm::vec3(nonNegative(n["scale"])) : color(n["scale"]);
        if (map.mapping == EnvironmentMapping::EqualArea && map.image->width != map.image->height)
            fail(n["mapping"].path, "\"equal_area\" needs a square image, but " + map.file.filename().string() + " is " +
                                        std::to_string(map.image->width) + "x" + std::to_string(map.image->height));
        if (n.has("transform")) map.orient(glm::mat3(transform(n["transform"])));
        scene_.environment = std::move(map);
    }

    void readFog(const Node& n) {
        checkKeys(n, {"density", "color"});
        require(n, "density");
        scene_.fog.density = nonNegative(n["density"]);
        if (n.has("color")) scene_.fog.color = color(n["color"]);
    }

    void readRender(const Node& n) {
        checkKeys(n, {"integrator", "max_depth", "min_throughput", "polarized"});
        RenderSettings& render = scene_.render;
        if (n.has("integrator")) render.integrator = named(n["integrator"], kIntegrators, "integrator");
        if (n.has("max_depth")) render.maxDepth = integer(n["max_depth"], 0, 1024);
        if (n.has("min_throughput")) render.minThroughput = unitInterval(n["min_throughput"]);
        if (n.has("polarized")) render.polarized = boolean(n["polarized"]);
    }

    // ---- materials and textures

    void readMaterials(const Node& n) {
        expectObject(n);
        for (const auto& item : n.value.items()) {
            const Node m = n[item.key()];
            if (item.key().empty()) fail(m.path, "material names must not be empty");
            addMaterial(material(m, item.key()));
        }
    }

    Material material(const Node& m, const std::string& name) {
        expectObject(m);
        require(m, "type");
        const std::string type = string(m["type"]);
        Material material;
        material.name = name;
        if (type == "diffuse") {
            checkKeys(m, {"type", "color"});
            readColor(m, material);
        } else if (type == "plastic") {
            checkKeys(m, {"type", "color", "specular", "shininess"});
            material.type = MaterialType::Plastic;
            readColor(m, material);
            if (m.has("specular")) material.specular = unitInterval(m["specular"]);
            if (m.has("shininess")) material.shininess = positive(m["shininess"]);
        } else if (type == "mirror") {
            checkKeys(m, {"type", "color"});
            material.type = MaterialType::Mirror;
            material.color = glm::vec3(1.0f);
            readColor(m, material);
        } else if (type == "conductor") {
            checkKeys(m, {"type", "preset", "eta", "k", "roughness", "samples"});
            material.type = MaterialType::Conductor;
            readComplexIor(m, material);
            readRoughness(m, material);
        } else if (type == "dielectric") {
            checkKeys(m, {"type", "ior", "absorption", "roughness", "samples"});
            material.type = MaterialType::Dielectric;
            if (m.has("ior")) {
                material.ior = number(m["ior"]);
                if (!(material.ior > 0.0f)) fail(m["ior"].path, "an index of refraction must be positive");
            }
            if (m.has("absorption")) {
                material.absorption = vec3(m["absorption"]);
                if (glm::any(glm::lessThan(material.absorption, glm::vec3(0.0f))))
                    fail(m["absorption"].path, "absorption coefficients must not be negative");
            }
            readRoughness(m, material);
        } else {
            const std::string hint = suggestion(type, kMaterialTypes);
            fail(m["type"].path, "unknown material type \"" + type + "\"" +
                                     (hint.empty() ? " (expected " + joined(kMaterialTypes) + ")" : hint));
        }
        return material;
    }

    /// "color": [r, g, b] or a texture of reflectances.
    void readColor(const Node& m, Material& material) {
        if (!m.has("color")) return;
        const Node c = m["color"];
        if (c.value.is_object()) material.colorTexture = texture(c, false);
        else material.color = reflectance(c);
    }

    /// "roughness": a number in [0, 1] or a texture of such numbers; "samples": rays of the glossy lobe.
    void readRoughness(const Node& m, Material& material) {
        if (m.has("samples")) material.samples = integer(m["samples"], 1, 4096);
        if (!m.has("roughness")) return;
        const Node r = m["roughness"];
        if (r.value.is_object()) material.roughnessTexture = texture(r, true);
        else material.roughness = unitInterval(r);
    }

    /// Either "preset" (a measured metal) or both "eta" and "k".
    void readComplexIor(const Node& m, Material& material) const {
        if (m.has("preset")) {
            if (m.has("eta") || m.has("k")) fail(m.path, "\"preset\" cannot be combined with \"eta\" or \"k\"");
            const std::string preset = string(m["preset"]);
            const std::optional<ComplexIor> ior = conductorPreset(preset);
            if (!ior) {
                const std::string hint = suggestion(preset, conductorPresetNames());
                fail(m["preset"].path, "unknown conductor preset \"" + preset + "\"" + hint +
                                           " (valid presets: " + joined(conductorPresetNames()) + ")");
            }
            material.eta = ior->eta;
            material.k = ior->k;
            return;
        }
        if (!m.has("eta") && !m.has("k")) fail(m.path, "a conductor needs \"preset\" or both \"eta\" and \"k\"");
        require(m, "eta");
        require(m, "k");
        material.eta = vec3(m["eta"]);
        if (!glm::all(glm::greaterThan(material.eta, glm::vec3(0.0f)))) fail(m["eta"].path, "eta components must be positive");
        material.k = vec3(m["k"]);
        if (glm::any(glm::lessThan(material.k, glm::vec3(0.0f)))) fail(m["k"].path, "k components must not be negative");
    }

    /// A texture object. In a color slot a pattern blends two "colors"; in a number slot (`scalar`),
    /// two "values". Both are fractions in [0, 1].
    Texture texture(const Node& n, bool scalar) {
        require(n, "type");
        Texture texture;
        texture.type = named(n["type"], kTextureTypes, "texture type");
        if (texture.type == TextureType::Image) {
            checkKeys(n, {"type", "file"});
            require(n, "file");
            texture.image = textureImage(n["file"], !scalar, texture.file);
            return texture;
        }
        const std::string blendKey = scalar ? "values" : "colors";
        std::vector<std::string> keys = {"type", blendKey, "scale"};
        if (hasOctaves(texture.type)) keys.push_back("octaves");
        checkKeys(n, keys);
        if (n.has(blendKey)) {
            const Node blend = n[blendKey];
            if (!blend.value.is_array() || blend.value.size() != 2)
                fail(blend.path, "expected an array of 2 " + std::string(scalar ? "numbers" : "colors") + ", got " + describe(blend.value));
            texture.color0 = scalar ? glm::vec3(unitInterval(blend[0])) : reflectance(blend[0]);
            texture.color1 = scalar ? glm::vec3(unitInterval(blend[1])) : reflectance(blend[1]);
        }
        if (n.has("scale")) texture.scale = positive(n["scale"]);
        if (n.has("octaves")) texture.octaves = integer(n["octaves"], 1, 16);
        return texture;
    }

    /// Loads an image file once per scene (and per decoding: colors are sRGB-decoded, numbers are not).
    std::shared_ptr<const Image> textureImage(const Node& n, bool srgb, std::filesystem::path& resolved) {
        std::filesystem::path path = string(n);
        if (path.empty()) fail(n.path, "texture file name is empty");
        if (path.is_relative()) path = folder_ / path;
        resolved = std::filesystem::absolute(path).lexically_normal();
        auto& image = textureImages_[{resolved, srgb}];
        if (!image) {
            try {
                image = std::make_shared<const Image>(wideray::readImage(resolved, srgb));
            } catch (const InputError& e) {
                fail(n.path, std::string("cannot load texture: ") + e.what());
            }
        }
        return image;
    }

    // ---- lights

    void readLights(const Node& n) {
        expectArray(n);
        for (size_t i = 0; i < n.value.size(); ++i) scene_.lights.push_back(readLight(n[i]));
    }

    Light readLight(const Node& n) const {
        expectObject(n);
        require(n, "type");
        const std::string type = string(n["type"]);
        const std::map<std::string, std::pair<LightType, std::vector<std::string>>> requiredKeysOf = {
            {"point", {LightType::Point, {"position"}}},
            {"directional", {LightType::Directional, {"direction"}}},
            {"quad", {LightType::Quad, {"corner", "edge_u", "edge_v"}}},
            {"triangle", {LightType::Triangle, {"corner", "edge_u", "edge_v"}}},
            {"sphere", {LightType::Sphere, {"center", "radius"}}},
        };
        auto found = requiredKeysOf.find(type);
        if (found == requiredKeysOf.end()) {
            std::vector<std::string> types;
            for (const auto& entry : requiredKeysOf) types.push_back(entry.first);
            const std::string hint = suggestion(type, types);
            fail(n["type"].path, "unknown light type \"" + type + "\"" + (hint.empty() ? " (expected " + joined(types) + ")" : hint));
        }
        Light light;
        light.type = found->second.first;
        const std::vector<std::string>& required = found->second.second;
        std::vector<std::string> keys = {"type", "color", "intensity"};
        keys.insert(keys.end(), required.begin(), required.end());
        if (light.isArea()) keys.push_back("samples");
        checkKeys(n, keys);
        for (const std::string& key : required) require(n, key);

        if (n.has("color")) light.color = color(n["color"]);
        if (n.has("intensity")) light.intensity = positive(n["intensity"]);
        if (n.has("samples")) light.samples = integer(n["samples"], 1, 4096);
        switch (light.type) {
        case LightType::Point: light.position = vec3(n["position"]); break;
        case LightType::Directional: light.direction = unitLength(nonZeroVec3(n["direction"])); break;
        case LightType::Quad:
        case LightType::Triangle:
            light.position = vec3(n["corner"]);
            light.edgeU = nonZeroVec3(n["edge_u"]);
            light.edgeV = nonZeroVec3(n["edge_v"]);
            if (glm::length(glm::cross(glm::normalize(light.edgeU), glm::normalize(light.edgeV))) < 1e-6f)
                fail(n["edge_v"].path, "must not be parallel to edge_u");
            break;
        case LightType::Sphere:
            light.position = vec3(n["center"]);
            light.radius = positive(n["radius"]);
            break;
        }
        return light;
    }

    uint32_t addMaterial(Material material) {
        const uint32_t index = uint32_t(scene_.materials.size());
        materialIndex_.emplace(material.name, index);
        scene_.materials.push_back(std::move(material));
        return index;
    }

    uint32_t materialNamed(const Node& n) const {
        const std::string name = string(n);
        if (auto it = materialIndex_.find(name); it != materialIndex_.end()) return it->second;
        std::vector<std::string> names;
        for (const Material& m : scene_.materials) names.push_back(m.name);
        fail(n.path, "unknown material \"" + name + "\"" + suggestion(name, names));
    }

    uint32_t defaultMaterial() {
        if (auto it = materialIndex_.find("default"); it != materialIndex_.end()) return it->second;
        return addMaterial({"default", MaterialType::Diffuse, glm::vec3(0.8f)});
    }

    /// Makes a mesh file's faceMaterial index scene.materials. A scene material named "<prefix>/<name>"
    /// or "<name>" restyles the file's material; otherwise the file's material is added as "<prefix>/<name>".
    void importMaterials(TriangleMesh& mesh, const std::string& prefix) {
        std::vector<uint32_t> sceneIndexOf;
        for (const MeshMaterial& m : mesh.materials) {
            const std::string qualified = prefix + "/" + m.name;
            if (auto it = materialIndex_.find(qualified); it != materialIndex_.end()) sceneIndexOf.push_back(it->second);
            else if (auto plain = materialIndex_.find(m.name); plain != materialIndex_.end()) sceneIndexOf.push_back(plain->second);
            else sceneIndexOf.push_back(addMaterial({qualified, MaterialType::Diffuse, m.diffuse}));
        }
        for (uint32_t& face : mesh.faceMaterial) face = sceneIndexOf.at(face);
    }

    /// Meshes without materials that some instance shows without an override get "default".
    void assignDefaultMaterial() {
        for (const MeshInstance& instance : scene_.instances) {
            TriangleMesh& mesh = scene_.meshes[instance.mesh];
            if (instance.material == MeshInstance::kMeshMaterials && mesh.faceMaterial.empty())
                mesh.faceMaterial.assign(mesh.triangles.size(), defaultMaterial());
        }
    }

    // ---- meshes

    /// Material names of different mesh files must not collide: "chair", then "chair#2", ...
    std::string uniquePrefix(const std::string& wanted) {
        std::string prefix = wanted;
        for (int n = 2; !materialPrefixes_.insert(prefix).second; ++n) prefix = wanted + "#" + std::to_string(n);
        return prefix;
    }

    uint32_t addMesh(TriangleMesh mesh) {
        scene_.meshes.push_back(std::move(mesh));
        return uint32_t(scene_.meshes.size() - 1);
    }

    uint32_t loadMeshFile(const Node& n, const std::optional<std::string>& meshName) {
        std::filesystem::path path = string(n);
        if (path.empty()) fail(n.path, "mesh file name is empty");
        if (path.is_relative()) path = folder_ / path;
        const std::filesystem::path key = std::filesystem::absolute(path).lexically_normal();
        if (auto it = meshOfFile_.find(key); it != meshOfFile_.end()) return it->second;

        TriangleMesh mesh;
        try {
            mesh = loadMesh(path);
        } catch (const InputError& e) {
            fail(n.path, std::string("cannot load mesh: ") + e.what());
        }
        importMaterials(mesh, uniquePrefix(meshName.value_or(path.stem().string())));
        const uint32_t index = addMesh(std::move(mesh));
        meshOfFile_.emplace(key, index);
        return index;
    }

    static std::vector<std::string> shapeKeys(const std::string& shape) {
        if (shape == "icosphere") return {"subdivisions"};
        if (shape == "torus") return {"major_radius", "minor_radius", "major_segments", "minor_segments"};
        if (shape == "terrain") return terrainKeys();
        return {};
    }

    std::string shapeName(const Node& n) const {
        const std::string shape = string(n);
        if (std::find(kShapes.begin(), kShapes.end(), shape) == kShapes.end()) {
            const std::string hint = suggestion(shape, kShapes);
            fail(n.path, "unknown shape \"" + shape + "\"" + (hint.empty() ? " (expected " + joined(kShapes) + ")" : hint));
        }
        return shape;
    }

    /// The keys of the ridged multifractal (generated "terrain" and "heightfield" objects).
    static std::vector<std::string> terrainKeys() {
        return {"resolution", "octaves", "lacunarity", "gain", "offset", "roughness", "frequency", "height", "seed"};
    }

    TerrainParameters terrain(const Node& n) const {
        TerrainParameters p;
        if (n.has("resolution")) p.resolution = integer(n["resolution"], 1, 4096);
        if (n.has("octaves")) p.octaves = integer(n["octaves"], 1, 16);
        if (n.has("lacunarity")) p.lacunarity = positive(n["lacunarity"]);
        if (n.has("gain")) p.gain = positive(n["gain"]);
        if (n.has("offset")) p.offset = number(n["offset"]);
        if (n.has("roughness")) p.roughness = number(n["roughness"]);
        if (n.has("frequency")) p.frequency = positive(n["frequency"]);
        if (n.has("height")) p.height = positive(n["height"]);
        if (n.has("seed")) p.seed = uint32_t(integer(n["seed"], 0, 1 << 30));
        // The highest octave's frequency and weight must stay finite (and within the noise's precision).
        const double top = double(p.frequency) * std::pow(double(p.lacunarity), p.octaves - 1);
        const double weight = std::pow(double(p.lacunarity), -double(p.roughness) * (p.octaves - 1));
        if (!(top <= 0x1p20) || !(weight <= 1e6) || !(std::fabs(p.offset) <= 1e3))
            fail(n.path, "frequency * lacunarity^(octaves - 1) must be at most 2^20, lacunarity^(-roughness (octaves - 1)) "
                         "at most 1e6 and |offset| at most 1000");
        return p;
    }

    void readHeightFieldObject(const Node& n) {
        std::vector<std::string> keys = terrainKeys();
        keys.insert(keys.end(), {"type", "material", "transform"});
        checkKeys(n, keys);
        HeightField f;
        f.terrain = terrain(n);
        f.heights = ridgedMultifractalHeights(f.terrain);
        f.transform = optionalTransform(n);
        f.material = n.has("material") ? materialNamed(n["material"]) : defaultMaterial();
        scene_.heightFields.push_back(std::move(f));
    }

    TriangleMesh generateShape(const std::string& shape, const Node& n) const {
        if (shape == "cube") return makeCube();
        if (shape == "terrain") {
            const TerrainParameters p = terrain(n);
            return heightFieldMesh(ridgedMultifractalHeights(p), p.resolution);
        }
        if (shape == "quad") return makeQuad();
        if (shape == "icosphere") return makeIcosphere(n.has("subdivisions") ? integer(n["subdivisions"], 0, 8) : 3);
        const float major = n.has("major_radius") ? positive(n["major_radius"]) : 1.0f;
        const float minor = n.has("minor_radius") ? positive(n["minor_radius"]) : 0.25f;
        if (minor >= major) fail(n.path, "minor_radius must be smaller than major_radius");
        return makeTorus(major, minor, n.has("major_segments") ? integer(n["major_segments"], 3, 4096) : 48,
                         n.has("minor_segments") ? integer(n["minor_segments"], 3, 4096) : 24);
    }

    glm::uvec3 triangle(const Node& n, size_t vertexCount) const {
        if (!n.value.is_array() || n.value.size() != 3)
            fail(n.path, "expected an array of 3 vertex indices, got " + describe(n.value));
        glm::uvec3 triangle;
        for (int k = 0; k < 3; ++k) {
            const Node index = n[size_t(k)];
            if (!index.value.is_number_integer()) fail(index.path, "expected an integer vertex index, got " + describe(index.value));
            const std::int64_t v = index.value.get<std::int64_t>();
            if (v < 0 || uint64_t(v) >= vertexCount)
                fail(index.path, "vertex index " + std::to_string(v) + " out of range (" + std::to_string(vertexCount) + " vertices)");
            triangle[k] = uint32_t(v);
        }
        return triangle;
    }

    /// "vertices", "indices" and optional "normals", "uvs", "face_materials" (names, one per triangle).
    TriangleMesh inlineTriangles(const Node& n) const {
        TriangleMesh mesh;
        require(n, "vertices");
        require(n, "indices");
        const Node vertices = n["vertices"], indices = n["indices"];
        expectArray(vertices);
        expectArray(indices);
        for (size_t i = 0; i < vertices.value.size(); ++i) mesh.positions.push_back(vec3(vertices[i]));
        for (size_t t = 0; t < indices.value.size(); ++t) mesh.triangles.push_back(triangle(indices[t], mesh.positions.size()));
        if (n.has("normals")) {
            const Node normals = n["normals"];
            expectArray(normals);
            if (normals.value.size() != mesh.positions.size())
                fail(normals.path, "expected one normal per vertex (" + std::to_string(mesh.positions.size()) + ")");
            for (size_t i = 0; i < normals.value.size(); ++i) mesh.normals.push_back(nonZeroVec3(normals[i]));
        }
        if (n.has("uvs")) {
            const Node uvs = n["uvs"];
            expectArray(uvs);
            if (uvs.value.size() != mesh.positions.size())
                fail(uvs.path, "expected one uv per vertex (" + std::to_string(mesh.positions.size()) + ")");
            for (size_t i = 0; i < uvs.value.size(); ++i) mesh.uvs.push_back(vector<2>(uvs[i]));
        }
        if (n.has("face_materials")) {
            const Node faces = n["face_materials"];
            expectArray(faces);
            if (faces.value.size() != mesh.triangles.size())
                fail(faces.path, "expected one material per triangle (" + std::to_string(mesh.triangles.size()) + ")");
            for (size_t t = 0; t < faces.value.size(); ++t) mesh.faceMaterial.push_back(materialNamed(faces[t]));
        }
        try {
            validateMesh(mesh, file_);
        } catch (const InputError& e) {
            fail(n.path, e.location().empty() ? e.message() : e.location() + ": " + e.message());
        }
        return mesh;
    }

    void readNamedMeshes(const Node& n) {
        expectObject(n);
        for (const auto& item : n.value.items()) {
            const Node m = n[item.key()];
            expectObject(m);
            const int sources = int(m.has("file")) + int(m.has("generate")) + int(m.has("vertices"));
            if (sources != 1) fail(m.path, "expected exactly one of \"file\", \"generate\" or \"vertices\"");
            uint32_t index;
            if (m.has("file")) {
                checkKeys(m, {"file"});
                index = loadMeshFile(m["file"], item.key());
            } else if (m.has("generate")) {
                const std::string shape = shapeName(m["generate"]);
                std::vector<std::string> keys = shapeKeys(shape);
                keys.push_back("generate");
                checkKeys(m, keys);
                index = addMesh(generateShape(shape, m));
            } else {
                checkKeys(m, {"vertices", "indices", "normals", "uvs", "face_materials"});
                index = addMesh(inlineTriangles(m));
            }
            meshNamed_.emplace(item.key(), index);
        }
    }

    // ---- objects

    glm::mat4 transform(const Node& n) const {
        expectObject(n);
        if (n.has("matrix")) {
            if (n.value.size() != 1) fail(n.path, "\"matrix\" cannot be combined with translate, rotate or scale");
            const Node m = n["matrix"];
            if (!m.value.is_array() || m.value.size() != 16)
                fail(m.path, "expected an array of 16 numbers (row-major), got " + describe(m.value));
            glm::mat4 matrix;
            for (int row = 0; row < 4; ++row)
                for (int column = 0; column < 4; ++column) matrix[column][row] = number(m[size_t(row * 4 + column)]);
            if (glm::row(matrix, 3) != glm::vec4(0.0f, 0.0f, 0.0f, 1.0f))
                fail(m.path, "the last row must be [0, 0, 0, 1] (only affine transforms)");
            if (glm::determinant(glm::mat3(matrix)) == 0.0f) fail(m.path, "matrix is singular");
            return matrix;
        }
        checkKeys(n, {"translate", "rotate", "scale"});
        glm::mat4 result(1.0f);
        if (n.has("scale")) {
            const Node s = n["scale"];
            const glm::vec3 scale = s.value.is_array() ? vec3(s) : glm::vec3(number(s));
            if (glm::any(glm::equal(scale, glm::vec3(0.0f)))) fail(s.path, "scale must not be zero");
            result = glm::scale(glm::mat4(1.0f), scale);
        }
        if (n.has("rotate")) {
            const Node r = n["rotate"];
            if (r.value.is_array()) {
                for (size_t i = 0; i < r.value.size(); ++i) result = rotation(r[i]) * result;
            } else {
                result = rotation(r) * result;
            }
        }
        if (n.has("translate")) result = glm::translate(glm::mat4(1.0f), vec3(n["translate"])) * result;
        return result;
    }

    glm::mat4 rotation(const Node& n) const {
        checkKeys(n, {"axis", "degrees"});
        require(n, "axis");
        require(n, "degrees");
        const glm::vec3 axis = glm::normalize(nonZeroVec3(n["axis"]));
        return glm::rotate(glm::mat4(1.0f), glm::radians(number(n["degrees"])), axis);
    }

    glm::mat4 optionalTransform(const Node& n) const { return n.has("transform") ? transform(n["transform"]) : glm::mat4(1.0f); }

    void readObjects(const Node& n) {
        expectArray(n);
        if (n.value.empty()) fail(n.path, "scene has no objects");
        for (size_t i = 0; i < n.value.size(); ++i) readObject(n[i]);
    }

    /// The object types, one row each: the type's name and its parse function. A new primitive adds
    /// a row here and a geometry kind (geometry/geometry_registry.cpp).
    using ObjectParser = void (SceneReader::*)(const Node&);
    static std::span<const std::pair<const char*, ObjectParser>> objectTypes() {
        static constexpr std::pair<const char*, ObjectParser> kTypes[] = {
            {"mesh", &SceneReader::readPlaced<&SceneReader::meshFileObject>},
            {"instance", &SceneReader::readPlaced<&SceneReader::namedMeshObject>},
            {"generated", &SceneReader::readPlaced<&SceneReader::generatedObject>},
            {"triangles", &SceneReader::readPlaced<&SceneReader::trianglesObject>},
            {"sphere", &SceneReader::readSphereObject},
            {"ellipsoid", &SceneReader::readAnalyticObject}, {"cylinder", &SceneReader::readAnalyticObject},
            {"cone", &SceneReader::readAnalyticObject}, {"paraboloid", &SceneReader::readAnalyticObject},
            {"hyperboloid", &SceneReader::readAnalyticObject}, {"quadric", &SceneReader::readAnalyticObject},
            {"torus", &SceneReader::readAnalyticObject}, {"blob", &SceneReader::readAnalyticObject},
            {"heightfield", &SceneReader::readHeightFieldObject},
            {"csg", &SceneReader::readCsgObject},
        };
        return kTypes;
    }

    void readObject(const Node& n) {
        expectObject(n);
        require(n, "type");
        const std::string type = string(n["type"]);
        std::vector<std::string> types;
        for (const auto& [name, parse] : objectTypes()) {
            if (type == name) return (this->*parse)(n);
            types.push_back(name);
        }
        const std::string hint = suggestion(type, types);
        fail(n["type"].path, "unknown object type \"" + type + "\"" + (hint.empty() ? " (expected " + joined(types) + ")" : hint));
    }

    /// The mesh types: each gives the instance that places its mesh.
    using MeshObjectParser = MeshInstance (SceneReader::*)(const Node&);
    static std::span<const std::pair<const char*, MeshObjectParser>> meshObjectTypes() {
        static constexpr std::pair<const char*, MeshObjectParser> kTypes[] = {
            {"mesh", &SceneReader::meshFileObject}, {"instance", &SceneReader::namedMeshObject},
            {"generated", &SceneReader::generatedObject}, {"triangles", &SceneReader::trianglesObject}};
        return kTypes;
    }

    template <MeshObjectParser parse>
    void readPlaced(const Node& n) {
        const MeshInstance placed = (this->*parse)(n);
        if (!n.has("repeat")) return scene_.instances.push_back(placed);
        const Repeat repeat = readRepeat(n["repeat"]);
        if (scene_.instances.size() + repeat.copies() > kMaxInstances)
            fail(n["repeat"].path, "more than " + std::to_string(kMaxInstances) + " instances in the scene");
        for (size_t k = 0; k < repeat.copies(); ++k) {
            const glm::mat4 move = repeat.move(k), turn = repeat.turn(k);
            std::optional<glm::mat4> end;
            if (placed.endTransform) end = move * *placed.endTransform * turn;
            scene_.instances.push_back({placed.mesh, move * placed.transform * turn, placed.material, end});
        }
    }

    /// "repeat": copies on a lattice of count[0] x count[1] x count[2] points `step` apart, each first
    /// turned about its object-space y axis by a random angle within +-`turn` degrees (seeded by
    /// `seed`): per copy, the move after the object's transform and the turn before it.
    struct Repeat {
        glm::ivec3 count;
        glm::vec3 step;
        float turnDegrees;
        uint32_t seed;

        size_t copies() const { return size_t(count.x) * size_t(count.y) * size_t(count.z); }
        glm::mat4 move(size_t k) const {
            const glm::vec3 at(float(k % size_t(count.x)), float(k / size_t(count.x) % size_t(count.y)),
                               float(k / (size_t(count.x) * size_t(count.y))));
            return glm::translate(glm::mat4(1.0f), step * at);
        }
        glm::mat4 turn(size_t k) const {
            const float u = float(pcgHash(uint32_t(k) ^ pcgHash(seed)) >> 8) * 0x1p-24f;  // [0, 1)
            return glm::rotate(glm::mat4(1.0f), glm::radians(turnDegrees * (2.0f * u - 1.0f)), glm::vec3(0, 1, 0));
        }
    };

    Repeat readRepeat(const Node& n) const {
        expectObject(n);
        checkKeys(n, {"count", "step", "turn", "seed"});
        require(n, "count");
        require(n, "step");
        const Node c = n["count"];
        if (!c.value.is_array() || c.value.size() != 3) fail(c.path, "expected [nx, ny, nz], got " + describe(c.value));
        Repeat r;
        r.count = {integer(c[size_t(0)], 1, 1000000), integer(c[size_t(1)], 1, 1000000), integer(c[size_t(2)], 1, 1000000)};
        if (r.copies() > 1000000) fail(c.path, "at most 1000000 copies");
        r.step = vec3(n["step"]);
        r.turnDegrees = n.has("turn") ? nonNegative(n["turn"]) : 0.0f;
        r.seed = n.has("seed") ? uint32_t(integer(n["seed"], 0, 1 << 30)) : 0u;
        return r;
    }

    MeshInstance meshFileObject(const Node& n) {
        checkKeys(n, {"type", "file", "material", "transform", "end_transform", "repeat"});
        require(n, "file");
        return instanceOf(loadMeshFile(n["file"], std::nullopt), n);
    }

    MeshInstance namedMeshObject(const Node& n) {
        checkKeys(n, {"type", "mesh", "material", "transform", "end_transform", "repeat"});
        require(n, "mesh");
        const Node name = n["mesh"];
        auto it = meshNamed_.find(string(name));
        if (it == meshNamed_.end()) {
            std::vector<std::string> names;
            for (const auto& [meshName, index] : meshNamed_) names.push_back(meshName);
            fail(name.path, "unknown mesh \"" + string(name) + "\"" + suggestion(string(name), names));
        }
        return instanceOf(it->second, n);
    }

    MeshInstance generatedObject(const Node& n) {
        require(n, "shape");
        const std::string shape = shapeName(n["shape"]);
        std::vector<std::string> keys = shapeKeys(shape);
        keys.insert(keys.end(), {"type", "shape", "material", "transform", "end_transform", "repeat"});
        checkKeys(n, keys);
        return ownMesh(generateShape(shape, n), n);
    }

    MeshInstance trianglesObject(const Node& n) {
        checkKeys(n, {"type", "vertices", "indices", "normals", "uvs", "material", "face_materials", "transform", "end_transform", "repeat"});
        if (n.has("material") && n.has("face_materials"))
            fail(n.path, "\"material\" and \"face_materials\" cannot be combined");
        return ownMesh(inlineTriangles(n), n);
    }

    void readSphereObject(const Node& n) {
        const Sphere s = sphere(n);
        const glm::mat4 m = optionalTransform(n);
        if (n.has("end_transform")) {  // a moving sphere is an ellipsoid moving between the two transforms
            AnalyticObject moving = sphereEllipsoid(s, m);
            moving.endTransform = sphereEllipsoid(s, transform(n["end_transform"])).transform;
            checkMotion(n["end_transform"], moving.transform, *moving.endTransform);
            scene_.analytics.push_back(moving);
            return;
        }
        if (isSimilarity(m)) {
            // A sphere stays a sphere under rotation, uniform scale and translation.
            scene_.spheres.push_back({glm::vec3(m * glm::vec4(s.center, 1.0f)), s.radius * glm::length(glm::vec3(m[0])), s.material});
            return;
        }
        // Any other transform makes it an ellipsoid.
        scene_.analytics.push_back(sphereEllipsoid(s, m));
    }

    Sphere sphere(const Node& n) {
        checkKeys(n, {"type", "center", "radius", "material", "transform", "end_transform"});
        require(n, "center");
        require(n, "radius");
        return {vec3(n["center"]), positive(n["radius"]), n.has("material") ? materialNamed(n["material"]) : defaultMaterial()};
    }

    /// The unit sphere, scaled, moved, transformed.
    static AnalyticObject sphereEllipsoid(const Sphere& s, const glm::mat4& m) {
        AnalyticObject e;
        e.transform = m * glm::translate(glm::mat4(1.0f), s.center) * glm::scale(glm::mat4(1.0f), glm::vec3(s.radius));
        e.material = s.material;
        return e;
    }

    static bool isSimilarity(const glm::mat4& m) {
        const glm::vec3 x(m[0]), y(m[1]), z(m[2]);
        const float scale = glm::length(x), tolerance = 1e-4f * scale * scale;
        return std::abs(glm::dot(y, y) - scale * scale) <= tolerance && std::abs(glm::dot(z, z) - scale * scale) <= tolerance &&
               std::abs(glm::dot(x, y)) <= tolerance && std::abs(glm::dot(y, z)) <= tolerance &&
               std::abs(glm::dot(x, z)) <= tolerance;
    }

    void readAnalyticObject(const Node& n) { scene_.analytics.push_back(analyticObject(n)); }

    /// An analytic primitive: its canonical shape sized by its own keys, then placed by its transform.
    AnalyticObject analyticObject(const Node& n) {
        const std::string type = string(n["type"]);
        AnalyticObject o;
        for (const auto& [name, shape] : kAnalyticShapes)
            if (name == type) o.shape = shape;
        glm::mat4 local(1.0f);
        switch (o.shape) {
        case AnalyticShape::Ellipsoid:
            checkKeys(n, {"type", "center", "radii", "material", "transform", "end_transform"});
            if (n.has("radii")) {
                const glm::vec3 radii = vec3(n["radii"]);
                if (!(radii.x > 0 && radii.y > 0 && radii.z > 0)) fail(n["radii"].path, "radii must be positive");
                local = glm::scale(local, radii);
            }
            if (n.has("center")) local = glm::translate(glm::mat4(1.0f), vec3(n["center"])) * local;
            break;
        case AnalyticShape::Quadric: {
            checkKeys(n, {"type", "coefficients", "material", "transform", "end_transform"});
            require(n, "coefficients");
            const Node c = n["coefficients"];
            if (!c.value.is_array() || c.value.size() != 10)
                fail(c.path, "expected an array of 10 numbers (A..J of Ax2 + By2 + Cz2 + Dxy + Exz + Fyz + Gx + Hy + Iz + J), got " + describe(c.value));
            bool zero = true;
            for (size_t i = 0; i < 10; ++i) zero &= (o.coefficients[i] = number(c[i])) == 0.0f;
            if (zero) fail(c.path, "the coefficients must not all be zero");
            break;
        }
        case AnalyticShape::Blob: {
            checkKeys(n, {"type", "balls", "threshold", "material", "transform", "end_transform"});
            require(n, "balls");
            const Node balls = n["balls"];
            expectArray(balls);
            if (balls.value.empty()) fail(balls.path, "a blob needs at least one ball");
            for (size_t i = 0; i < balls.value.size(); ++i) {
                const Node b = balls[i];
                expectObject(b);
                checkKeys(b, {"center", "radius", "strength"});
                require(b, "center");
                require(b, "radius");
                BlobBall ball{vec3(b["center"]), positive(b["radius"]), 1.0f};
                if (b.has("strength")) {
                    ball.strength = number(b["strength"]);
                    if (ball.strength == 0.0f) fail(b["strength"].path, "strength must not be zero");
                }
                o.balls.push_back(ball);
            }
            if (n.has("threshold")) o.threshold = positive(n["threshold"]);
            break;
        }
        case AnalyticShape::Torus: {
            checkKeys(n, {"type", "major_radius", "minor_radius", "material", "transform", "end_transform"});
            if (n.has("major_radius")) o.majorRadius = positive(n["major_radius"]);
            if (n.has("minor_radius")) o.minorRadius = positive(n["minor_radius"]);
            if (o.minorRadius >= o.majorRadius) fail(n.path, "minor_radius must be smaller than major_radius");
            break;
        }
        default: {
            std::vector<std::string> keys = {"type", "radius", "height", "capped", "material", "transform", "end_transform"};
            if (o.shape == AnalyticShape::Hyperboloid) keys.push_back("sheets");
            checkKeys(n, keys);
            const float radius = n.has("radius") ? positive(n["radius"]) : 1.0f;
            const float height = n.has("height") ? positive(n["height"]) : 2.0f;
            local = glm::scale(local, glm::vec3(radius, 0.5f * height, radius));
            if (n.has("capped")) o.capped = boolean(n["capped"]);
            if (n.has("sheets")) {
                const int sheets = integer(n["sheets"], 1, 2);
                if (sheets == 2) o.shape = AnalyticShape::TwoSheetHyperboloid;
            }
        }
        }
        o.transform = optionalTransform(n) * local;
        if (n.has("end_transform")) {
            o.endTransform = transform(n["end_transform"]) * local;
            checkMotion(n["end_transform"], o.transform, *o.endTransform);
        }
        o.material = n.has("material") ? materialNamed(n["material"]) : defaultMaterial();
        return o;
    }

    MeshInstance instanceOf(uint32_t mesh, const Node& n) const {
        const uint32_t material = n.has("material") ? materialNamed(n["material"]) : MeshInstance::kMeshMaterials;
        return {mesh, optionalTransform(n), material, endTransform(n)};
    }

    /// A moving object's transform at time 1 ("end_transform"; "transform" is at time 0).
    std::optional<glm::mat4> endTransform(const Node& n) const {
        if (!n.has("end_transform")) return std::nullopt;
        const glm::mat4 end = transform(n["end_transform"]);
        checkMotion(n["end_transform"], optionalTransform(n), end);
        return end;
    }

    /// The interpolated transforms must stay well invertible: their determinant (a cubic in the time)
    /// keeps the sign it has at the start and a millionth of its size, checked at 257 times.
    void checkMotion(const Node& end, const glm::mat4& start, const glm::mat4& stop) const {
        const double first = glm::determinant(glm::dmat3(start));
        for (int i = 0; i <= 256; ++i) {
            const double t = double(i) / 256.0;
            if (!(glm::determinant((1.0 - t) * glm::dmat3(start) + t * glm::dmat3(stop)) * first > 1e-6 * first * first))
                fail(end.path, "the motion passes through a (nearly) singular transform (from transform to end_transform the "
                               "object would mirror or flatten, e.g. a turn by 180 degrees)");
        }
    }

    /// Generated and inline meshes belong to one object, so its material goes into the mesh itself.
    MeshInstance ownMesh(TriangleMesh mesh, const Node& n) {
        if (mesh.faceMaterial.empty())
            mesh.faceMaterial.assign(mesh.triangles.size(), n.has("material") ? materialNamed(n["material"]) : defaultMaterial());
        return {addMesh(std::move(mesh)), optionalTransform(n), MeshInstance::kMeshMaterials, endTransform(n)};
    }

    // ---- CSG

    void readCsgObject(const Node& n) {
        CsgObject object;
        csgOperation(n, glm::mat4(1.0f), std::nullopt, object);
        scene_.csgs.push_back(std::move(object));
    }

    /// A "csg" node and, recursively, its operands; its transform and material apply to all of them
    /// (an operand's own material wins). Returns the node's index.
    uint32_t csgOperation(const Node& n, const glm::mat4& parent, std::optional<uint32_t> material, CsgObject& object) {
        checkKeys(n, {"type", "operation", "operands", "material", "transform"});
        require(n, "operation");
        require(n, "operands");
        const glm::mat4 transform = parent * optionalTransform(n);
        if (n.has("material")) material = materialNamed(n["material"]);
        const uint32_t index = uint32_t(object.nodes.size());
        object.nodes.push_back({CsgNode::Kind::Operation, named(n["operation"], kCsgOperations, "CSG operation"), 0, {}});
        const Node operands = n["operands"];
        expectArray(operands);
        if (operands.value.size() < 2) fail(operands.path, "a CSG operation needs at least two operands");
        if (operands.value.size() > 1024) fail(operands.path, "at most 1024 operands per CSG operation");
        for (size_t k = 0; k < operands.value.size(); ++k) {
            const uint32_t operand = csgOperand(operands[k], transform, material, object);
            object.nodes[index].operands.push_back(operand);
        }
        return index;
    }

    uint32_t csgOperand(const Node& n, const glm::mat4& parent, std::optional<uint32_t> material, CsgObject& object) {
        expectObject(n);
        require(n, "type");
        if (n.has("end_transform")) fail(n["end_transform"].path, "CSG operands cannot move");
        const std::string type = string(n["type"]);
        if (type == "csg") {
            if (++csgDepth_ >= 64) fail(n.path, "CSG nesting deeper than 64 levels");
            const uint32_t index = csgOperation(n, parent, material, object);
            --csgDepth_;
            return index;
        }
        for (const auto& [name, parse] : meshObjectTypes()) {
            if (type != name) continue;
            if (n.has("repeat")) fail(n["repeat"].path, "a CSG operand cannot be repeated");
            MeshInstance placed = (this->*parse)(n);
            placed.transform = parent * placed.transform;
            if (!n.has("material") && material) placed.material = *material;
            const TriangleMesh& mesh = scene_.meshes[placed.mesh];
            if (placed.material == MeshInstance::kMeshMaterials && mesh.faceMaterial.empty()) placed.material = defaultMaterial();
            if (const std::string defect = closedSurfaceDefect(mesh); !defect.empty())
                fail(n.path, "a CSG operand must be a solid: " + defect);
            object.meshes.push_back(placed);
            object.nodes.push_back({CsgNode::Kind::Mesh, CsgOperation::Union, uint32_t(object.meshes.size() - 1), {}});
            return uint32_t(object.nodes.size() - 1);
        }
        AnalyticObject solid;
        if (type == "sphere") {
            solid = sphereEllipsoid(sphere(n), optionalTransform(n));
        } else if (std::any_of(kAnalyticShapes.begin(), kAnalyticShapes.end(), [&](const auto& s) { return s.first == type; })) {
            solid = analyticObject(n);
            if (solid.shape == AnalyticShape::Quadric)
                fail(n["type"].path, "a general quadric is not a closed solid and cannot be a CSG operand");
            if (!solid.capped) fail(n["capped"].path, "a CSG operand must be closed: an uncapped quadric is not");
        } else {
            std::vector<std::string> types = {"csg", "sphere"};
            for (const auto& [name, parse] : meshObjectTypes()) types.push_back(name);
            for (const auto& [name, shape] : kAnalyticShapes)
                if (shape != AnalyticShape::Quadric) types.push_back(name);
            const std::string hint = suggestion(type, types);
            fail(n["type"].path, "\"" + type + "\" cannot be a CSG operand" + (hint.empty() ? " (expected " + joined(types) + ")" : hint));
        }
        solid.transform = parent * solid.transform;
        if (!n.has("material") && material) solid.material = *material;
        object.analytics.push_back(solid);
        object.nodes.push_back({CsgNode::Kind::Analytic, CsgOperation::Union, uint32_t(object.analytics.size() - 1), {}});
        return uint32_t(object.nodes.size() - 1);
    }

    std::filesystem::path folder_;
    SceneDescription scene_;
    std::unordered_map<std::string, uint32_t> materialIndex_;
    std::map<std::string, uint32_t> meshNamed_;
    std::map<std::filesystem::path, uint32_t> meshOfFile_;
    std::set<std::string> materialPrefixes_;
    int csgDepth_ = 0;
    static constexpr size_t kMaxInstances = 10000000;
    std::map<std::pair<std::filesystem::path, bool>, std::shared_ptr<const Image>> textureImages_;
};

} // namespace

SceneDescription parseScene(const std::string& jsonText, const std::filesystem::path& file) {
    const Json json = parseJson(jsonText, file.string());
    return SceneReader(file).read(json);
}

std::string readSceneText(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw InputError(file.string(), "", "cannot open scene file");
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

SceneDescription loadScene(const std::filesystem::path& file) { return parseScene(readSceneText(file), file); }

std::optional<FrameRange> loadSceneFrames(const std::filesystem::path& file) {
    return SceneReader(file).readFrames(parseJson(readSceneText(file), file.string()));
}

} // namespace wideray
