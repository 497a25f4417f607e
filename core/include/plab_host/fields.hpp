// Per-body fields that plug-ins register by name (SPH density and pressure,
// a coupling's porosity...): one column of doubles per field, indexed by
// body, each with its default (a new body's value) and its unit.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace plab {

class BodyFields {
public:
    int index(const std::string& name) const;  // -1 when no plug-in registered it
    // Registers a field once (later calls return its index); its unit is
    // the first non-empty unit declared for it. The column holds `rows`
    // copies of the default.
    int add(const std::string& name, double default_value, const char* unit, std::size_t rows);
    std::size_t size() const { return columns_.size(); }
    std::vector<double>& column(int f) { return columns_[std::size_t(f)]; }
    const std::vector<double>& column(int f) const { return columns_[std::size_t(f)]; }
    const std::vector<std::string>& names() const { return names_; }
    const std::string& unit(int f) const { return units_[std::size_t(f)]; }
    double default_value(int f) const { return defaults_[std::size_t(f)]; }
    // Every column at `rows` bodies; bodies added since take the default.
    void resize(std::size_t rows);
    // Every column down to the rows whose new index (Bodies::remove) is not -1.
    void keep_rows(const std::vector<std::int32_t>& new_index);
    // All columns, for the last-good snapshot and checkpoints.
    const std::vector<std::vector<double>>& columns() const { return columns_; }
    void set_columns(const std::vector<std::vector<double>>& columns) { columns_ = columns; }  // (as many fields)

private:
    std::vector<std::string> names_;
    std::vector<std::vector<double>> columns_;
    std::vector<double> defaults_;
    std::vector<std::string> units_;
};

} // namespace plab
