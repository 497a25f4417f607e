// Errors the user sees. Every input error names the JSON path, the value and
// the valid range; every run error names the quantity, the body/contact, the
// step and a likely cause.
#pragma once

#include <cstdio>
#include <stdexcept>
#include <string>

namespace plab {

// A number in a message: three significant digits ("2.1e-05", "0.9").
inline std::string short_number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", v);
    return buf;
}

// Bad input (scene, command line, plug-in library): the message is complete.
class InputError : public std::runtime_error {
public:
    InputError(std::string path, const std::string& message)
        : std::runtime_error(path.empty() ? message : path + ": " + message), path_(std::move(path)) {}
    const std::string& path() const { return path_; }

private:
    std::string path_;
};

// A plug-in library refused by the host (wrong ABI, missing symbol, ...).
class PluginError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// A run stopped by the stability detector; the world keeps its last good state.
// `quantity` names what went out of bounds ("overlap", "energy gain", ...),
// empty for other run failures.
class RunError : public std::runtime_error {
public:
    explicit RunError(const std::string& message, std::string quantity = "")
        : std::runtime_error(message), quantity_(std::move(quantity)) {}
    const std::string& quantity() const { return quantity_; }

private:
    std::string quantity_;
};

} // namespace plab
