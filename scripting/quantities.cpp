#include "quantities.hpp"

#include "measurements/measurement.hpp"


namespace plab {

namespace {

const std::vector<QuantityInfo>& builtin() {
    static const std::vector<QuantityInfo> q = {
        {"time", "s", "simulated time"},
        {"step", "-", "steps taken"},
        {"dt", "s", "the last timestep"},
        {"contacts", "-", "active contacts of every model"},
        {"unbalanced_ratio", "-", "mean unbalanced force over mean contact force (PFC's ratio)"},
        {"bonds.intact", "-", "intact bonds"},
        {"bonds.broken", "-", "bonds broken so far"},
        {"energy.<kinetic|strain|body|boundary|slip|dashpot|local_damping|bond_break|balance>", "J",
         "energy terms of the run's balance (2D: per metre of thickness)"},
        {"ball.position.<x|y|z|magnitude>", "m", "one ball's (with \"id\")"},
        {"ball.velocity.<x|y|z|magnitude>", "m/s", "one ball's (with \"id\")"},
        {"ball.angular_velocity.<x|y|z|magnitude>", "rad/s", "one ball's (with \"id\")"},
        {"ball.force.<x|y|z|magnitude>", "N", "one ball's resultant force (with \"id\")"},
        {"ball.applied_force.<x|y|z|magnitude>", "N", "one ball's applied force (with \"id\")"},
        {"clump.<position|velocity|angular_velocity|angular_momentum|force|moment>.<x|y|z|magnitude>", "as ball.*",
         "one clump's (with \"id\"): angular momentum kg m^2/s, moment N m about its centre of mass"},
        {"clump.principal_angular_velocity.<x|y|z|magnitude>", "rad/s",
         "one clump's spin about its principal axes, smallest moment first (with \"id\")"},
        {"clump.kinetic_energy", "J", "one clump's, translation and rotation (with \"id\")"},
        {"group.<max|min|mean>.<position|velocity|angular_velocity|force|applied_force>.<x|y|z|magnitude>",
         "as ball.*", "over a group's balls (with \"group\")"},
        {"wall.force.<x|y|z>", "N", "force of the balls on a wall (with \"wall\")"},
        {"wall.moment.<x|y|z>", "N m", "their moment about the wall's centre (with \"wall\")"},
        {"inlet.<count|mass>", "-, kg", "balls an inlet has added so far (with \"inlet\": its name)"},
        {"outlet.<count|mass>", "-, kg", "balls an outlet has removed so far (with \"outlet\": its name)"},
        {"probe.<field>", "the field's", "kernel-weighted mean of a per-body field at a point (with point, radius, group)"},
    };
    return q;
}

// A measurement's doc ends in its unit, "[m]", unless its unit depends on a
// parameter (then it names several).
std::string measurement_unit(const std::string& doc) {
    const auto open = doc.rfind('['), close = doc.rfind(']');
    if (open == std::string::npos || close != doc.size() - 1 || doc.find('[') != open) return "";
    return doc.substr(open + 1, close - open - 1);
}

std::string vector_unit(const std::string& what) {
    if (what == "position") return "m";
    if (what == "velocity") return "m/s";
    if (what == "angular_velocity" || what == "principal_angular_velocity") return "rad/s";
    if (what == "force" || what == "applied_force") return "N";
    if (what == "angular_momentum") return "kg m^2/s";
    if (what == "moment") return "N m";
    return "";
}

} // namespace

std::vector<std::string> quantity_parts(const std::string& quantity) {
    std::vector<std::string> parts(1);
    for (char ch : quantity) {
        if (ch == '.') parts.emplace_back();
        else parts.back() += ch;
    }
    return parts;
}

std::vector<QuantityInfo> history_quantities() {
    std::vector<QuantityInfo> all = builtin();
    for (const auto& [name, info] : measurements()) {
        const std::string unit = measurement_unit(info.doc);
        all.push_back({"measure." + name, unit.empty() ? "see doc" : unit, info.doc});
    }
    return all;
}

std::string quantity_unit(const std::string& quantity, const World& w) {
    const auto parts = quantity_parts(quantity);
    for (const QuantityInfo& q : builtin())
        if (q.name == quantity) return q.unit;
    if (parts[0] == "energy") return "J";
    if (parts[0] == "ball" && parts.size() == 3) return vector_unit(parts[1]);
    if (parts[0] == "clump" && parts.size() == 3) return vector_unit(parts[1]);
    if (parts[0] == "group" && parts.size() == 4) return vector_unit(parts[2]);
    if (parts[0] == "wall" && parts.size() == 3) return parts[1] == "force" ? "N" : "N m";
    if ((parts[0] == "inlet" || parts[0] == "outlet") && parts.size() == 2) return parts[1] == "mass" ? "kg" : "-";
    if (parts[0] == "probe" && parts.size() == 2) {
        const int f = w.fields.index(parts[1]);
        return f < 0 || w.fields.unit(f) == "1" ? "" : w.fields.unit(f);
    }
    if (parts[0] == "measure" && parts.size() == 2) {
        const auto it = measurements().find(parts[1]);
        return it == measurements().end() ? "" : measurement_unit(it->second.doc);
    }
    return "";
}

} // namespace plab
