#pragma once
// The lookup every registry of this layer shares: the row of a table by its name, or an InputError
// naming the option and every valid name.
#include <span>
#include <string>
#include <string_view>

#include "core/error.h"

namespace wideray {

template <class Row>
const Row& findByName(std::span<const Row> rows, std::string_view name, const char* option, const char* what) {
    std::string names;
    for (const Row& row : rows) {
        if (name == row.name) return row;
        names += std::string(names.empty() ? "" : ", ") + row.name;
    }
    throw InputError(option, "", std::string("no ") + what + " is named '" + std::string(name) + "' (expected " + names + ")");
}

} // namespace wideray
