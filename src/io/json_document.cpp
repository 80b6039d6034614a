#include "io/json_document.h"

#include <algorithm>
#include <memory>
#include <set>

namespace wideray {
namespace {

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

} // namespace

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

/// Follows nlohmann's parse events to know the key path of the value being read, so that duplicate
/// keys (which nlohmann would silently resolve to the last) and out-of-range numbers can name it.
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

} // namespace wideray
