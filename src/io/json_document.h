#pragma once
// JSON documents as scene files use them: parsed with errors that name the line and column, or the
// key path ("objects[2].transform.scale") of a duplicate key or a number out of range, and read
// through typed accessors that name the key path of any value that is not what they expect.
#include <cmath>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "core/error.h"

namespace wideray {

// Numbers are parsed with strtof and printed as the shortest text that reads back as the same
// float, so writeScene -> parseScene reproduces every float exactly.
using Json = nlohmann::basic_json<nlohmann::ordered_map, std::vector, std::string, bool, std::int64_t,
                                  std::uint64_t, float>;

/// A JSON value with the key path that leads to it ("objects[2].transform.scale").
struct Node {
    const Json& value;
    std::string path;

    bool has(const std::string& key) const { return value.contains(key); }
    Node operator[](const std::string& key) const { return {value.at(key), path.empty() ? key : path + "." + key}; }
    Node operator[](size_t index) const { return {value.at(index), path + "[" + std::to_string(index) + "]"}; }
};

/// "an array of 3 elements", "a string", ...: what a value is, for messages.
std::string describe(const Json& value);
/// " (did you mean \"x\"?)" for the candidate nearest to `word`, or "" when none is near.
std::string suggestion(const std::string& word, const std::vector<std::string>& candidates);
/// The words quoted and joined with commas.
std::string joined(const std::vector<std::string>& words);

/// Parses a document; throws InputError naming `file` and the line and column or key path.
Json parseJson(const std::string& text, const std::string& file);

/// Typed values of a document, each checked: a wrong value throws InputError naming the file and
/// the key path.
class JsonReader {
public:
    explicit JsonReader(std::string file) : file_(std::move(file)) {}

protected:
    [[noreturn]] void fail(const std::string& path, const std::string& message) const {
        throw InputError(file_, path, message);
    }

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

    std::string file_;
};

} // namespace wideray
