// Stanford PLY loading: ascii, binary_little_endian and binary_big_endian, version 1.0.
// Reads vertex positions (and nx/ny/nz, u/v or s/t when present) and polygon faces; every other
// property and element is skipped.
#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cstring>
#include <fstream>
#include <optional>
#include <string_view>

#include "core/error.h"
#include "io/mesh_io.h"

namespace wideray {
namespace {

enum class ScalarType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

std::optional<ScalarType> scalarTypeNamed(std::string_view name) {
    if (name == "char" || name == "int8") return ScalarType::Int8;
    if (name == "uchar" || name == "uint8") return ScalarType::UInt8;
    if (name == "short" || name == "int16") return ScalarType::Int16;
    if (name == "ushort" || name == "uint16") return ScalarType::UInt16;
    if (name == "int" || name == "int32") return ScalarType::Int32;
    if (name == "uint" || name == "uint32") return ScalarType::UInt32;
    if (name == "float" || name == "float32") return ScalarType::Float32;
    if (name == "double" || name == "float64") return ScalarType::Float64;
    return std::nullopt;
}

bool isInteger(ScalarType type) { return type != ScalarType::Float32 && type != ScalarType::Float64; }

size_t sizeOf(ScalarType type) {
    switch (type) {
    case ScalarType::Int8:
    case ScalarType::UInt8: return 1;
    case ScalarType::Int16:
    case ScalarType::UInt16: return 2;
    case ScalarType::Int32:
    case ScalarType::UInt32:
    case ScalarType::Float32: return 4;
    case ScalarType::Float64: return 8;
    }
    return 0;
}

struct PlyProperty {
    std::string name;
    ScalarType type;                         ///< of the value, or of each entry of a list
    std::optional<ScalarType> listCountType; ///< set for a list property
};

struct PlyElement {
    std::string name;
    size_t count = 0;
    std::vector<PlyProperty> properties;
};

enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct PlyHeader {
    PlyFormat format = PlyFormat::Ascii;
    std::vector<PlyElement> elements;
    size_t bodyOffset = 0; ///< first byte after the end_header line
    size_t bodyLine = 0;   ///< line number of that byte
};

std::vector<std::string_view> splitWords(std::string_view line) {
    std::vector<std::string_view> words;
    size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
        const size_t start = i;
        while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
        if (i > start) words.push_back(line.substr(start, i - start));
    }
    return words;
}

std::optional<size_t> parseCount(std::string_view word) {
    size_t value = 0;
    const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (ec != std::errc() || end != word.data() + word.size()) return std::nullopt;
    return value;
}

PlyHeader parseHeader(std::string_view data, const std::string& file) {
    PlyHeader header;
    size_t pos = 0, lineNumber = 0;
    bool sawFormat = false;
    while (true) {
        if (pos >= data.size()) throw InputError(file, "line " + std::to_string(lineNumber), "header has no end_header");
        size_t end = data.find('\n', pos);
        if (end == std::string_view::npos) end = data.size();
        std::string_view line = data.substr(pos, end - pos);
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        pos = end + 1;
        ++lineNumber;
        const std::string location = "line " + std::to_string(lineNumber);
        const auto fail = [&](const std::string& message) { throw InputError(file, location, message); };

        if (lineNumber == 1) {
            if (line != "ply") fail("not a PLY file (it does not start with 'ply')");
            continue;
        }
        const std::vector<std::string_view> words = splitWords(line);
        if (words.empty() || words[0] == "comment" || words[0] == "obj_info") continue;
        if (words[0] == "end_header") break;

        if (words[0] == "format") {
            if (words.size() != 3) fail("expected 'format <type> 1.0'");
            if (words[1] == "ascii") header.format = PlyFormat::Ascii;
            else if (words[1] == "binary_little_endian") header.format = PlyFormat::BinaryLittleEndian;
            else if (words[1] == "binary_big_endian") header.format = PlyFormat::BinaryBigEndian;
            else fail("unknown format '" + std::string(words[1]) + "'");
            if (words[2] != "1.0" && words[2] != "1") fail("unsupported version " + std::string(words[2]));
            sawFormat = true;
        } else if (words[0] == "element") {
            const std::optional<size_t> count = words.size() == 3 ? parseCount(words[2]) : std::nullopt;
            if (!count) fail("expected 'element <name> <count>'");
            header.elements.push_back({std::string(words[1]), *count, {}});
        } else if (words[0] == "property") {
            if (header.elements.empty()) fail("property before any element");
            const auto typeNamed = [&](std::string_view name) {
                const std::optional<ScalarType> type = scalarTypeNamed(name);
                if (!type) fail("unsupported property type '" + std::string(name) + "'");
                return *type;
            };
            PlyProperty property;
            if (words.size() == 5 && words[1] == "list") {
                property = {std::string(words[4]), typeNamed(words[3]), typeNamed(words[2])};
                if (!isInteger(*property.listCountType)) fail("a list's count type must be an integer type");
            } else if (words.size() == 3) {
                property = {std::string(words[2]), typeNamed(words[1]), std::nullopt};
            } else {
                fail("expected 'property <type> <name>' or 'property list <count type> <type> <name>'");
            }
            header.elements.back().properties.push_back(property);
        } else {
            fail("unknown header keyword '" + std::string(words[0]) + "'");
        }
    }
    if (!sawFormat) throw InputError(file, "line 2", "header has no format line");
    header.bodyOffset = std::min(pos, data.size());
    header.bodyLine = lineNumber + 1;
    return header;
}

/// Reads binary values; past the end it returns zeros and remembers that the data was truncated.
class BinaryReader {
public:
    BinaryReader(std::string_view data, size_t offset, bool bigEndian)
        : data_(data), pos_(offset), bigEndian_(bigEndian) {}

    double read(ScalarType type) {
        switch (type) {
        case ScalarType::Int8: return readAs<int8_t>();
        case ScalarType::UInt8: return readAs<uint8_t>();
        case ScalarType::Int16: return readAs<int16_t>();
        case ScalarType::UInt16: return readAs<uint16_t>();
        case ScalarType::Int32: return readAs<int32_t>();
        case ScalarType::UInt32: return readAs<uint32_t>();
        case ScalarType::Float32: return readAs<float>();
        case ScalarType::Float64: return readAs<double>();
        }
        return 0.0;
    }

    /// Integer types only (checked when the header is interpreted).
    int64_t readInteger(ScalarType type) { return int64_t(read(type)); }

    void skip(ScalarType type) {
        if (data_.size() - pos_ < sizeOf(type)) truncated_ = true;
        pos_ = std::min(pos_ + sizeOf(type), data_.size());
    }

    bool truncated() const { return truncated_; }
    std::string location() const { return "byte " + std::to_string(pos_); }

private:
    template <class T>
    T readAs() {
        if (data_.size() - pos_ < sizeof(T)) {
            truncated_ = true;
            pos_ = data_.size();
            return T{};
        }
        std::array<char, sizeof(T)> bytes;
        std::memcpy(bytes.data(), data_.data() + pos_, sizeof(T));
        if (bigEndian_) std::reverse(bytes.begin(), bytes.end());
        pos_ += sizeof(T);
        T value;
        std::memcpy(&value, bytes.data(), sizeof(T));
        return value;
    }

    std::string_view data_;
    size_t pos_;
    bool bigEndian_;
    bool truncated_ = false;
};

/// Reads whitespace-separated ascii values, counting lines for error messages; past the end it
/// returns zeros and remembers that the data was truncated.
class AsciiReader {
public:
    AsciiReader(std::string_view data, size_t offset, size_t line, const std::string& file)
        : data_(data), pos_(offset), line_(line), file_(file) {}

    double read(ScalarType type) {
        if (isInteger(type)) return double(readInteger(type));
        const std::string_view word = nextWord();
        if (word.empty()) return 0.0;
        double value = 0.0;
        parse(word, value);
        return value;
    }

    int64_t readInteger(ScalarType) {
        const std::string_view word = nextWord();
        if (word.empty()) return 0;
        int64_t value = 0;
        parse(word, value);
        return value;
    }

    void skip(ScalarType) { nextWord(); }

    bool truncated() const { return truncated_; }
    std::string location() const { return "line " + std::to_string(line_); }

private:
    std::string_view nextWord() {
        while (pos_ < data_.size() && std::isspace(static_cast<unsigned char>(data_[pos_]))) {
            if (data_[pos_] == '\n') ++line_;
            ++pos_;
        }
        const size_t start = pos_;
        while (pos_ < data_.size() && !std::isspace(static_cast<unsigned char>(data_[pos_]))) ++pos_;
        if (pos_ == start) truncated_ = true;
        return data_.substr(start, pos_ - start);
    }

    template <class T>
    void parse(std::string_view word, T& value) {
        if (word.size() > 1 && word.front() == '+') word.remove_prefix(1);
        const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
        if (ec != std::errc() || end != word.data() + word.size())
            throw InputError(file_, location(), "'" + std::string(word) + "' is not a number");
    }

    std::string_view data_;
    size_t pos_;
    size_t line_;
    const std::string& file_;
    bool truncated_ = false;
};

template <class Reader>
[[noreturn]] void throwTruncated(const std::string& file, const Reader& in, const PlyElement& element, size_t index) {
    throw InputError(file, in.location(),
                     "file ends in " + element.name + " " + std::to_string(index) + " of " +
                         std::to_string(element.count));
}

template <class Reader>
void skipList(Reader& in, const PlyProperty& property) {
    const int64_t count = in.readInteger(*property.listCountType);
    for (int64_t i = 0; i < count && !in.truncated(); ++i) in.skip(property.type);
}

template <class Reader>
void skipProperty(Reader& in, const PlyProperty& property) {
    if (property.listCountType) skipList(in, property);
    else in.skip(property.type);
}

template <class Reader>
void skipElement(Reader& in, const PlyElement& element, const std::string& file) {
    // Items without properties hold no data: a count of 2^63 of them must not be counted through.
    if (element.properties.empty()) return;
    for (size_t i = 0; i < element.count; ++i) {
        for (const PlyProperty& property : element.properties) skipProperty(in, property);
        if (in.truncated()) throwTruncated(file, in, element, i);
    }
}

/// Where a vertex property goes: an index into VertexValues, or none.
enum VertexSlot { X, Y, Z, NX, NY, NZ, U, V, R, G, B, SlotCount, Ignored = SlotCount };
using VertexValues = std::array<float, SlotCount + 1>; // the last entry absorbs ignored scalars

glm::vec3 srgbToLinear(const glm::vec3& c) {
    glm::vec3 out;
    for (int i = 0; i < 3; ++i) out[i] = c[i] <= 0.04045f ? c[i] / 12.92f : std::pow((c[i] + 0.055f) / 1.055f, 2.4f);
    return out;
}

VertexSlot slotNamed(const std::string& name) {
    static const std::array<std::pair<std::string_view, VertexSlot>, 19> slots{{
        {"x", X}, {"y", Y}, {"z", Z}, {"nx", NX}, {"ny", NY}, {"nz", NZ}, {"u", U}, {"v", V}, {"s", U}, {"t", V},
        {"red", R}, {"green", G}, {"blue", B}, {"r", R}, {"g", G}, {"b", B},
        {"diffuse_red", R}, {"diffuse_green", G}, {"diffuse_blue", B}}};
    for (const auto& [slotName, slot] : slots)
        if (name == slotName) return slot;
    return Ignored;
}

template <class Reader>
void readVertices(Reader& in, const PlyElement& element, size_t reserve, TriangleMesh& mesh,
                  const std::string& file) {
    std::vector<VertexSlot> slots;
    std::array<bool, SlotCount + 1> present{};
    for (const PlyProperty& property : element.properties) {
        const VertexSlot slot = property.listCountType ? Ignored : slotNamed(property.name);
        slots.push_back(slot);
        present[slot] = true;
    }
    if (!present[X] || !present[Y] || !present[Z])
        throw InputError(file, "header", "element vertex lacks property x, y or z");
    const bool withNormals = present[NX] && present[NY] && present[NZ];
    const bool withUvs = present[U] && present[V];
    const bool withColors = present[R] && present[G] && present[B];
    // Colors stored as integers are 8-bit sRGB (0-255); as floats, linear values.
    bool integerColors = false;
    for (size_t p = 0; p < slots.size(); ++p)
        if (slots[p] == R) integerColors = isInteger(element.properties[p].type);

    mesh.positions.reserve(reserve);
    if (withNormals) mesh.normals.reserve(reserve);
    if (withUvs) mesh.uvs.reserve(reserve);
    if (withColors) mesh.colors.reserve(reserve);
    VertexValues values{};
    for (size_t i = 0; i < element.count; ++i) {
        for (size_t p = 0; p < slots.size(); ++p) {
            if (element.properties[p].listCountType) skipList(in, element.properties[p]);
            else values[slots[p]] = float(in.read(element.properties[p].type));
        }
        if (in.truncated()) throwTruncated(file, in, element, i);
        mesh.positions.emplace_back(values[X], values[Y], values[Z]);
        if (withNormals) mesh.normals.emplace_back(values[NX], values[NY], values[NZ]);
        if (withUvs) mesh.uvs.emplace_back(values[U], values[V]);
        if (withColors) {
            const glm::vec3 c(values[R], values[G], values[B]);
            // Linear floats: clamped to [0, 1], NaN to 0.
            auto unit = [](float x) { return x > 0.0f ? std::min(x, 1.0f) : 0.0f; };
            mesh.colors.push_back(integerColors ? srgbToLinear(glm::clamp(c / 255.0f, 0.0f, 1.0f))
                                                : glm::vec3(unit(c.x), unit(c.y), unit(c.z)));
        }
    }
}

const PlyProperty& vertexIndexList(const PlyElement& faces, const std::string& file) {
    for (const PlyProperty& property : faces.properties) {
        if (property.name != "vertex_indices" && property.name != "vertex_index") continue;
        if (!property.listCountType || !isInteger(*property.listCountType) || !isInteger(property.type))
            throw InputError(file, "header", "face property " + property.name + " must be a list of integers");
        return property;
    }
    throw InputError(file, "header", "element face has no vertex_indices list");
}

template <class Reader>
void readFaces(Reader& in, const PlyElement& element, size_t vertexCount, size_t reserve, TriangleMesh& mesh,
               const std::string& file) {
    const PlyProperty& indexList = vertexIndexList(element, file);
    mesh.triangles.reserve(reserve);
    std::vector<uint32_t> polygon;
    for (size_t i = 0; i < element.count; ++i) {
        for (const PlyProperty& property : element.properties) {
            if (&property != &indexList) {
                skipProperty(in, property);
                continue;
            }
            const int64_t cornerCount = in.readInteger(*property.listCountType);
            if (in.truncated()) throwTruncated(file, in, element, i);
            if (cornerCount < 3)
                throw InputError(file, in.location(),
                                 "face " + std::to_string(i) + " has " + std::to_string(cornerCount) +
                                     " vertices (at least 3 needed)");
            polygon.clear();
            for (int64_t c = 0; c < cornerCount; ++c) {
                const int64_t index = in.readInteger(property.type);
                if (in.truncated()) throwTruncated(file, in, element, i);
                if (index < 0 || size_t(index) >= vertexCount)
                    throw InputError(file, in.location(),
                                     "face " + std::to_string(i) + " refers to vertex " + std::to_string(index) +
                                         " but there are " + std::to_string(vertexCount));
                polygon.push_back(uint32_t(index));
            }
            for (size_t c = 2; c < polygon.size(); ++c) mesh.triangles.emplace_back(polygon[0], polygon[c - 1], polygon[c]);
        }
        if (in.truncated()) throwTruncated(file, in, element, i);
    }
}

template <class Reader>
TriangleMesh readBody(Reader& in, const PlyHeader& header, size_t bodyBytes, const std::string& file) {
    size_t vertexCount = 0;
    for (const PlyElement& element : header.elements)
        if (element.name == "vertex") vertexCount = element.count;
    if (vertexCount > UINT32_MAX) throw InputError(file, "header", "too many vertices");

    TriangleMesh mesh;
    bool sawVertices = false, sawFaces = false;
    for (const PlyElement& element : header.elements) {
        // A header may promise more items than the file holds, so reserve no more than its size allows.
        const size_t reserve = std::min(element.count, bodyBytes);
        if (element.name == "vertex" && !sawVertices) {
            readVertices(in, element, reserve, mesh, file);
            sawVertices = true;
        } else if (element.name == "face" && !sawFaces) {
            readFaces(in, element, vertexCount, reserve, mesh, file);
            sawFaces = true;
        } else {
            skipElement(in, element, file);
        }
    }
    return mesh;
}

std::string readWholeFile(const std::filesystem::path& path) {
    std::ifstream stream(path, std::ios::binary);
    if (!stream) throw InputError(path.string(), "", "cannot open file");
    stream.seekg(0, std::ios::end);
    std::string data(size_t(stream.tellg()), '\0');
    stream.seekg(0);
    stream.read(data.data(), std::streamsize(data.size()));
    if (!stream) throw InputError(path.string(), "", "cannot read file");
    return data;
}

} // namespace

TriangleMesh loadPly(const std::filesystem::path& path) { return parsePly(readWholeFile(path), path.string()); }

TriangleMesh parsePly(const std::string& data, const std::string& file) {
    const PlyHeader header = parseHeader(data, file);
    const size_t bodyBytes = data.size() - header.bodyOffset;

    TriangleMesh mesh;
    if (header.format == PlyFormat::Ascii) {
        AsciiReader in(data, header.bodyOffset, header.bodyLine, file);
        mesh = readBody(in, header, bodyBytes, file);
    } else {
        BinaryReader in(data, header.bodyOffset, header.format == PlyFormat::BinaryBigEndian);
        mesh = readBody(in, header, bodyBytes, file);
    }
    validateMesh(mesh, file);
    return mesh;
}

} // namespace wideray
