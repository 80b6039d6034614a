// glTF 2.0 loading (.gltf and .glb) through tinygltf: the triangle primitives of the default
// scene, flattened into one mesh with node transforms applied.
#include <algorithm>
#include <cctype>
#include <cstring>
#include <fstream>
#include <iostream>
#include <limits>
#include <optional>
#include <span>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <tiny_gltf.h>

#include "core/error.h"
#include "io/mesh_io.h"

namespace wideray {
namespace {

/// Images are decoded only when a material's base color uses them (mesh_framing.cpp): here the bytes
/// of a data URI are kept as they are. Images in buffer views are copied from their buffer, checked,
/// by SceneFlattener (tinygltf passes them without checking the view against its buffer), and
/// external files are read by name. tinygltf itself warns about (and tolerates) missing files.
bool keepImageEncoded(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
    // tinygltf leaves uri empty for data URIs (it names external files only).
    if (image->bufferView < 0 && image->uri.empty() && size > 0) {
        image->image.assign(bytes, bytes + size);
        image->as_is = true;
    }
    return true;
}

std::string trimmed(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
    return s;
}

glm::dmat4 localTransform(const tinygltf::Node& node) {
    if (node.matrix.size() == 16) return glm::make_mat4(node.matrix.data()); // column-major, as glTF stores it
    glm::dmat4 transform(1.0);
    if (node.translation.size() == 3)
        transform = glm::translate(transform, glm::dvec3(node.translation[0], node.translation[1], node.translation[2]));
    if (node.rotation.size() == 4) {
        const glm::dquat rotation(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
        transform *= glm::mat4_cast(rotation);
    }
    if (node.scale.size() == 3) transform = glm::scale(transform, glm::dvec3(node.scale[0], node.scale[1], node.scale[2]));
    return transform;
}

/// Reads accessor elements as floats (normalized integers are scaled to [0,1] or [-1,1]) or as
/// unsigned indices, checking every offset against its buffer.
class AccessorReader {
public:
    /// `inputBytes`: the size of the file read, which bounds the accessors that hold no data.
    AccessorReader(const tinygltf::Model& model, const std::string& file, size_t inputBytes)
        : model_(model), file_(file), dataBytes_(inputBytes) {
        for (const tinygltf::Buffer& buffer : model.buffers) dataBytes_ += buffer.data.size();
    }

    template <int N>
    std::vector<glm::vec<N, float>> readFloats(int accessorIndex) {
        const tinygltf::Accessor& accessor = checkedAccessor(accessorIndex);
        const std::string where = "accessors[" + std::to_string(accessorIndex) + "]";
        if (tinygltf::GetNumComponentsInType(uint32_t(accessor.type)) != N)
            throw InputError(file_, where, "expected " + std::to_string(N) + " components per element");
        std::vector<glm::vec<N, float>> values(accessor.count, glm::vec<N, float>(0.0f));
        forEachComponent(accessorIndex, N, [&](size_t element, int component, const unsigned char* bytes) {
            values[element][component] = componentAsFloat(accessor, bytes, where);
        });
        return values;
    }

    std::vector<uint32_t> readIndices(int accessorIndex) {
        const tinygltf::Accessor& accessor = checkedAccessor(accessorIndex);
        const std::string where = "accessors[" + std::to_string(accessorIndex) + "]";
        if (accessor.type != TINYGLTF_TYPE_SCALAR) throw InputError(file_, where, "indices must be scalars");
        std::vector<uint32_t> indices(accessor.count, 0);
        forEachComponent(accessorIndex, 1, [&](size_t element, int, const unsigned char* bytes) {
            switch (accessor.componentType) {
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: indices[element] = *bytes; break;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: indices[element] = load<uint16_t>(bytes); break;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: indices[element] = load<uint32_t>(bytes); break;
            default: throw InputError(file_, where, "indices must be unsigned integers");
            }
        });
        return indices;
    }

private:
    template <class T>
    static T load(const unsigned char* bytes) {
        T value;
        std::memcpy(&value, bytes, sizeof(T));
        return value;
    }

    const tinygltf::Accessor& checkedAccessor(int accessorIndex) const {
        if (accessorIndex < 0 || size_t(accessorIndex) >= model_.accessors.size())
            throw InputError(file_, "accessors[" + std::to_string(accessorIndex) + "]", "no such accessor");
        const tinygltf::Accessor& accessor = model_.accessors[size_t(accessorIndex)];
        const std::string where = "accessors[" + std::to_string(accessorIndex) + "]";
        if (accessor.sparse.isSparse) throw InputError(file_, where, "sparse accessors are not supported");
        // Checked before the elements are allocated: an element takes a byte of data at least (and an
        // accessor without bufferView, all zeros, takes none).
        if (accessor.count > dataBytes_)
            throw InputError(file_, where, "count " + std::to_string(accessor.count) + " is more than the file's " +
                             std::to_string(dataBytes_) + " bytes of data can justify");
        return accessor;
    }

    /// Calls visit(element, component, bytes) for every component; an accessor without a
    /// bufferView reads as zeros, so visits nothing.
    template <class Visit>
    void forEachComponent(int accessorIndex, int componentCount, Visit visit) const {
        const tinygltf::Accessor& accessor = model_.accessors[size_t(accessorIndex)];
        const std::string where = "accessors[" + std::to_string(accessorIndex) + "]";
        if (accessor.bufferView < 0 || accessor.count == 0) return;
        if (size_t(accessor.bufferView) >= model_.bufferViews.size())
            throw InputError(file_, where, "no such bufferView " + std::to_string(accessor.bufferView));
        const tinygltf::BufferView& view = model_.bufferViews[size_t(accessor.bufferView)];
        if (view.buffer < 0 || size_t(view.buffer) >= model_.buffers.size())
            throw InputError(file_, where, "no such buffer " + std::to_string(view.buffer));
        const std::vector<unsigned char>& buffer = model_.buffers[size_t(view.buffer)].data;

        const int componentSize = tinygltf::GetComponentSizeInBytes(uint32_t(accessor.componentType));
        const int stride = accessor.ByteStride(view);
        if (componentSize <= 0 || stride <= 0) throw InputError(file_, where, "bad component type or byte stride");
        const size_t start = view.byteOffset + accessor.byteOffset;
        const size_t end = start + size_t(stride) * (accessor.count - 1) + size_t(componentSize * componentCount);
        if (end > view.byteOffset + view.byteLength || end > buffer.size())
            throw InputError(file_, where, "data runs past the end of its bufferView");

        for (size_t element = 0; element < accessor.count; ++element) {
            const unsigned char* bytes = buffer.data() + start + element * size_t(stride);
            for (int component = 0; component < componentCount; ++component)
                visit(element, component, bytes + component * componentSize);
        }
    }

    float componentAsFloat(const tinygltf::Accessor& accessor, const unsigned char* bytes,
                           const std::string& where) const {
        const bool normalized = accessor.normalized;
        switch (accessor.componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return load<float>(bytes);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? *bytes / 255.0f : float(*bytes);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            const float value = load<uint16_t>(bytes);
            return normalized ? value / 65535.0f : value;
        }
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            const float value = load<int8_t>(bytes);
            return normalized ? std::max(value / 127.0f, -1.0f) : value;
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            const float value = load<int16_t>(bytes);
            return normalized ? std::max(value / 32767.0f, -1.0f) : value;
        }
        default: throw InputError(file_, where, "unsupported component type " + std::to_string(accessor.componentType));
        }
    }

    const tinygltf::Model& model_;
    const std::string& file_;
    size_t dataBytes_;
};

/// Appends the triangle primitives of the scene's nodes to one mesh.
class SceneFlattener {
public:
    SceneFlattener(const tinygltf::Model& model, const std::string& file, size_t inputBytes)
        : model_(model), file_(file), accessors_(model, file, inputBytes) {
        for (size_t m = 0; m < model.materials.size(); ++m) {
            const tinygltf::Material& material = model.materials[m];
            const std::vector<double>& color = material.pbrMetallicRoughness.baseColorFactor;
            MeshMaterial meshMaterial{material.name.empty() ? "material" + std::to_string(m) : material.name};
            if (color.size() >= 3) meshMaterial.diffuse = glm::vec3(color[0], color[1], color[2]);
            setDiffuseImage(material.pbrMetallicRoughness.baseColorTexture.index, meshMaterial);
            mesh_.materials.push_back(meshMaterial);
        }
    }

    /// The image of a texture: its file (relative to the glTF file's folder), or its bytes when it is
    /// inside the file (decoded only if the material is rendered, mesh_framing.cpp).
    void setDiffuseImage(int textureIndex, MeshMaterial& material) const {
        if (textureIndex < 0 || size_t(textureIndex) >= model_.textures.size()) return;
        const int source = model_.textures[size_t(textureIndex)].source;
        if (source < 0 || size_t(source) >= model_.images.size()) return;
        const tinygltf::Image& image = model_.images[size_t(source)];
        const std::string where = "images[" + std::to_string(source) + "]";
        std::span<const unsigned char> bytes;
        if (image.bufferView >= 0) {
            if (size_t(image.bufferView) >= model_.bufferViews.size())
                throw InputError(file_, where, "no such bufferView " + std::to_string(image.bufferView));
            const tinygltf::BufferView& view = model_.bufferViews[size_t(image.bufferView)];
            if (view.buffer < 0 || size_t(view.buffer) >= model_.buffers.size())
                throw InputError(file_, where, "its bufferView names no buffer");
            const std::vector<unsigned char>& buffer = model_.buffers[size_t(view.buffer)].data;
            if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset)
                throw InputError(file_, where, "its bufferView runs past the end of its buffer");
            bytes = {buffer.data() + view.byteOffset, view.byteLength};
        } else if (image.as_is) {
            bytes = image.image;
        } else {
            material.diffuseTexture = image.uri;  // empty where a data URI could not be decoded
            return;
        }
        // The format from the MIME type (tinygltf takes a data URI's from its prefix); without one,
        // OpenImageIO tries every format it reads.
        const std::string& type = image.mimeType;
        const std::string extension = type == "image/png" ? ".png" : type == "image/jpeg" ? ".jpg" : "";
        material.diffuseTexture = file_ + ":" + where + extension;
        material.diffuseTextureBytes = std::make_shared<const std::vector<unsigned char>>(bytes.begin(), bytes.end());
    }

    void addNode(int nodeIndex, const glm::dmat4& parentTransform) {
        const std::string where = "nodes[" + std::to_string(nodeIndex) + "]";
        if (nodeIndex < 0 || size_t(nodeIndex) >= model_.nodes.size()) throw InputError(file_, where, "no such node");
        if (onPath_.size() < model_.nodes.size()) onPath_.resize(model_.nodes.size(), false);
        if (onPath_[size_t(nodeIndex)]) throw InputError(file_, where, "node is its own ancestor");
        // glTF's nodes form disjoint trees; a node reached twice could repeat a subtree exponentially.
        if (visited_.size() < model_.nodes.size()) visited_.resize(model_.nodes.size(), false);
        if (visited_[size_t(nodeIndex)])
            throw InputError(file_, where, "node is reached twice (a node has one parent at most, and a scene "
                                           "lists each root node once)");
        visited_[size_t(nodeIndex)] = true;
        onPath_[size_t(nodeIndex)] = true;

        const tinygltf::Node& node = model_.nodes[size_t(nodeIndex)];
        const glm::dmat4 transform = parentTransform * localTransform(node);
        if (node.mesh >= 0) {
            if (size_t(node.mesh) >= model_.meshes.size())
                throw InputError(file_, where, "no such mesh " + std::to_string(node.mesh));
            const tinygltf::Mesh& gltfMesh = model_.meshes[size_t(node.mesh)];
            for (size_t p = 0; p < gltfMesh.primitives.size(); ++p)
                addPrimitive(gltfMesh.primitives[p], transform,
                             "meshes[" + std::to_string(node.mesh) + "].primitives[" + std::to_string(p) + "]");
        }
        for (int child : node.children) addNode(child, transform);
        onPath_[size_t(nodeIndex)] = false;
    }

    /// Normals and uvs survive only if every primitive had them.
    TriangleMesh take() {
        if (!allHaveNormals_) mesh_.normals.clear();
        if (!allHaveUvs_) mesh_.uvs.clear();
        if (model_.materials.empty()) {
            mesh_.faceMaterial.clear();
            mesh_.materials.clear();
        }
        return std::move(mesh_);
    }

private:
    void addPrimitive(const tinygltf::Primitive& primitive, const glm::dmat4& transform, const std::string& where) {
        if (primitive.mode != TINYGLTF_MODE_TRIANGLES) {
            std::cerr << "warning: " << file_ << ":" << where << ": skipping primitive of mode " << primitive.mode
                      << " (only triangles are loaded)\n";
            return;
        }
        const auto attribute = [&](const char* name) -> std::optional<int> {
            const auto it = primitive.attributes.find(name);
            return it == primitive.attributes.end() ? std::nullopt : std::optional<int>(it->second);
        };
        const std::optional<int> positionAccessor = attribute("POSITION");
        if (!positionAccessor) throw InputError(file_, where, "primitive has no POSITION attribute");

        const std::vector<glm::vec3> positions = accessors_.readFloats<3>(*positionAccessor);
        const size_t firstVertex = mesh_.positions.size();
        for (const glm::vec3& p : positions) mesh_.positions.emplace_back(transform * glm::dvec4(p, 1.0));

        const std::optional<int> normalAccessor = attribute("NORMAL");
        allHaveNormals_ = allHaveNormals_ && normalAccessor;
        if (allHaveNormals_) {
            const glm::dmat3 normalTransform = glm::transpose(glm::inverse(glm::dmat3(transform)));
            for (const glm::vec3& n : accessors_.readFloats<3>(*normalAccessor))
                mesh_.normals.emplace_back(glm::normalize(normalTransform * glm::dvec3(n)));
        }
        const std::optional<int> uvAccessor = attribute("TEXCOORD_0");
        allHaveUvs_ = allHaveUvs_ && uvAccessor;
        if (allHaveUvs_) {
            // glTF's v runs down the image, ours (OBJ's) up.
            for (const glm::vec2& uv : accessors_.readFloats<2>(*uvAccessor)) mesh_.uvs.emplace_back(uv.x, 1.0f - uv.y);
        }
        if ((allHaveNormals_ && mesh_.normals.size() != mesh_.positions.size()) ||
            (allHaveUvs_ && mesh_.uvs.size() != mesh_.positions.size()))
            throw InputError(file_, where, "attributes have different counts");

        std::vector<uint32_t> indices;
        if (primitive.indices >= 0) {
            indices = accessors_.readIndices(primitive.indices);
        } else {
            indices.resize(positions.size());
            for (size_t i = 0; i < indices.size(); ++i) indices[i] = uint32_t(i);
        }
        if (indices.size() % 3 != 0)
            throw InputError(file_, where, "index count " + std::to_string(indices.size()) + " is not a multiple of 3");

        // A mirroring transform turns the winding around; swapping two corners keeps it.
        const bool mirrored = glm::determinant(glm::dmat3(transform)) < 0.0;
        const uint32_t material = materialIndex(primitive.material);
        for (size_t i = 0; i < indices.size(); i += 3) {
            for (size_t k = i; k < i + 3; ++k)
                if (indices[k] >= positions.size())
                    throw InputError(file_, where,
                                     "index " + std::to_string(indices[k]) + " out of range (" +
                                         std::to_string(positions.size()) + " vertices)");
            glm::uvec3 triangle(firstVertex + indices[i], firstVertex + indices[i + 1], firstVertex + indices[i + 2]);
            if (mirrored) std::swap(triangle.y, triangle.z);
            mesh_.triangles.push_back(triangle);
            mesh_.faceMaterial.push_back(material);
        }
    }

    uint32_t materialIndex(int gltfMaterial) {
        if (gltfMaterial >= 0 && size_t(gltfMaterial) < model_.materials.size()) return uint32_t(gltfMaterial);
        if (!defaultMaterial_) {
            defaultMaterial_ = uint32_t(mesh_.materials.size());
            mesh_.materials.push_back({"default"});
        }
        return *defaultMaterial_;
    }

    const tinygltf::Model& model_;
    const std::string& file_;
    AccessorReader accessors_;
    TriangleMesh mesh_;
    std::vector<bool> onPath_, visited_;
    std::optional<uint32_t> defaultMaterial_;
    bool allHaveNormals_ = true;
    bool allHaveUvs_ = true;
};

/// The default scene's root nodes; the first scene's when none is marked default; every node
/// that is nobody's child when the file has no scenes.
std::vector<int> rootNodes(const tinygltf::Model& model) {
    if (!model.scenes.empty()) {
        const size_t scene = model.defaultScene >= 0 && size_t(model.defaultScene) < model.scenes.size()
                                 ? size_t(model.defaultScene)
                                 : 0;
        return model.scenes[scene].nodes;
    }
    std::vector<bool> isChild(model.nodes.size(), false);
    for (const tinygltf::Node& node : model.nodes)
        for (int child : node.children)
            if (child >= 0 && size_t(child) < isChild.size()) isChild[size_t(child)] = true;
    std::vector<int> roots;
    for (size_t i = 0; i < model.nodes.size(); ++i)
        if (!isChild[i]) roots.push_back(int(i));
    return roots;
}

} // namespace

namespace {

/// `load` fills the model through one of tinygltf's entry points; the rest is the same for all.
template <class Load>
TriangleMesh meshFromGltf(const std::string& file, size_t inputBytes, Load load) {
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(keepImageEncoded, nullptr);
    tinygltf::Model model;
    std::string error, warning;
    bool loaded = false;
    try {
        loaded = load(loader, model, error, warning);
    } catch (const std::exception& e) {  // tinygltf indexes some arrays with at() on broken files
        throw InputError(file, "", std::string("cannot parse glTF: ") + e.what());
    }
    if (!warning.empty()) std::cerr << "warning: " << file << ": " << trimmed(warning) << "\n";
    if (!loaded || !error.empty()) throw InputError(file, "", trimmed(error.empty() ? "cannot parse glTF" : error));

    SceneFlattener flattener(model, file, inputBytes);
    for (int node : rootNodes(model)) flattener.addNode(node, glm::dmat4(1.0));
    TriangleMesh mesh = flattener.take();
    validateMesh(mesh, file);
    return mesh;
}

} // namespace

TriangleMesh loadGltf(const std::filesystem::path& path) {
    const std::string file = path.string();
    if (!std::ifstream(path)) throw InputError(file, "", "cannot open file");
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    const bool binary = extension == ".glb";
    std::error_code ec;
    const size_t bytes = std::filesystem::file_size(path, ec);
    return meshFromGltf(file, ec ? 0 : bytes, [&](tinygltf::TinyGLTF& loader, tinygltf::Model& model, std::string& error,
                                  std::string& warning) {
        return binary ? loader.LoadBinaryFromFile(&model, &error, &warning, file)
                      : loader.LoadASCIIFromFile(&model, &error, &warning, file);
    });
}

TriangleMesh parseGltf(const std::string& data, const std::string& file) {
    if (data.size() > std::numeric_limits<unsigned int>::max()) throw InputError(file, "", "larger than 4 GiB");
    const std::string folder = std::filesystem::path(file).parent_path().string();
    const bool binary = data.starts_with("glTF");
    return meshFromGltf(file, data.size(), [&](tinygltf::TinyGLTF& loader, tinygltf::Model& model, std::string& error,
                                  std::string& warning) {
        const auto length = static_cast<unsigned int>(data.size());
        return binary ? loader.LoadBinaryFromMemory(&model, &error, &warning,
                                                    reinterpret_cast<const unsigned char*>(data.data()), length, folder)
                      : loader.LoadASCIIFromString(&model, &error, &warning, data.data(), length, folder);
    });
}

} // namespace wideray
