#include <plab_host/fields.hpp>

namespace plab {

int BodyFields::index(const std::string& name) const {
    for (std::size_t i = 0; i < names_.size(); ++i)
        if (names_[i] == name) return int(i);
    return -1;
}

int BodyFields::add(const std::string& name, double default_value, const char* unit, std::size_t rows) {
    const int found = index(name);
    if (found >= 0) {
        if (units_[std::size_t(found)].empty() && unit) units_[std::size_t(found)] = unit;
        return found;
    }
    names_.push_back(name);
    defaults_.push_back(default_value);
    units_.push_back(unit ? unit : "");
    columns_.emplace_back(rows, default_value);
    return int(columns_.size()) - 1;
}

void BodyFields::resize(std::size_t rows) {
    for (std::size_t f = 0; f < columns_.size(); ++f) columns_[f].resize(rows, defaults_[f]);
}

void BodyFields::keep_rows(const std::vector<std::int32_t>& new_index) {
    for (auto& c : columns_) {
        std::size_t kept = 0;
        for (std::size_t i = 0; i < new_index.size() && i < c.size(); ++i)
            if (new_index[i] >= 0) c[std::size_t(new_index[i])] = c[i], ++kept;
        c.resize(kept);
    }
}

} // namespace plab
