#include "json_reader.hpp"

#include <cmath>
#include <sstream>

namespace plab {

std::string show(const json& value) {
    std::string s = value.dump();
    return s.size() > 60 ? s.substr(0, 57) + "..." : s;
}

namespace {
std::string range_words(double lo, double hi, bool lo_open, bool hi_open) {
    std::ostringstream s;
    s << (lo_open ? "(" : "[") << lo << ", " << hi << (hi_open ? ")" : "]");
    return s.str();
}
} // namespace

void Node::fail(const std::string& message) const { throw InputError(path_, message); }

void Node::expect_object() const {
    if (!j_->is_object()) fail("expected an object, got " + show(*j_));
}

void Node::expect_array() const {
    if (!j_->is_array()) fail("expected an array, got " + show(*j_));
}

void Node::allow_keys(std::initializer_list<const char*> allowed) const {
    allow_keys(std::vector<const char*>(allowed));
}

void Node::allow_keys(const std::vector<const char*>& allowed) const {
    expect_object();
    for (auto it = j_->begin(); it != j_->end(); ++it) {
        bool ok = false;
        for (const char* a : allowed) ok = ok || it.key() == a;
        if (ok) continue;
        std::string list;
        for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
        throw InputError(path_ + "." + it.key(), "unknown key '" + it.key() + "'; allowed here: " + list);
    }
}

Node Node::at(const std::string& key) const {
    expect_object();
    auto it = j_->find(key);
    if (it == j_->end()) throw InputError(path_ + "." + key, "missing required key '" + key + "'");
    return Node(*it, path_ + "." + key);
}

Node Node::at(std::size_t index) const {
    expect_array();
    if (index >= j_->size())
        fail("index " + std::to_string(index) + " out of range (size " + std::to_string(j_->size()) + ")");
    return Node((*j_)[index], path_ + "[" + std::to_string(index) + "]");
}

double Node::number(double lo, double hi, bool lo_open, bool hi_open) const {
    if (!j_->is_number()) fail("expected a number, got " + show(*j_));
    const double v = j_->get<double>();
    const bool ok = std::isfinite(v) && (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
    if (!ok) {
        std::ostringstream s;
        s << "value " << v << " is outside the valid range " << range_words(lo, hi, lo_open, hi_open);
        fail(s.str());
    }
    return v;
}

long Node::integer(long lo, long hi) const {
    if (!j_->is_number_integer() && !(j_->is_number() && std::floor(j_->get<double>()) == j_->get<double>()))
        fail("expected a whole number, got " + show(*j_));
    const double v = j_->get<double>();
    if (v < double(lo) || v > double(hi))
        fail("value " + show(*j_) + " is outside the valid range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return long(v);
}

std::string Node::string() const {
    if (!j_->is_string()) fail("expected a string, got " + show(*j_));
    return j_->get<std::string>();
}

std::string Node::choice(std::initializer_list<const char*> options) const {
    const std::string s = string();
    std::string list;
    for (const char* o : options) {
        if (s == o) return s;
        list += (list.empty() ? "" : ", ") + std::string(o);
    }
    fail("value \"" + s + "\" is not one of: " + list);
}

bool Node::boolean() const {
    if (!j_->is_boolean()) fail("expected true or false, got " + show(*j_));
    return j_->get<bool>();
}

Vec Node::vec(int dim) const {
    if (!j_->is_array() || int(j_->size()) != dim)
        fail("expected " + std::to_string(dim) + " numbers (a " + std::to_string(dim) + "D vector), got " + show(*j_));
    Vec v = Vec::Zero();
    for (int c = 0; c < dim; ++c) v[c] = at(c).number();
    return v;
}

double Node::number_or(const std::string& key, double fallback, double lo, double hi, bool lo_open,
                       bool hi_open) const {
    return has(key) ? at(key).number(lo, hi, lo_open, hi_open) : fallback;
}

Vec Node::vec_or(const std::string& key, int dim, const Vec& fallback) const {
    return has(key) ? at(key).vec(dim) : fallback;
}

std::string Node::string_or(const std::string& key, const std::string& fallback) const {
    return has(key) ? at(key).string() : fallback;
}

} // namespace plab
