#pragma once
// Errors that reach the user: each names where the problem is (file, line or JSON key) and what it is.
#include <stdexcept>
#include <string>

namespace wideray {

/// An input error: a bad scene file, mesh or command-line value. `what()` is the full message,
/// "FILE:LOCATION: MESSAGE", ready to print.
class InputError : public std::runtime_error {
public:
    InputError(const std::string& file, const std::string& location, const std::string& message)
        : std::runtime_error(format(file, location, message)), file_(file), location_(location), message_(message) {}

    const std::string& file() const { return file_; }
    const std::string& location() const { return location_; }
    const std::string& message() const { return message_; }

private:
    static std::string format(const std::string& file, const std::string& location, const std::string& message) {
        std::string s = file;
        if (!location.empty()) s += ":" + location;
        return s + ": " + message;
    }
    std::string file_, location_, message_;
};

} // namespace wideray
