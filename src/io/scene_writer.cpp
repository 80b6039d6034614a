// SceneDescription -> JSON, which parseScene reads back into an equal scene.
#include <set>
#include <stdexcept>

#include "io/json_document.h"
#include "io/scene_parser.h"
#include "io/scene_vocabulary.h"

namespace wideray {
namespace {

Json array(const glm::vec3& v) { return Json::array({v.x, v.y, v.z}); }

Json textureJson(const Texture& texture, bool scalar) {
    Json j = {{"type", nameOf(kTextureTypes, texture.type)}};
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
    case LightType::Triangle:
        j = {{"type", light.type == LightType::Quad ? "quad" : "triangle"}, {"corner", array(light.position)}, {"edge_u", array(light.edgeU)},
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

Json analyticJson(const AnalyticObject& a, const std::vector<Material>& materials) {
    const bool twoSheets = a.shape == AnalyticShape::TwoSheetHyperboloid;
    Json object = {{"type", nameOf(kAnalyticShapes, twoSheets ? AnalyticShape::Hyperboloid : a.shape)},
                   {"transform", {{"matrix", matrixJson(a.transform)}}},
                   {"material", materials.at(a.material).name}};
    if (a.endTransform) object["end_transform"] = {{"matrix", matrixJson(*a.endTransform)}};
    if (twoSheets) object["sheets"] = 2;
    if (a.shape == AnalyticShape::Quadric) object["coefficients"] = a.coefficients;
    if (a.shape == AnalyticShape::Blob) {
        object["threshold"] = a.threshold;
        Json& balls = object["balls"] = Json::array();
        for (const BlobBall& b : a.balls) balls.push_back({{"center", array(b.center)}, {"radius", b.radius}, {"strength", b.strength}});
    }
    if (a.shape == AnalyticShape::Torus) {
        object["major_radius"] = a.majorRadius;
        object["minor_radius"] = a.minorRadius;
    }
    const bool hasCaps = a.shape != AnalyticShape::Ellipsoid && a.shape != AnalyticShape::Quadric &&
                         a.shape != AnalyticShape::Torus && a.shape != AnalyticShape::Blob;
    if (hasCaps && !a.capped) object["capped"] = false;
    return object;
}

Json instanceJson(const MeshInstance& instance, const std::vector<Material>& materials) {
    Json object = {{"type", "instance"}, {"mesh", "mesh" + std::to_string(instance.mesh)}};
    if (instance.material != MeshInstance::kMeshMaterials) object["material"] = materials.at(instance.material).name;
    object["transform"] = {{"matrix", matrixJson(instance.transform)}};
    if (instance.endTransform) object["end_transform"] = {{"matrix", matrixJson(*instance.endTransform)}};
    return object;
}

/// A CSG node with its operands, each solid placed by its own (composed) transform.
Json csgJson(const CsgObject& csg, uint32_t index, const std::vector<Material>& materials) {
    const CsgNode& node = csg.nodes[index];
    if (node.kind == CsgNode::Kind::Analytic) return analyticJson(csg.analytics[node.solid], materials);
    if (node.kind == CsgNode::Kind::Mesh) return instanceJson(csg.meshes[node.solid], materials);
    Json operands = Json::array();
    for (uint32_t operand : node.operands) operands.push_back(csgJson(csg, operand, materials));
    return {{"type", "csg"}, {"operation", nameOf(kCsgOperations, node.operation)}, {"operands", std::move(operands)}};
}

Json cameraJson(const Camera& camera) {
    return {{"position", array(camera.position)}, {"look_at", array(camera.lookAt)}, {"up", array(camera.up)},
            {"fov", camera.fovY}, {"aperture", camera.aperture}, {"focus_distance", camera.focusDistance},
            {"shutter", {camera.shutterOpen, camera.shutterClose}}};
}

} // namespace

std::string writeScene(const SceneDescription& scene) {
    std::set<std::string> names;
    for (const Material& m : scene.materials)
        if (m.name.empty() || !names.insert(m.name).second)
            throw std::invalid_argument("writeScene: material names must be unique and non-empty (\"" + m.name + "\")");

    Json root;
    root["camera"] = cameraJson(scene.camera);
    if (const std::optional<Animation>& animation = scene.animation) {
        Json keys = Json::array();
        for (const CameraKey& key : animation->keys) {
            Json k = cameraJson(key.camera);
            k["frame"] = key.frame;
            keys.push_back(std::move(k));
        }
        root["animation"] = {{"frames", {animation->firstFrame, animation->lastFrame}}, {"keyframes", std::move(keys)}};
    }
    root["image"] = {{"width", scene.image.width}, {"height", scene.image.height}, {"spp", scene.image.samplesPerPixel}};
    root["background"] = array(scene.background);
    if (const std::optional<EnvironmentMap>& map = scene.environment)
        root["environment"] = {{"file", map->file.string()}, {"mapping", nameOf(kEnvironmentMappings, map->mapping)},
                               {"scale", array(map->scale)},
                               {"transform", {{"matrix", matrixJson(glm::mat4(map->toWorld))}}}};
    root["fog"] = {{"density", scene.fog.density}, {"color", array(scene.fog.color)}};
    root["render"] = {{"integrator", nameOf(kIntegrators, scene.render.integrator)}, {"max_depth", scene.render.maxDepth}, {"min_throughput", scene.render.minThroughput},
                      {"polarized", scene.render.polarized}};
    Json& materials = root["materials"] = Json::object();
    for (const Material& m : scene.materials) materials[m.name] = materialJson(m);
    Json& lights = root["lights"] = Json::array();
    for (const Light& light : scene.lights) lights.push_back(lightJson(light));
    Json& meshes = root["meshes"] = Json::object();
    for (size_t i = 0; i < scene.meshes.size(); ++i)
        meshes["mesh" + std::to_string(i)] = meshJson(scene.meshes[i], scene.materials);

    Json& objects = root["objects"] = Json::array();
    for (const MeshInstance& instance : scene.instances) objects.push_back(instanceJson(instance, scene.materials));
    for (const Sphere& s : scene.spheres)
        objects.push_back({{"type", "sphere"}, {"center", array(s.center)}, {"radius", s.radius},
                           {"material", scene.materials.at(s.material).name}});
    for (const HeightField& f : scene.heightFields) {
        const TerrainParameters& t = f.terrain;
        objects.push_back({{"type", "heightfield"}, {"resolution", t.resolution}, {"octaves", t.octaves},
                           {"lacunarity", t.lacunarity}, {"gain", t.gain}, {"offset", t.offset}, {"roughness", t.roughness},
                           {"frequency", t.frequency}, {"height", t.height}, {"seed", t.seed},
                           {"transform", {{"matrix", matrixJson(f.transform)}}},
                           {"material", scene.materials.at(f.material).name}});
    }
    for (const AnalyticObject& a : scene.analytics) objects.push_back(analyticJson(a, scene.materials));
    for (const CsgObject& csg : scene.csgs) objects.push_back(csgJson(csg, 0, scene.materials));
    return root.dump(2) + "\n";
}

} // namespace wideray
