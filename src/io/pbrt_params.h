#pragma once
// A pbrt directive's parameter list ("type name" followed by a value or a bracketed list), looked up
// by name with the types pbrt allows for each use. What a directive never looks up is reported
// (PbrtParams::unused) so that nothing is dropped silently.
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace wideray {

/// Bad input found where the file name is not known: the reader adds it ("FILE:line N: message").
struct PbrtLineError {
    int line;
    std::string message;
};

struct PbrtParam {
    std::string type, name;
    std::vector<double> numbers;
    std::vector<std::string> strings;  ///< string, texture and bool values ("true", "false")
    int line = 0;
    mutable bool used = false;
};

class PbrtParams {
public:
    std::vector<PbrtParam> list;

    /// The parameter called `name` (marked used), or null.
    const PbrtParam* find(const std::string& name) const {
        for (const PbrtParam& p : list)
            if (p.name == name) return p.used = true, &p;
        return nullptr;
    }
    bool has(const std::string& name) const {
        for (const PbrtParam& p : list)
            if (p.name == name) return true;
        return false;
    }
    /// The one number of `name`, `fallback` when absent; throws PbrtLineError when it is not one number.
    float number(const std::string& name, float fallback) const {
        const PbrtParam* p = find(name);
        if (!p) return fallback;
        if (p->numbers.size() != 1) throw PbrtLineError{p->line, "\"" + p->type + " " + name + "\" must be one number"};
        return float(p->numbers[0]);
    }
    /// The names nobody looked up.
    std::vector<const PbrtParam*> unused() const {
        std::vector<const PbrtParam*> out;
        for (const PbrtParam& p : list)
            if (!p.used) out.push_back(&p);
        return out;
    }
};

} // namespace wideray
