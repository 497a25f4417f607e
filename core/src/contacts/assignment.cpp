#include "contacts/assignment.hpp"

namespace plab {

int AssignmentTable::group_index(const std::string& name) {
    const int found = find_group(name);
    if (found >= 0) return found;
    groups_.push_back(name);
    const int n = group_count();
    std::vector<int> grown(std::size_t(n) * std::size_t(n), -1);
    for (int a = 0; a < n - 1; ++a)
        for (int b = 0; b < n - 1; ++b) grown[std::size_t(a * n + b)] = table_[std::size_t(a * (n - 1) + b)];
    table_ = std::move(grown);
    return n - 1;
}

int AssignmentTable::find_group(const std::string& name) const {
    for (std::size_t i = 0; i < groups_.size(); ++i)
        if (groups_[i] == name) return int(i);
    return -1;
}

void AssignmentTable::assign(int a, int b, int instance) {
    const int n = group_count();
    table_[std::size_t(a * n + b)] = instance;
    table_[std::size_t(b * n + a)] = instance;
}

} // namespace plab
