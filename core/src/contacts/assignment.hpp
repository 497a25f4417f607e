// PFC's contact model assignment table (CMAT): the groups of the scene, by
// name, and which model instance each pair of groups takes (-1: none, no
// contact and no cost).
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace plab {

class AssignmentTable {
public:
    int group_index(const std::string& name);       // creates on first use
    int find_group(const std::string& name) const;  // -1 when unknown
    const std::vector<std::string>& group_names() const { return groups_; }
    const std::string& group_name(int group) const { return groups_[std::size_t(group)]; }
    int group_count() const { return int(groups_.size()); }
    void assign(int group_a, int group_b, int instance);
    int assigned(int group_a, int group_b) const { return table_[std::size_t(group_a * group_count() + group_b)]; }
    // groups × groups, row-major, for checkpoints
    const std::vector<int>& table() const { return table_; }
    void set_table(std::vector<int> table) { table_ = std::move(table); }

private:
    std::vector<std::string> groups_;
    std::vector<int> table_;
};

} // namespace plab
