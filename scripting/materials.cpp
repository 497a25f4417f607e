// Scene materials: constants stated once, given to the properties that the
// models and passes using them take from their package's material
// (materials.hpp).
#include "materials.hpp"

#include "generators.hpp"

#include <plab_host/plugins.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace plab {

namespace {
// Two statements of one constant agree when they are the same number up to
// the rounding of a printed decimal.
bool same_value(double a, double b) { return std::fabs(a - b) <= 1e-9 * std::max(std::fabs(a), std::fabs(b)); }

// c0 >= kMachFactor x the expected maximum speed: Mach 0.1, a density error
// of about (v/c0)^2 = 1 % (Monaghan 1994, "Simulating free surface flows").
constexpr double kMachFactor = 10.0;

std::string number_text(double x) {
    std::ostringstream s;
    s << x;
    return s.str();
}

struct ExpectedSpeed {
    double value;
    std::string from;  // the rule and its numbers, for the run summary
};

// scene.materials.NAME.expected_max_speed: a number (m/s), or an object with
// "speed" (a moving wall, a piston, an inflow, a settling body) and/or
// "depth" D (the hydrostatic condition g D / c0^2 <= 1 %, which the long-wave
// speed sqrt(g D) in place of the speed gives; Morris, Fox & Zhu 1997, the
// body-force term of their c0 estimate), or "dam_break_height" H alone.
ExpectedSpeed read_expected_speed(const Node& n, const Vec& gravity) {
    if (n.value().is_number()) {
        const double v = n.positive();
        return {v, "given: " + number_text(v) + " m/s"};
    }
    if (!n.value().is_object() || n.size() == 0)
        n.fail("expected a speed in m/s or an object with \"dam_break_height\" (m), \"speed\" (m/s) and/or "
               "\"depth\" (m), got " + show(n.value()));
    n.allow_keys({"speed", "depth", "dam_break_height"});
    if (n.has("dam_break_height") && n.size() != 1)
        n.fail("\"dam_break_height\" stands alone (it sets the depth too), got " + show(n.value()));
    const double g = gravity.norm();
    const auto needs_gravity = [&](const Node& k) {
        if (!(g > 0)) k.fail("needs gravity: scene.gravity is zero");
    };
    if (n.has("dam_break_height")) {
        const Node h = n.at("dam_break_height");
        const double height = h.positive();
        needs_gravity(h);
        // Ritter's (1892) dry-bed dam break: the surge tip runs at 2 sqrt(g H),
        // twice the free-fall speed sqrt(2 g H) of the column's top.
        const double v = 2.0 * std::sqrt(g * height);
        return {v, "dam_break_height H = " + number_text(height) + " m: 2 sqrt(g H) with g = " + number_text(g) +
                       " m/s2 = " + number_text(v) + " m/s"};
    }
    double v = 0;
    std::string from;
    if (n.has("speed")) {
        v = n.at("speed").positive();
        from = "speed " + number_text(v) + " m/s";
    }
    if (n.has("depth")) {
        const Node d = n.at("depth");
        const double depth = d.positive();
        needs_gravity(d);
        const double wave = std::sqrt(g * depth);
        from += (from.empty() ? "" : ", ") + std::string("depth D = ") + number_text(depth) + " m: sqrt(g D) = " +
                number_text(wave) + " m/s";
        v = std::max(v, wave);
    }
    return {v, from + (n.size() > 1 ? "; the larger, " + number_text(v) + " m/s" : "")};
}
} // namespace

// speed_of_sound "auto" (kMachFactor x expected_max_speed) or a number no
// lower than that; both keys end as numbers in mat.values.
void Materials::resolve_speed_of_sound(const Node& m, const Vec& gravity, Material& mat) {
    const bool has_expected = m.has("expected_max_speed");
    ExpectedSpeed expected{0, ""};
    if (has_expected) {
        expected = read_expected_speed(m.at("expected_max_speed"), gravity);
        mat.values["expected_max_speed"] = expected.value;
        mat.used.push_back("expected_max_speed");  // read here; sph_eos takes it for its advice when declared
    }
    if (!m.has("speed_of_sound")) {
        if (has_expected) m.at("expected_max_speed").fail("sets the speed of sound only with \"speed_of_sound\": \"auto\" (or a number >= " + number_text(kMachFactor * expected.value) + " m/s) in this material");
        return;
    }
    const Node c = m.at("speed_of_sound");
    const double floor_c0 = kMachFactor * expected.value;
    json entry = {{"material", mat.name}};
    double c0;
    if (c.value().is_string()) {
        if (c.value().get<std::string>() != "auto")
            c.fail("expected a number (m/s) or \"auto\" (10 x expected_max_speed), got " + show(c.value()));
        if (!has_expected)
            c.fail("\"auto\" sets c0 = 10 x the material's expected_max_speed, which is not given: add "
                   "\"expected_max_speed\": {\"dam_break_height\": H}, {\"speed\": v} or a speed in m/s");
        c0 = floor_c0;
        entry["rule"] = "auto: 10 x expected_max_speed";
    } else {
        c0 = c.positive();
        if (has_expected && c0 < floor_c0 * (1 - 1e-9))
            c.fail("value " + number_text(c0) + " is outside the valid range [" + number_text(floor_c0) +
                   ", inf): 10 x expected_max_speed " + number_text(expected.value) + " m/s (" + expected.from +
                   "); use \"auto\" or a larger value");
        entry["rule"] = has_expected ? "given, checked >= 10 x expected_max_speed" : "given (no expected_max_speed to check it against)";
    }
    mat.values["speed_of_sound"] = c0;
    entry["speed_of_sound"] = c0;
    if (has_expected) {
        entry["expected_max_speed"] = expected.value;
        entry["from"] = expected.from;
        entry["mach_factor"] = c0 / expected.value;
    }
    sound_report_.push_back(entry);
}

void Materials::load(const Node& n, const World& w) {
    n.expect_object();
    group_material_.assign(w.group_names().size(), -1);
    for (auto it = n.value().begin(); it != n.value().end(); ++it) {
        const Node m(*it, n.path() + "." + it.key());
        m.expect_object();
        Material mat{it.key(), m.path(), *it, {}, {}};
        mat.values.erase("groups");
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
        // a property value: a number, true/false, or a name (a choice or a
        // group); the kind of the property that takes it checks it
        for (auto v = it->begin(); v != it->end(); ++v)
            if (v.key() != "groups" && v.key() != "speed_of_sound" && v.key() != "expected_max_speed" &&
                !v->is_number() && !v->is_boolean() && !v->is_string() && !v->is_null())
                Node(*v, m.path() + "." + v.key())
                    .fail("expected a property value (a number, true or false, or a name), got " + show(*v));
        resolve_speed_of_sound(m, w.gravity, mat);
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

namespace {
// The value a contact between two materials takes from their values a and b
// by the property's mixing rule (abi.h PLAB_MIX_*); NaN for none.
double mix(uint32_t rule, double a, double b) {
    switch (rule) {
    case PLAB_MIX_HARMONIC: return a + b == 0.0 ? 0.0 : 2.0 * a * b / (a + b);
    case PLAB_MIX_ARITHMETIC: return 0.5 * (a + b);
    case PLAB_MIX_GEOMETRIC: return a * b < 0.0 ? std::nan("") : std::sqrt(a * b);
    case PLAB_MIX_MAX: return std::max(a, b);
    case PLAB_MIX_MIN: return std::min(a, b);
    default: return std::nan("");
    }
}
const char* mix_formula(uint32_t rule) {
    switch (rule) {
    case PLAB_MIX_HARMONIC: return "harmonic mean 2ab/(a+b)";
    case PLAB_MIX_ARITHMETIC: return "arithmetic mean (a+b)/2";
    case PLAB_MIX_GEOMETRIC: return "geometric mean sqrt(ab)";
    case PLAB_MIX_MAX: return "max(a, b)";
    case PLAB_MIX_MIN: return "min(a, b)";
    default: return "none";
    }
}
} // namespace

void Materials::fill(const Node& owner, const std::vector<std::vector<int>>& sides, const plab_property_desc* props,
                     uint32_t count, const plab_material_desc* material, const Vec& gravity,
                     const std::vector<std::string>& groups, std::vector<double>& values) {
    const json* given = owner.has("properties") ? &owner.value()["properties"] : nullptr;
    for (uint32_t p = 0; p < count; ++p) {
        const std::string key = props[p].key;
        const bool explicit_value = given && given->contains(key);
        // a property the package material declares (the host has checked
        // that the two declare it alike) takes the scene materials' values;
        // any other takes none
        const bool shared = material_property(material, props[p].key) != nullptr;
        for (std::size_t s = 0; shared && s < sides.size() && s < 2; ++s)
            for (int mi : sides[s]) {
                std::vector<std::string>& takeable = materials_[mi].takeable;
                if (std::find(takeable.begin(), takeable.end(), key) == takeable.end()) takeable.push_back(key);
            }
        // per side of the rule: the value its materials give, and where
        struct Stated {
            bool set = false;
            double x = 0;
            std::string path;
        } side[2];
        for (std::size_t s = 0; shared && s < sides.size() && s < 2; ++s)
            for (int mi : sides[s]) {
                Material& m = materials_[mi];
                if (!m.values.contains(key)) continue;
                if (std::find(m.used.begin(), m.used.end(), key) == m.used.end()) m.used.push_back(key);
                const Node v(m.values[key], m.path + "." + key);
                const double x = read_property(v, props[p], groups);
                std::ostringstream msg;
                if (explicit_value && !same_value(x, values[p])) {
                    msg << "value " << show((*given)[key]) << " contradicts " << property_value_text(props[p], x, groups)
                        << " of " << v.path() << "; state it once, in the material";
                    throw InputError(owner.path() + ".properties." + key, msg.str());
                }
                if (side[s].set && !same_value(x, side[s].x)) {
                    msg << "the groups on one side of this rule have different values of " << key << ": "
                        << property_value_text(props[p], side[s].x, groups) << " at " << side[s].path << " and "
                        << property_value_text(props[p], x, groups) << " at " << v.path()
                        << "; one value serves the whole rule: give each pair of groups its own rule";
                    owner.fail(msg.str());
                }
                side[s] = {true, x, v.path()};
            }
        if (side[0].set && side[1].set && !same_value(side[0].x, side[1].x)) {
            // a contact between two materials: the property's mixing rule
            const uint32_t rule = props[p].mixing;
            const std::string a = property_value_text(props[p], side[0].x, groups) + " at " + side[0].path;
            const std::string b = property_value_text(props[p], side[1].x, groups) + " at " + side[1].path;
            std::ostringstream msg;
            if (rule == PLAB_MIX_NONE) {
                msg << "the groups of this rule have different values of " << key << ": " << a << " and " << b << "; "
                    << key << " has no mixing rule (mixing none: plab plugins --describe shows each property's), so "
                    << "the two materials must agree, or " << key << " must leave them and be given in the rule's "
                    << "properties";
                owner.fail(msg.str());
            }
            const double x = mix(rule, side[0].x, side[1].x);
            if (!in_range(props[p], x)) {
                msg << "the " << mix_formula(rule) << " of " << key << " from " << a << " and " << b << " is "
                    << number_text(x) << ", outside the valid range " << range_text(props[p]);
                owner.fail(msg.str());
            }
            values[p] = x;
            continue;
        }
        if (side[1].set) values[p] = side[1].x;
        else if (side[0].set) values[p] = side[0].x;
        const bool from_material = side[0].set || side[1].set;
        const int axis = key == "gravity_x" ? 0 : key == "gravity_y" ? 1 : key == "gravity_z" ? 2 : -1;
        if (axis < 0 || from_material) continue;
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
        for (auto v = m.values.begin(); v != m.values.end(); ++v) {
            if (v.key() == "groups" || std::find(m.used.begin(), m.used.end(), v.key()) != m.used.end()) continue;
            std::string takeable;
            for (const std::string& k : m.takeable) takeable += (takeable.empty() ? "" : ", ") + k;
            throw InputError(m.path + "." + v.key(),
                             "no contact model or pass using the material \"" + m.name + "\" takes a property '" +
                                 v.key() + "' from it; they take " +
                                 (takeable.empty() ? std::string("none (none of them names a package material)")
                                                   : takeable) +
                                 ": the properties their package's material declares (plab plugins --describe NAME "
                                 "shows a model's or pass's material)");
        }
}

} // namespace plab
