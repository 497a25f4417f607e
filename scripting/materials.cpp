// Scene materials: constants stated once, copied into the same-named
// properties of the models and passes that use them (materials.hpp).
#include "materials.hpp"

#include "generators.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace plab {

namespace {
// Two statements of one constant agree when they are the same number up to
// the rounding of a printed decimal.
bool same_value(double a, double b) { return std::fabs(a - b) <= 1e-9 * std::max(std::fabs(a), std::fabs(b)); }
} // namespace

void Materials::load(const Node& n, const World& w) {
    n.expect_object();
    group_material_.assign(w.group_names().size(), -1);
    for (auto it = n.value().begin(); it != n.value().end(); ++it) {
        const Node m(*it, n.path() + "." + it.key());
        m.expect_object();
        Material mat{it.key(), m.path(), &*it, {}, {}};
        const Node groups = m.at("groups");
        groups.expect_array();
        for (std::size_t i = 0; i < groups.size(); ++i) {
            const std::string name = groups.at(i).string();
            const int g = w.find_group(name);
            if (g < 0) {
                std::string known;
                for (const auto& s : w.group_names()) known += (known.empty() ? "" : ", ") + s;
                groups.at(i).fail("unknown group \"" + name + "\"; groups in this scene: " + known);
            }
            if (group_material_[g] >= 0)
                groups.at(i).fail("group \"" + name + "\" already has the material \"" +
                                  materials_[group_material_[g]].name + "\"; a group has one material");
            group_material_[g] = int(materials_.size());
            mat.groups.push_back(g);
        }
        for (auto v = it->begin(); v != it->end(); ++v)
            if (v.key() != "groups" && !v->is_number())
                Node(*v, m.path() + "." + v.key()).fail("expected a number (a property value), got " + show(*v));
        materials_.push_back(std::move(mat));
    }
}

int Materials::of_group(int group) const {
    return group >= 0 && group < int(group_material_.size()) ? group_material_[group] : -1;
}

int Materials::find(const Node& n) const {
    const std::string name = n.string();
    std::string known;
    for (std::size_t i = 0; i < materials_.size(); ++i) {
        if (materials_[i].name == name) return int(i);
        known += (known.empty() ? "" : ", ") + materials_[i].name;
    }
    n.fail("unknown material \"" + name + "\"; materials in this scene: " + (known.empty() ? "none" : known));
}

void Materials::fill(const Node& owner, const std::vector<int>& materials, const plab_property_desc* props,
                     uint32_t count, const Vec& gravity, std::vector<double>& values) {
    const json* given = owner.has("properties") ? &owner.value()["properties"] : nullptr;
    for (uint32_t p = 0; p < count; ++p) {
        const std::string key = props[p].key;
        const bool explicit_value = given && given->contains(key);
        std::string source;  // path of the value filled so far
        for (int mi : materials) {
            Material& m = materials_[mi];
            if (!m.values->contains(key)) continue;
            if (std::find(m.used.begin(), m.used.end(), key) == m.used.end()) m.used.push_back(key);
            const Node v((*m.values)[key], m.path + "." + key);
            const double x = read_property(v, props[p]);
            std::ostringstream s;
            if (explicit_value && !same_value(x, (*given)[key].get<double>())) {
                s << "value " << (*given)[key].get<double>() << " contradicts " << x << " of " << v.path()
                  << "; state it once, in the material";
                throw InputError(owner.path() + ".properties." + key, s.str());
            }
            if (!source.empty() && !same_value(x, values[p])) {
                s << "the groups of this rule have different values of " << key << ": " << values[p] << " at " << source
                  << " and " << x << " at " << v.path();
                owner.fail(s.str());
            }
            values[p] = x;
            source = v.path();
        }
        const int axis = key == "gravity_x" ? 0 : key == "gravity_y" ? 1 : key == "gravity_z" ? 2 : -1;
        if (axis < 0 || !source.empty()) continue;
        if (explicit_value && !same_value(values[p], gravity[axis])) {
            std::ostringstream s;
            s << "value " << values[p] << " contradicts the component " << gravity[axis]
              << " of scene.gravity; leave it out to take the scene's gravity";
            throw InputError(owner.path() + ".properties." + key, s.str());
        }
        values[p] = gravity[axis];
    }
}

void Materials::check_all_used() const {
    for (const Material& m : materials_)
        for (auto v = m.values->begin(); v != m.values->end(); ++v) {
            if (v.key() == "groups" || std::find(m.used.begin(), m.used.end(), v.key()) != m.used.end()) continue;
            throw InputError(m.path + "." + v.key(),
                             "no contact model or pass using the material \"" + m.name + "\" has a property '" +
                                 v.key() + "' (plab plugins --describe NAME lists them)");
        }
}

} // namespace plab
