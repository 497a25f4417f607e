// Reading a JSON scene with errors that name the JSON path, the value and
// the valid range. A Node is a JSON value together with its path; every
// object read through it rejects keys it does not know.
#pragma once

#include <plab_host/errors.hpp>
#include <plab_host/types.hpp>

#include <nlohmann/json.hpp>

#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

namespace plab {

using json = nlohmann::json;

std::string show(const json& value);  // short text of a value for messages

class Node {
public:
    Node(const json& j, std::string path) : j_(&j), path_(std::move(path)) {}

    const json& value() const { return *j_; }
    const std::string& path() const { return path_; }
    bool has(const std::string& key) const { return j_->is_object() && j_->contains(key); }

    // Fails with the list of allowed keys when the object holds another one.
    void allow_keys(std::initializer_list<const char*> allowed) const;
    void allow_keys(const std::vector<const char*>& allowed) const;  // a set built at run time
    Node at(const std::string& key) const;           // required member
    Node at(std::size_t index) const;                // array element
    std::size_t size() const { return j_->size(); }

    void expect_object() const;
    void expect_array() const;
    // [[noreturn]] error at this node
    [[noreturn]] void fail(const std::string& message) const;

    double number(double lo = -kInf, double hi = kInf, bool lo_open = false, bool hi_open = false) const;
    double positive() const { return number(0.0, kInf, true, true); }
    long integer(long lo, long hi) const;
    std::string string() const;
    std::string choice(std::initializer_list<const char*> options) const;
    bool boolean() const;
    // A vector of `dim` numbers (2D scenes write [x, y]; z = 0).
    Vec vec(int dim) const;

    // Optional members with a default.
    double number_or(const std::string& key, double fallback, double lo = -kInf, double hi = kInf,
                     bool lo_open = false, bool hi_open = false) const;
    Vec vec_or(const std::string& key, int dim, const Vec& fallback) const;
    std::string string_or(const std::string& key, const std::string& fallback) const;

private:
    const json* j_;
    std::string path_;
};

} // namespace plab
