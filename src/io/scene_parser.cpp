// Scene files: JSON -> Scene with every value checked, and Scene -> JSON for round trips.
#include "io/scene_parser.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

#include <glm/gtc/matrix_access.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "io/mesh_generators.h"
#include "io/image_io.h"
#include "io/mesh_io.h"
#include "shading/material_model.h"

namespace wideray {
namespace {

// Numbers are parsed with strtof and printed as the shortest text that reads back as the same
// float, so writeScene -> parseScene reproduces every float exactly.
using Json = nlohmann::basic_json<nlohmann::ordered_map, std::vector, std::string, bool, std::int64_t,
                                  std::uint64_t, float>;

size_t editDistance(const std::string& a, const std::string& b) {
    std::vector<size_t> previous(b.size() + 1), current(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) previous[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        current[0] = i;
        for (size_t j = 1; j <= b.size(); ++j)
            current[j] = std::min({previous[j] + 1, current[j - 1] + 1, previous[j - 1] + (a[i - 1] != b[j - 1])});
        std::swap(previous, current);
    }
    return previous[b.size()];
}

/// " (did you mean "x"?)" for the closest candidate within edit distance 2, else "".
std::string suggestion(const std::string& word, const std::vector<std::string>& candidates) {
    const std::string* best = nullptr;
    size_t bestDistance = 3;
    for (const std::string& candidate : candidates) {
        const size_t d = editDistance(word, candidate);
        if (d < bestDistance) bestDistance = d, best = &candidate;
    }
    return best ? " (did you mean \"" + *best + "\"?)" : "";
}

std::string joined(const std::vector<std::string>& words) {
    std::string s;
    for (const std::string& w : words) s += (s.empty() ? "" : ", ") + w;
    return s;
}

std::string describe(const Json& value) {
    if (value.is_array()) return "an array of " + std::to_string(value.size()) + " elements";
    if (value.is_object()) return "an object";
    if (value.is_number()) return "a number";
    if (value.is_string()) return "a string";
    if (value.is_boolean()) return "a boolean";
    return "null";
}

/// A JSON value with the key path that leads to it ("objects[2].transform.scale").
struct Node {
    const Json& value;
    std::string path;

    bool has(const std::string& key) const { return value.contains(key); }
    Node operator[](const std::string& key) const { return {value.at(key), path.empty() ? key : path + "." + key}; }
    Node operator[](size_t index) const { return {value.at(index), path + "[" + std::to_string(index) + "]"}; }
};

/// Follows nlohmann's parse events to know the key path of the value being read, so that duplicate
/// keys (which nlohmann would silently resolve to the last) and out-of-range numbers can name it.
class KeyPathTracker {
public:
    explicit KeyPathTracker(std::string file) : file_(std::move(file)) {}

    bool operator()(int, Json::parse_event_t event, Json& parsed) {
        using Event = Json::parse_event_t;
        switch (event) {
        case Event::object_start: frames_.emplace_back(true); break;
        case Event::array_start: frames_.emplace_back(false); break;
        case Event::key: {
            Frame& frame = frames_.back();
            frame.key = parsed.get<std::string>();
            if (!frame.keys.insert(frame.key).second)
                throw InputError(file_, currentPath(), "duplicate key \"" + frame.key + "\"");
            break;
        }
        case Event::object_end:
        case Event::array_end: frames_.pop_back(); [[fallthrough]];
        case Event::value:
            if (!frames_.empty() && !frames_.back().isObject) ++frames_.back().index;
            break;
        }
        return true;
    }

    /// The path of the value being read, such as "lights[1].position[2]".
    std::string currentPath() const {
        std::string path;
        for (const Frame& frame : frames_) {
            if (frame.isObject) path += (path.empty() ? "" : ".") + frame.key;
            else path += "[" + std::to_string(frame.index) + "]";
        }
        return path;
    }

private:
    struct Frame {
        explicit Frame(bool object) : isObject(object) {}
        bool isObject;
        std::set<std::string> keys;
        std::string key;
        size_t index = 0;
    };

    std::string file_;
    std::vector<Frame> frames_;
};

std::string lineAndColumn(const std::string& text, size_t byte) {
    const size_t end = std::min(byte > 0 ? byte - 1 : 0, text.size());  // nlohmann counts from 1
    size_t line = 1, lineStart = 0;
    for (size_t i = 0; i < end; ++i)
        if (text[i] == '\n') ++line, lineStart = i + 1;
    return "line " + std::to_string(line) + ", column " + std::to_string(end - lineStart + 1);
}

Json parseJson(const std::string& text, const std::string& file) {
    // std::function copies its callable, so the tracker is shared to be asked for the path afterwards.
    auto tracker = std::make_shared<KeyPathTracker>(file);
    auto callback = [tracker](int depth, Json::parse_event_t event, Json& parsed) { return (*tracker)(depth, event, parsed); };
    try {
        return Json::parse(text, callback, true, true);
    } catch (const Json::parse_error& e) {
        // nlohmann's message is "[json.exception.parse_error.101] parse error at ...: <what>".
        const std::string what = e.what();
        const size_t colon = what.find(": ", what.find("parse error"));
        throw InputError(file, lineAndColumn(text, e.byte),
                         "malformed JSON: " + (colon == std::string::npos ? what : what.substr(colon + 2)));
    } catch (const Json::out_of_range&) {
        // nlohmann refuses numbers that overflow a float (the only way to write Inf in JSON).
        throw InputError(file, tracker->currentPath(), "number is out of range (not a finite 32-bit float)");
    }
}

const std::vector<std::string> kShapes = {"cube", "icosphere", "torus", "quad"};
const std::vector<std::string> kMaterialTypes = {"diffuse", "plastic", "mirror", "conductor", "dielectric"};
const std::vector<std::pair<std::string, TextureType>> kTextureTypes = {
    {"checker", TextureType::Checker}, {"noise", TextureType::Noise},   {"fbm", TextureType::Fbm},
    {"turbulence", TextureType::Turbulence}, {"marble", TextureType::Marble}, {"image", TextureType::Image}};

bool hasOctaves(TextureType type) {
    return type == TextureType::Fbm || type == TextureType::Turbulence || type == TextureType::Marble;
}

class SceneReader {
public:
    explicit SceneReader(const std::filesystem::path& file) : file_(file.string()), folder_(file.parent_path()) {
        scene_.file = file;
    }

    Scene read(const Json& json) {
        const Node root{json, ""};
        checkKeys(root, {"camera", "image", "background", "fog", "render", "materials", "lights", "meshes", "objects"});
        if (root.has("camera")) readCamera(root["camera"]);
        if (root.has("image")) readImage(root["image"]);
        if (root.has("background")) scene_.background = color(root["background"]);
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

private:
    [[noreturn]] void fail(const std::string& path, const std::string& message) const {
        throw InputError(file_, path, message);
    }

    // ---- typed values

    void expectObject(const Node& n) const {
        if (!n.value.is_object()) fail(n.path, "expected an object, got " + describe(n.value));
    }

    void expectArray(const Node& n) const {
        if (!n.value.is_array()) fail(n.path, "expected an array, got " + describe(n.value));
    }

    void checkKeys(const Node& n, const std::vector<std::string>& allowed) const {
        expectObject(n);
        for (const auto& item : n.value.items()) {
            if (std::find(allowed.begin(), allowed.end(), item.key()) != allowed.end()) continue;
            const std::string hint = suggestion(item.key(), allowed);
            fail(n[item.key()].path,
                 "unknown key \"" + item.key() + "\"" + (hint.empty() ? " (valid keys: " + joined(allowed) + ")" : hint));
        }
    }

    void require(const Node& n, const std::string& key) const {
        if (!n.has(key)) fail(n.path, "missing required key \"" + key + "\"");
    }

    float number(const Node& n) const {
        if (!n.value.is_number()) fail(n.path, "expected a number, got " + describe(n.value));
        return n.value.get<float>();
    }

    float positive(const Node& n) const {
        const float v = number(n);
        if (!(v > 0.0f)) fail(n.path, "must be positive");
        return v;
    }

    float nonNegative(const Node& n) const {
        const float v = number(n);
        if (v < 0.0f) fail(n.path, "must not be negative");
        return v;
    }

    int integer(const Node& n, int lowest, int highest) const {
        if (!n.value.is_number()) fail(n.path, "expected an integer, got " + describe(n.value));
        const double v = n.value.get<double>();
        if (v != std::floor(v)) fail(n.path, "expected an integer");
        if (v < lowest || v > highest)
            fail(n.path, "must be in " + std::to_string(lowest) + ".." + std::to_string(highest));
        return int(v);
    }

    float unitInterval(const Node& n) const {
        const float v = number(n);
        if (!(v >= 0.0f && v <= 1.0f)) fail(n.path, "must be in [0, 1]");
        return v;
    }

    bool boolean(const Node& n) const {
        if (!n.value.is_boolean()) fail(n.path, "expected true or false, got " + describe(n.value));
        return n.value.get<bool>();
    }

    std::string string(const Node& n) const {
        if (!n.value.is_string()) fail(n.path, "expected a string, got " + describe(n.value));
        return n.value.get<std::string>();
    }

    template <int L>
    glm::vec<L, float> vector(const Node& n) const {
        const std::string expected = "expected an array of " + std::to_string(L) + " numbers";
        if (!n.value.is_array() || n.value.size() != L) fail(n.path, expected + ", got " + describe(n.value));
        glm::vec<L, float> v;
        for (int i = 0; i < L; ++i) {
            if (!n.value[i].is_number()) fail(n.path, expected + ", got " + describe(n.value[i]) + " at index " + std::to_string(i));
            v[i] = number(n[size_t(i)]);
        }
        return v;
    }

    glm::vec3 vec3(const Node& n) const { return vector<3>(n); }

    glm::vec3 nonZeroVec3(const Node& n) const {
        const glm::vec3 v = vec3(n);
        if (v == glm::vec3(0.0f)) fail(n.path, "must not be the zero vector");
        return v;
    }

    /// Normalizes, but leaves vectors that are already unit length (such as those writeScene wrote) exactly as they are.
    static glm::vec3 unitLength(const glm::vec3& v) {
        return std::abs(glm::dot(v, v) - 1.0f) <= 1e-6f ? v : glm::normalize(v);
    }

    glm::vec3 color(const Node& n) const {
        const glm::vec3 c = vec3(n);
        if (glm::any(glm::lessThan(c, glm::vec3(0.0f)))) fail(n.path, "color components must not be negative");
        return c;
    }

    /// A color that is a fraction of light, such as an albedo: components in [0, 1].
    glm::vec3 reflectance(const Node& n) const {
        const glm::vec3 c = color(n);
        if (glm::any(glm::greaterThan(c, glm::vec3(1.0f))))
            fail(n.path, "a reflectance reflects at most all light: components must be in [0, 1]");
        return c;
    }

    // ---- camera, image, fog, render settings

    void readCamera(const Node& n) {
        checkKeys(n, {"position", "look_at", "up", "fov", "aperture", "focus_distance"});
        Camera& camera = scene_.camera;
        if (n.has("position")) camera.position = vec3(n["position"]);
        if (n.has("look_at")) camera.lookAt = vec3(n["look_at"]);
        if (n.has("up")) camera.up = nonZeroVec3(n["up"]);
        if (n.has("fov")) {
            camera.fovY = number(n["fov"]);
            if (!(camera.fovY > 0.0f && camera.fovY < 180.0f)) fail(n["fov"].path, "must be in (0, 180) degrees");
        }
        if (n.has("aperture")) camera.aperture = nonNegative(n["aperture"]);
        if (n.has("focus_distance")) camera.focusDistance = nonNegative(n["focus_distance"]);
        const glm::vec3 view = camera.lookAt - camera.position;
        if (view == glm::vec3(0.0f)) fail(n.path, "look_at must differ from position");
        if (glm::length(glm::cross(glm::normalize(view), glm::normalize(camera.up))) < 1e-6f)
            fail(n.path, "up must not be parallel to the viewing direction");
    }

    void readImage(const Node& n) {
        checkKeys(n, {"width", "height", "spp"});
        if (n.has("width")) scene_.image.width = integer(n["width"], 1, 65536);
        if (n.has("height")) scene_.image.height = integer(n["height"], 1, 65536);
        if (n.has("spp")) scene_.image.samplesPerPixel = integer(n["spp"], 1, 1 << 20);
    }

    void readFog(const Node& n) {
        checkKeys(n, {"density", "color"});
        require(n, "density");
        scene_.fog.density = nonNegative(n["density"]);
        if (n.has("color")) scene_.fog.color = color(n["color"]);
    }

    void readRender(const Node& n) {
        checkKeys(n, {"max_depth", "min_throughput", "polarized"});
        RenderSettings& render = scene_.render;
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
        const std::string type = string(n["type"]);
        const auto known = std::find_if(kTextureTypes.begin(), kTextureTypes.end(), [&](const auto& t) { return t.first == type; });
        if (known == kTextureTypes.end()) {
            std::vector<std::string> names;
            for (const auto& t : kTextureTypes) names.push_back(t.first);
            const std::string hint = suggestion(type, names);
            fail(n["type"].path, "unknown texture type \"" + type + "\"" + (hint.empty() ? " (expected " + joined(names) + ")" : hint));
        }
        Texture texture;
        texture.type = known->second;
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
            {"sphere", {LightType::Sphere, {"center", "radius"}}},
        };
        auto found = requiredKeysOf.find(type);
        if (found == requiredKeysOf.end()) {
            const std::vector<std::string> types = {"point", "directional", "quad", "sphere"};
            const std::string hint = suggestion(type, types);
            fail(n["type"].path, "unknown light type \"" + type + "\"" + (hint.empty() ? " (expected " + joined(types) + ")" : hint));
        }
        Light light;
        light.type = found->second.first;
        const std::vector<std::string>& required = found->second.second;
        std::vector<std::string> keys = {"type", "color", "intensity"};
        keys.insert(keys.end(), required.begin(), required.end());
        const bool isArea = light.type == LightType::Quad || light.type == LightType::Sphere;
        if (isArea) keys.push_back("samples");
        checkKeys(n, keys);
        for (const std::string& key : required) require(n, key);

        if (n.has("color")) light.color = color(n["color"]);
        if (n.has("intensity")) light.intensity = positive(n["intensity"]);
        if (n.has("samples")) light.samples = integer(n["samples"], 1, 4096);
        switch (light.type) {
        case LightType::Point: light.position = vec3(n["position"]); break;
        case LightType::Directional: light.direction = unitLength(nonZeroVec3(n["direction"])); break;
        case LightType::Quad:
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

    TriangleMesh generateShape(const std::string& shape, const Node& n) const {
        if (shape == "cube") return makeCube();
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

    void readObject(const Node& n) {
        expectObject(n);
        require(n, "type");
        const std::string type = string(n["type"]);
        if (type == "mesh") {
            checkKeys(n, {"type", "file", "material", "transform"});
            require(n, "file");
            const uint32_t mesh = loadMeshFile(n["file"], std::nullopt);
            addInstance(mesh, n);
        } else if (type == "instance") {
            checkKeys(n, {"type", "mesh", "material", "transform"});
            require(n, "mesh");
            const Node name = n["mesh"];
            auto it = meshNamed_.find(string(name));
            if (it == meshNamed_.end()) {
                std::vector<std::string> names;
                for (const auto& [meshName, index] : meshNamed_) names.push_back(meshName);
                fail(name.path, "unknown mesh \"" + string(name) + "\"" + suggestion(string(name), names));
            }
            addInstance(it->second, n);
        } else if (type == "generated") {
            require(n, "shape");
            const std::string shape = shapeName(n["shape"]);
            std::vector<std::string> keys = shapeKeys(shape);
            keys.insert(keys.end(), {"type", "shape", "material", "transform"});
            checkKeys(n, keys);
            addOwnMesh(generateShape(shape, n), n);
        } else if (type == "triangles") {
            checkKeys(n, {"type", "vertices", "indices", "normals", "uvs", "material", "face_materials", "transform"});
            if (n.has("material") && n.has("face_materials"))
                fail(n.path, "\"material\" and \"face_materials\" cannot be combined");
            addOwnMesh(inlineTriangles(n), n);
        } else if (type == "sphere") {
            checkKeys(n, {"type", "center", "radius", "material", "transform"});
            require(n, "center");
            require(n, "radius");
            scene_.spheres.push_back(sphere(n));
        } else {
            const std::vector<std::string> types = {"mesh", "instance", "generated", "triangles", "sphere"};
            const std::string hint = suggestion(type, types);
            fail(n["type"].path, "unknown object type \"" + type + "\"" + (hint.empty() ? " (expected " + joined(types) + ")" : hint));
        }
    }

    void addInstance(uint32_t mesh, const Node& n) {
        const uint32_t material = n.has("material") ? materialNamed(n["material"]) : MeshInstance::kMeshMaterials;
        scene_.instances.push_back({mesh, optionalTransform(n), material});
    }

    /// Generated and inline meshes belong to one object, so its material goes into the mesh itself.
    void addOwnMesh(TriangleMesh mesh, const Node& n) {
        if (mesh.faceMaterial.empty())
            mesh.faceMaterial.assign(mesh.triangles.size(), n.has("material") ? materialNamed(n["material"]) : defaultMaterial());
        scene_.instances.push_back({addMesh(std::move(mesh)), optionalTransform(n), MeshInstance::kMeshMaterials});
    }

    Sphere sphere(const Node& n) {
        Sphere s{vec3(n["center"]), positive(n["radius"]), 0};
        s.material = n.has("material") ? materialNamed(n["material"]) : defaultMaterial();
        if (!n.has("transform")) return s;
        const glm::mat4 m = transform(n["transform"]);
        // A sphere stays a sphere only under rotation, uniform scale and translation.
        const glm::vec3 x(m[0]), y(m[1]), z(m[2]);
        const float scale = glm::length(x), tolerance = 1e-4f * scale * scale;
        const bool similarity = std::abs(glm::dot(y, y) - scale * scale) <= tolerance &&
                                std::abs(glm::dot(z, z) - scale * scale) <= tolerance &&
                                std::abs(glm::dot(x, y)) <= tolerance && std::abs(glm::dot(y, z)) <= tolerance &&
                                std::abs(glm::dot(x, z)) <= tolerance;
        if (!similarity) fail(n["transform"].path, "a sphere's transform must be a similarity (uniform scale, rotation, translation)");
        s.center = glm::vec3(m * glm::vec4(s.center, 1.0f));
        s.radius *= scale;
        return s;
    }

    std::string file_;
    std::filesystem::path folder_;
    Scene scene_;
    std::unordered_map<std::string, uint32_t> materialIndex_;
    std::map<std::string, uint32_t> meshNamed_;
    std::map<std::filesystem::path, uint32_t> meshOfFile_;
    std::set<std::string> materialPrefixes_;
    std::map<std::pair<std::filesystem::path, bool>, std::shared_ptr<const Image>> textureImages_;
};

// ---- writing

Json array(const glm::vec3& v) { return Json::array({v.x, v.y, v.z}); }

Json textureJson(const Texture& texture, bool scalar) {
    const auto named = std::find_if(kTextureTypes.begin(), kTextureTypes.end(), [&](const auto& t) { return t.second == texture.type; });
    Json j = {{"type", named->first}};
    if (texture.type == TextureType::Image) {
        j["file"] = texture.file.string();
        return j;
    }
    if (scalar) j["values"] = Json::array({texture.color0.x, texture.color1.x});
    else j["colors"] = Json::array({array(texture.color0), array(texture.color1)});
    j["scale"] = texture.scale;
    if (hasOctaves(texture.type)) j["octaves"] = texture.octaves;
    return j;
}

Json materialJson(const Material& m) {
    const Json color = m.colorTexture ? textureJson(*m.colorTexture, false) : array(m.color);
    const Json roughness = m.roughnessTexture ? textureJson(*m.roughnessTexture, true) : Json(m.roughness);
    switch (m.type) {
    case MaterialType::Diffuse: return {{"type", "diffuse"}, {"color", color}};
    case MaterialType::Plastic:
        return {{"type", "plastic"}, {"color", color}, {"specular", m.specular}, {"shininess", m.shininess}};
    case MaterialType::Mirror: return {{"type", "mirror"}, {"color", color}};
    case MaterialType::Conductor:
        return {{"type", "conductor"}, {"eta", array(m.eta)}, {"k", array(m.k)}, {"roughness", roughness},
                {"samples", m.samples}};
    case MaterialType::Dielectric:
        return {{"type", "dielectric"}, {"ior", m.ior}, {"absorption", array(m.absorption)}, {"roughness", roughness},
                {"samples", m.samples}};
    }
    throw std::invalid_argument("writeScene: unknown material type");
}

Json lightJson(const Light& light) {
    Json j;
    switch (light.type) {
    case LightType::Point: j = {{"type", "point"}, {"position", array(light.position)}}; break;
    case LightType::Directional: j = {{"type", "directional"}, {"direction", array(light.direction)}}; break;
    case LightType::Quad:
        j = {{"type", "quad"}, {"corner", array(light.position)}, {"edge_u", array(light.edgeU)},
             {"edge_v", array(light.edgeV)}, {"samples", light.samples}};
        break;
    case LightType::Sphere:
        j = {{"type", "sphere"}, {"center", array(light.position)}, {"radius", light.radius}, {"samples", light.samples}};
        break;
    }
    j["color"] = array(light.color);
    j["intensity"] = light.intensity;
    return j;
}

Json meshJson(const TriangleMesh& mesh, const std::vector<Material>& materials) {
    Json vertices = Json::array(), indices = Json::array();
    for (const glm::vec3& p : mesh.positions) vertices.push_back(array(p));
    for (const glm::uvec3& t : mesh.triangles) indices.push_back({t.x, t.y, t.z});
    Json j = {{"vertices", std::move(vertices)}, {"indices", std::move(indices)}};
    if (!mesh.normals.empty()) {
        Json& normals = j["normals"] = Json::array();
        for (const glm::vec3& n : mesh.normals) normals.push_back(array(n));
    }
    if (!mesh.uvs.empty()) {
        Json& uvs = j["uvs"] = Json::array();
        for (const glm::vec2& uv : mesh.uvs) uvs.push_back({uv.x, uv.y});
    }
    if (!mesh.faceMaterial.empty()) {
        Json& faces = j["face_materials"] = Json::array();
        for (uint32_t m : mesh.faceMaterial) faces.push_back(materials.at(m).name);
    }
    return j;
}

Json matrixJson(const glm::mat4& m) {
    Json j = Json::array();
    for (int row = 0; row < 4; ++row)
        for (int column = 0; column < 4; ++column) j.push_back(m[column][row]);
    return j;
}

} // namespace

Scene parseScene(const std::string& jsonText, const std::filesystem::path& file) {
    const Json json = parseJson(jsonText, file.string());
    return SceneReader(file).read(json);
}

Scene loadScene(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw InputError(file.string(), "", "cannot open scene file");
    std::ostringstream text;
    text << in.rdbuf();
    return parseScene(text.str(), file);
}

std::string writeScene(const Scene& scene) {
    std::set<std::string> names;
    for (const Material& m : scene.materials)
        if (m.name.empty() || !names.insert(m.name).second)
            throw std::invalid_argument("writeScene: material names must be unique and non-empty (\"" + m.name + "\")");

    const Camera& camera = scene.camera;
    Json root;
    root["camera"] = {{"position", array(camera.position)}, {"look_at", array(camera.lookAt)},
                      {"up", array(camera.up)}, {"fov", camera.fovY}, {"aperture", camera.aperture},
                      {"focus_distance", camera.focusDistance}};
    root["image"] = {{"width", scene.image.width}, {"height", scene.image.height}, {"spp", scene.image.samplesPerPixel}};
    root["background"] = array(scene.background);
    root["fog"] = {{"density", scene.fog.density}, {"color", array(scene.fog.color)}};
    root["render"] = {{"max_depth", scene.render.maxDepth}, {"min_throughput", scene.render.minThroughput},
                      {"polarized", scene.render.polarized}};
    Json& materials = root["materials"] = Json::object();
    for (const Material& m : scene.materials) materials[m.name] = materialJson(m);
    Json& lights = root["lights"] = Json::array();
    for (const Light& light : scene.lights) lights.push_back(lightJson(light));
    Json& meshes = root["meshes"] = Json::object();
    for (size_t i = 0; i < scene.meshes.size(); ++i)
        meshes["mesh" + std::to_string(i)] = meshJson(scene.meshes[i], scene.materials);

    Json& objects = root["objects"] = Json::array();
    for (const MeshInstance& instance : scene.instances) {
        Json object = {{"type", "instance"}, {"mesh", "mesh" + std::to_string(instance.mesh)}};
        if (instance.material != MeshInstance::kMeshMaterials) object["material"] = scene.materials.at(instance.material).name;
        object["transform"] = {{"matrix", matrixJson(instance.transform)}};
        objects.push_back(std::move(object));
    }
    for (const Sphere& s : scene.spheres)
        objects.push_back({{"type", "sphere"}, {"center", array(s.center)}, {"radius", s.radius},
                           {"material", scene.materials.at(s.material).name}});
    return root.dump(2) + "\n";
}

} // namespace wideray
