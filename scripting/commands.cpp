// The command sequence (cycle, solve, set, output) and recorded histories.
#include <plab_host/errors.hpp>

#include "clump_generator.hpp"
#include "generators.hpp"
#include "measurements/measurement.hpp"
#include "metrics.hpp"
#include "quantities.hpp"
#include "simulation.hpp"
#include "variables.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <unistd.h>

namespace plab {

namespace {

int component(const Node& n, const std::string& c) {
    if (c == "x") return 0;
    if (c == "y") return 1;
    if (c == "z") return 2;
    if (c == "magnitude") return 3;
    n.fail("unknown component \"" + c + "\"; use x, y, z or magnitude");
}

double pick(const Vec& v, int c) { return c == 3 ? v.norm() : v[c]; }

// "; groups in this scene: a, b" / "; walls in this scene: ..." for messages
// about a misspelt name.
std::string listed(const char* what, const std::vector<std::string>& names) {
    std::string s;
    for (const auto& x : names) s += (s.empty() ? "" : ", ") + x;
    return std::string("; ") + what + " in this scene: " + (s.empty() ? "none" : s);
}

std::vector<std::string> wall_names(const World& w) {
    std::vector<std::string> names;
    for (const Wall& wall : w.walls.walls) names.push_back(wall.name);
    return names;
}


// The named vector of every body; null for loads never applied (all zero).
const Vec* body_vectors(const Bodies& b, const std::string& which) {
    if (which == "position") return b.position.data();
    if (which == "velocity") return b.velocity.data();
    if (which == "angular_velocity") return b.angular_velocity.data();
    if (which == "applied_force") return b.has_applied_loads() ? b.applied_force.data() : nullptr;
    return b.force.data();
}

Vec body_vector(const Vec* v, std::size_t i) { return v ? v[i] : Vec(Vec::Zero()); }

int body_index(const World& w, BodyId id) {
    for (std::size_t i = 0; i < w.bodies.size(); ++i)
        if (w.bodies.id[i] == id) return int(i);
    return -1;
}

// probe.FIELD: a per-body field (e.g. sph_pressure) at `point`, the Shepard
// average over the group's balls within `radius` with Wendland C2 weights
// (1 - q)^4 (1 + 4q), q = d / radius; NaN while no ball is in reach. A wall
// pressure sensor is a probe on the wall of the sensor's size.
std::function<double(const World&)> field_probe(const Node& n, const World& w, const std::string& field) {
    const int f = w.fields.index(field);
    if (f < 0) n.at("quantity").fail("no per-body field \"" + field + "\"" + listed("fields", w.fields.names()));
    const Vec point = n.at("point").vec(w.dim);
    const double radius = n.at("radius").positive();
    const std::string g = n.at("group").string();
    const int group = w.find_group(g);
    if (group < 0) n.at("group").fail("unknown group \"" + g + "\"" + listed("groups", w.group_names()));
    return [f, point, radius, group](const World& x) {
        const std::vector<double>& values = x.fields.column(f);
        double sum = 0, weight = 0;
        for (std::size_t i = 0; i < x.bodies.size(); ++i) {
            if (x.bodies.group[i] != group) continue;
            const double q = (x.bodies.position[i] - point).norm() / radius;
            if (q >= 1) continue;
            const double wq = std::pow(1 - q, 4) * (1 + 4 * q);
            sum += wq * values[i];
            weight += wq;
        }
        return weight > 0 ? sum / weight : std::nan("");
    };
}

int clump_index(const World& w, BodyId id) {
    const auto it = std::find(w.clumps.id.begin(), w.clumps.id.end(), id);
    return it == w.clumps.id.end() ? -1 : int(it - w.clumps.id.begin());
}

// clump.<vector>.<component> and clump.kinetic_energy of the clump "id"
std::function<double(const World&)> clump_quantity(const Node& n, const World& w, const std::vector<std::string>& parts) {
    const Node idn = n.at("id");
    const BodyId id = BodyId(idn.integer(0, long(w.bodies.next_id) - 1));
    const auto index = [id](const World& x) { return clump_index(x, id); };
    if (index(w) < 0) {
        std::vector<std::string> ids;
        for (BodyId c : w.clumps.id) ids.push_back(std::to_string(c));
        idn.fail("no clump has id " + std::to_string(id) + listed("clump ids", ids));
    }
    if (parts.size() == 2)
        return [index](const World& x) {
            const int c = index(x);
            return c < 0 ? std::nan("") : x.clumps.kinetic_energy(std::size_t(c));
        };
    const std::string which = parts[1];
    const Node qn = n.at("quantity");
    const int comp = component(qn, parts[2]);
    using Column = std::vector<Vec> Clumps::*;
    const std::pair<const char*, Column> columns[] = {
        {"position", &Clumps::position}, {"velocity", &Clumps::velocity},
        {"angular_velocity", &Clumps::angular_velocity}, {"angular_momentum", &Clumps::angular_momentum},
        {"force", &Clumps::force}, {"moment", &Clumps::moment}};
    for (const auto& named : columns)  // (a structured binding cannot be captured before C++20)
        if (which == named.first)
            return [index, column = named.second, comp](const World& x) {
                const int c = index(x);
                return c < 0 ? std::nan("") : pick((x.clumps.*column)[std::size_t(c)], comp);
            };
    if (which == "principal_angular_velocity")  // about the principal axes, smallest moment first
        return [index, comp](const World& x) {
            const int c = index(x);
            if (c < 0) return std::nan("");
            return pick(x.clumps.orientation[std::size_t(c)].conjugate() * x.clumps.angular_velocity[std::size_t(c)], comp);
        };
    qn.fail("unknown clump quantity \"" + which +
            "\"; use position, velocity, angular_velocity, principal_angular_velocity, angular_momentum, force or moment, "
            "or kinetic_energy");
}

// One history column from its description.
std::function<double(const World&)> quantity(const Node& n, const World& w) {
    const std::string q = n.at("quantity").string();
    const auto parts = quantity_parts(q);
    const Node qn = n.at("quantity");
    const char* known =
        "time, step, dt, contacts, unbalanced_ratio, bonds.intact, bonds.broken, "
        "energy.<kinetic|strain|body|boundary|slip|dashpot|local_damping|bond_break|balance>, ball.<position|velocity|angular_velocity|force|applied_force>.<x|y|z|magnitude> (with id), "
        "clump.<position|velocity|angular_velocity|principal_angular_velocity|angular_momentum|force|moment>.<x|y|z|magnitude> or clump.kinetic_energy (with id), "
        "group.<max|min|mean>.<position|velocity|...>.<x|y|z|magnitude> (with group), wall.<force|moment>.<x|y|z> "
        "(with wall), probe.<field> (with point, radius, group), measure.<name> (with \"with\": {...}), or an \"expression\" of earlier columns";
    if (q == "time") return [](const World& x) { return x.time; };
    if (q == "step") return [](const World& x) { return double(x.step_count); };
    if (q == "dt") return [](const World& x) { return x.last_dt; };
    if (q == "contacts") return [](const World& x) { return double(active_contacts(x)); };
    if (q == "unbalanced_ratio") return [](const World& x) { return unbalanced_force_ratio(x); };
    if (q == "bonds.intact") return [](const World& x) { return double(intact_bonds(x)); };
    if (q == "bonds.broken") return [](const World& x) { return double(x.bond_breaks.size()); };
    if (q == "energy.bond_break") return [](const World& x) { return x.energies.bond_break; };
    if (parts[0] == "energy" && parts.size() == 2) {
        const std::string e = parts[1];
        if (e == "kinetic") return [](const World& x) { return x.energies.kinetic; };
        if (e == "strain") return [](const World& x) { return x.energies.strain; };
        if (e == "body") return [](const World& x) { return x.energies.body; };
        if (e == "boundary") return [](const World& x) { return x.energies.boundary; };
        if (e == "slip") return [](const World& x) { return x.energies.slip; };
        if (e == "dashpot") return [](const World& x) { return x.energies.dashpot; };
        if (e == "local_damping") return [](const World& x) { return x.energies.local_damping; };
        if (e == "balance") return [](const World& x) { return x.energies.balance(); };
    }
    const bool vec_name = parts.size() >= 2 && (parts[parts.size() - 2] == "position" || parts[parts.size() - 2] == "velocity" ||
                                                parts[parts.size() - 2] == "angular_velocity" || parts[parts.size() - 2] == "force" ||
                                                parts[parts.size() - 2] == "applied_force");
    if (parts[0] == "ball" && parts.size() == 3 && vec_name) {
        const BodyId id = BodyId(n.at("id").integer(0, long(w.bodies.next_id) - 1));
        const std::string which = parts[1];
        const int c = component(qn, parts[2]);
        return [id, which, c](const World& x) {
            const int i = body_index(x, id);
            return i < 0 ? std::nan("") : pick(body_vector(body_vectors(x.bodies, which), std::size_t(i)), c);
        };
    }
    if (parts[0] == "clump" && (parts.size() == 3 || q == "clump.kinetic_energy")) return clump_quantity(n, w, parts);
    if (parts[0] == "group" && parts.size() == 4 && vec_name) {
        const std::string g = n.at("group").string();
        const int group = w.find_group(g);
        if (group < 0) n.at("group").fail("unknown group \"" + g + "\"" + listed("groups", w.group_names()));
        const std::string op = parts[1], which = parts[2];
        if (op != "max" && op != "min" && op != "mean") qn.fail("unknown reduction \"" + op + "\"; use max, min or mean");
        const int c = component(qn, parts[3]);
        return [group, op, which, c](const World& x) {
            double acc = op == "max" ? -kInf : (op == "min" ? kInf : 0.0);
            std::size_t count = 0;
            const Vec* v = body_vectors(x.bodies, which);
            for (std::size_t i = 0; i < x.bodies.size(); ++i) {
                if (x.bodies.group[i] != group) continue;
                const double s = pick(body_vector(v, i), c);
                acc = op == "max" ? std::max(acc, s) : op == "min" ? std::min(acc, s) : acc + s;
                ++count;
            }
            return op == "mean" ? (count ? acc / double(count) : std::nan("")) : acc;
        };
    }
    if (parts[0] == "wall" && parts.size() == 3 && (parts[1] == "force" || parts[1] == "moment")) {
        const std::string name = n.at("wall").string();
        const int wall = w.walls.find(name);
        if (wall < 0) n.at("wall").fail("unknown wall \"" + name + "\"" + listed("walls", wall_names(w)));
        const bool force = parts[1] == "force";
        const int c = component(qn, parts[2]);
        return [wall, force, c](const World& x) {
            const Wall& wl = x.walls.walls[wall];
            return pick(force ? wl.force : wl.moment, c);
        };
    }
    if (parts[0] == "probe" && parts.size() == 2) return field_probe(n, w, parts[1]);
    if (parts[0] == "measure" && parts.size() == 2) {
        const auto it = measurements().find(parts[1]);
        if (it == measurements().end()) {
            std::string names;
            for (const auto& [name, info] : measurements()) names += (names.empty() ? "" : ", ") + name;
            qn.fail("unknown measurement \"" + parts[1] + "\"; measurements: " + names);
        }
        static const json empty = json::object();
        return it->second.make(n.has("with") ? n.at("with") : Node(empty, n.path() + ".with"), w);
    }
    qn.fail("unknown quantity \"" + q + "\"; known: " + known);
}

} // namespace

void Simulation::load_histories(const Node& n) {
    n.allow_keys({"every", "record", "at_end"});
    history_every_ = n.has("every") ? n.at("every").integer(1, 1L << 40) : 100;
    history_at_end_ = n.has("at_end") && n.at("at_end").boolean();
    const Node rec = n.at("record");
    rec.expect_array();
    for (std::size_t i = 0; i < rec.size(); ++i) {
        const Node h = rec.at(i);
        h.allow_keys({"name", "quantity", "id", "group", "wall", "inlet", "outlet", "point", "radius", "expression", "with"});
        HistoryColumn col;
        if (h.has("expression")) {
            if (h.has("quantity")) h.fail("a column has a \"quantity\" or an \"expression\", not both");
            col.name = h.at("name").string();
            std::vector<std::string> earlier;
            for (const auto& c : history_cols_) earlier.push_back(c.name);
            auto expr = std::make_shared<Expression>(h.at("expression").string(), earlier, scene_variables(scene_),
                                                     h.at("expression").path());
            col.derive = [expr](const std::vector<double>& row) { return (*expr)(row); };
        } else {
            col.name = h.string_or("name", h.at("quantity").string());
            col.sample = flows_.quantity(h);
            if (!col.sample) col.sample = quantity(h, *world_);
            col.unit = quantity_unit(h.at("quantity").string(), *world_);
        }
        history_cols_.push_back(std::move(col));
    }
}

void Simulation::load_output(const Node& n) {
    n.allow_keys({"dir", "vtk_interval", "vtk", "png"});
    if (n.has("dir")) out_dir_ = n.at("dir").string();
    if (n.has("vtk") && n.has("vtk_interval"))
        n.at("vtk_interval").fail("give the interval once: vtk_interval is short for vtk.interval");
    if (n.has("vtk")) vtk_ = read_vtk_options(n.at("vtk"));
    if (n.has("vtk_interval")) {
        vtk_.interval = n.number_or("vtk_interval", 0.0, 0.0, kInf, false, true);
        vtk_interval_path_ = "scene.output.vtk_interval";
    }
    if (n.has("png")) load_png_output(n.at("png"));
}

namespace {

// The clumps whose pebbles a selection holds, once each, in index order;
// the pebbles leave the selection (their clump moves them).
std::vector<int> take_clumps(const World& w, std::vector<int>& sel) {
    std::vector<int> clumps;
    if (w.bodies.clump.empty()) return clumps;
    std::vector<int> balls;
    for (int i : sel) {
        const std::int32_t c = w.bodies.clump[std::size_t(i)];
        if (c < 0) balls.push_back(i);
        else clumps.push_back(c);
    }
    std::sort(clumps.begin(), clumps.end());
    clumps.erase(std::unique(clumps.begin(), clumps.end()), clumps.end());
    sel = std::move(balls);
    return clumps;
}

using ClumpAction = std::function<void(World&, const std::vector<int>&)>;

// What a `set` key does to the selected clumps (null: the key is not one
// for clumps, an error when the selection holds one).
ClumpAction clump_action(const Node& n, const char* key, int dim) {
    const std::string k = key;
    if (k == "velocity") {
        const Vec v = n.at(key).vec(dim);
        return [v](World& w, const std::vector<int>& cs) { for (int c : cs) w.clumps.velocity[std::size_t(c)] = v; };
    }
    if (k == "angular_velocity") {
        const Vec om = read_angular_velocity(n, dim);
        return [om](World& w, const std::vector<int>& cs) { for (int c : cs) w.clumps.set_spin(std::size_t(c), om); };
    }
    if (k == "fix" || k == "free") {
        const std::uint8_t f = read_clump_fixity(n.at(key), dim);
        const bool fix = k == "fix";
        return [f, fix](World& w, const std::vector<int>& cs) {
            for (int c : cs) {
                std::uint8_t& x = w.clumps.fixity[std::size_t(c)];
                x = fix ? std::uint8_t(x | f) : std::uint8_t(x & ~f);
            }
        };
    }
    if (k == "local_damping") {
        const double a = n.at(key).number(0.0, 1.0, false, true);
        return [a](World& w, const std::vector<int>& cs) { for (int c : cs) w.clumps.local_damping[std::size_t(c)] = a; };
    }
    return nullptr;
}

} // namespace

// `velocity_profile`: each component of the velocity an expression of the
// ball's position x, y (, z) and the scene's variables, evaluated at each
// selected ball when the command runs (a mode shape: Islam eq. 25).
std::function<void(World&, const std::vector<int>&)> Simulation::velocity_profile(const Node& n, int dim) const {
    n.expect_array();
    if (n.size() != std::size_t(dim))
        n.fail("needs " + std::to_string(dim) + " expressions, one per velocity component, got " + std::to_string(n.size()));
    std::vector<std::shared_ptr<Expression>> components;
    const std::vector<std::string> names = dim == 3 ? std::vector<std::string>{"x", "y", "z"} : std::vector<std::string>{"x", "y"};
    for (std::size_t c = 0; c < n.size(); ++c)
        components.push_back(std::make_shared<Expression>(n.at(c).string(), names, scene_variables(scene_), n.at(c).path()));
    const std::string path = n.path();
    return [components, dim, path](World& w, const std::vector<int>& sel) {
        std::vector<double> at(std::size_t(dim), 0.0);
        for (int i : sel) {
            for (int c = 0; c < dim; ++c) at[std::size_t(c)] = w.bodies.position[i][c];
            Vec v = Vec::Zero();
            for (int c = 0; c < dim; ++c) v[c] = (*components[std::size_t(c)])(at);
            if (!v.allFinite())
                throw InputError(path, "is not finite at ball id " + std::to_string(w.bodies.id[i]) + " (x = " +
                                           std::to_string(at[0]) + ", y = " + std::to_string(at[1]) + ")");
            w.bodies.velocity[i] = v;
        }
    };
}

std::function<void(World&)> Simulation::load_set(const Node& n) {
    n.allow_keys({"group", "id", "region", "wall", "velocity", "angular_velocity", "random_velocity",
                  "velocity_profile", "fix", "free", "applied_force", "local_damping", "viscous_damping", "gravity"});
    const int dim = world_->dim;
    std::vector<std::function<void(World&)>> actions;
    if (n.has("gravity")) {
        const Vec g = n.at("gravity").vec(dim);
        actions.push_back([g](World& w) { w.gravity = g; });
    }
    if (n.has("wall")) {
        const std::string name = n.at("wall").string();
        const int wall = world_->walls.find(name);
        if (wall < 0) n.at("wall").fail("unknown wall \"" + name + "\"" + listed("walls", wall_names(*world_)));
        for (const char* k : {"group", "id", "region", "fix", "free", "applied_force", "local_damping", "viscous_damping"})
            if (n.has(k)) n.at(k).fail(std::string("'") + k + "' does not apply to a wall (set velocity or angular_velocity)");
        if (n.has("velocity")) {
            const Vec v = n.at("velocity").vec(dim);
            actions.push_back([wall, v](World& w) { w.walls.walls[wall].velocity = v; });
        }
        if (n.has("angular_velocity")) {
            const Vec om = read_angular_velocity(n, dim);
            actions.push_back([wall, om](World& w) { w.walls.walls[wall].angular_velocity = om; });
        }
    } else if (n.has("group") || n.has("id") || n.has("region")) {
        // the balls are chosen when the command runs (a region selects by the positions then)
        auto selector = select(n, *world_);
        std::vector<std::function<void(World&, const std::vector<int>&)>> on_balls;
        if (n.has("velocity")) {
            const Vec v = n.at("velocity").vec(dim);
            on_balls.push_back([v](World& w, const std::vector<int>& sel) { for (int i : sel) w.bodies.velocity[i] = v; });
        }
        if (n.has("angular_velocity")) {
            const Vec om = read_angular_velocity(n, dim);
            on_balls.push_back([om](World& w, const std::vector<int>& sel) { for (int i : sel) w.bodies.angular_velocity[i] = om; });
        }
        if (n.has("random_velocity")) {  // as LAMMPS's `velocity create`: each component uniform in [-a, a], seeded
            const Node rv = n.at("random_velocity");
            rv.allow_keys({"amplitude", "seed"});
            const double a = rv.at("amplitude").number(0.0, kInf, false, true);
            const std::uint64_t seed = std::uint64_t(rv.at("seed").integer(0, 1L << 62));
            on_balls.push_back([a, seed, dim](World& w, const std::vector<int>& sel) {
                Rng rng(seed);
                for (int i : sel) {
                    w.bodies.velocity[i].setZero();
                    for (int c = 0; c < dim; ++c) w.bodies.velocity[i][c] = rng.uniform(-a, a);
                }
            });
        }
        if (n.has("velocity_profile")) on_balls.push_back(velocity_profile(n.at("velocity_profile"), dim));
        if (n.has("fix")) {
            const std::uint8_t f = read_fixity(n.at("fix"));
            on_balls.push_back([f](World& w, const std::vector<int>& sel) { for (int i : sel) w.bodies.fixity[i] |= f; });
        }
        if (n.has("free")) {
            const std::uint8_t f = read_fixity(n.at("free"));
            on_balls.push_back([f](World& w, const std::vector<int>& sel) {
                for (int i : sel) w.bodies.fixity[i] = (w.bodies.fixity[i] & ~f) | w.bodies.implicit_fixity();
            });
        }
        if (n.has("applied_force")) {
            const Vec f = n.at("applied_force").vec(dim);
            on_balls.push_back([f](World& w, const std::vector<int>& sel) {
                if (!w.bodies.has_applied_loads()) w.bodies.enable_applied_loads();
                for (int i : sel) w.bodies.applied_force[i] = f;
            });
        }
        if (n.has("viscous_damping")) {
            const double c = n.at("viscous_damping").number(0.0, kInf, false, true);
            on_balls.push_back([c](World& w, const std::vector<int>& sel) { for (int i : sel) w.bodies.viscous_damping[i] = c; });
        }
        if (n.has("local_damping")) {
            const double a = n.at("local_damping").number(0.0, 1.0, false, true);
            on_balls.push_back([a](World& w, const std::vector<int>& sel) { for (int i : sel) w.bodies.local_damping[i] = a; });
        }
        // on clumps: their own motion, or an error naming the key
        std::vector<ClumpAction> on_clumps;
        std::vector<std::string> not_for_clumps;
        for (const char* k : {"velocity", "angular_velocity", "random_velocity", "velocity_profile", "fix", "free",
                              "applied_force", "viscous_damping", "local_damping"}) {
            if (!n.has(k)) continue;
            if (ClumpAction a = clump_action(n, k, dim)) on_clumps.push_back(std::move(a));
            else not_for_clumps.push_back(k);
        }
        const std::string path = n.path();
        actions.push_back([selector, on_balls, on_clumps, not_for_clumps, path](World& w) {
            std::vector<int> sel = selector(w);
            const std::vector<int> clumps = take_clumps(w, sel);
            if (!clumps.empty() && !not_for_clumps.empty())
                throw InputError(path + "." + not_for_clumps.front(),
                                 "does not apply to a clump (the selection holds pebbles of clump id " +
                                     std::to_string(w.clumps.id[std::size_t(clumps.front())]) +
                                     "); a clump takes velocity, angular_velocity, fix, free and local_damping");
            for (const auto& a : on_balls) a(w, sel);
            for (const auto& a : on_clumps) a(w, clumps);
            for (int c : clumps) w.clumps.place_pebbles(w.bodies, std::size_t(c));
        });
    } else if (!n.has("gravity")) {
        n.fail("a set command needs a target: group, id, region or wall (or sets gravity)");
    }
    return [actions](World& w) { for (const auto& a : actions) a(w); };
}

namespace {
bool is_pebble_of(const World& w, std::size_t ball, BodyId clump_id) {
    if (w.bodies.clump.empty() || w.bodies.clump[ball] < 0) return false;
    return w.clumps.id[std::size_t(w.bodies.clump[ball])] == clump_id;
}
} // namespace

// Bodies chosen by group, id (a clump's id: its pebbles) and/or region (all
// given criteria must hold).
std::function<std::vector<int>(const World&)> Simulation::select(const Node& n, const World& w) const {
    int group = -1;
    if (n.has("group")) {
        group = w.find_group(n.at("group").string());
        if (group < 0)
            n.at("group").fail("unknown group \"" + n.at("group").string() + "\"" + listed("groups", w.group_names()));
    }
    long id = -1;
    if (n.has("id")) id = n.at("id").integer(0, long(w.bodies.next_id) - 1);
    Vec lo = Vec::Constant(-kInf), hi = Vec::Constant(kInf);
    if (n.has("region")) {
        const Node r = n.at("region");
        r.allow_keys({"min", "max"});
        lo = r.at("min").vec(w.dim);
        hi = r.at("max").vec(w.dim);
        if (w.dim == 2) { lo.z() = -kInf; hi.z() = kInf; }
    }
    json criteria = json::object();  // only what selects, not what is set
    for (const char* k : {"group", "id", "region"})
        if (n.has(k)) criteria[k] = n.value()[k];
    const std::string path = n.path();
    return [=](const World& world) {
        std::vector<int> sel;
        for (std::size_t i = 0; i < world.bodies.size(); ++i) {
            if (group >= 0 && world.bodies.group[i] != group) continue;
            if (id >= 0 && world.bodies.id[i] != BodyId(id) && !is_pebble_of(world, i, BodyId(id))) continue;
            const Vec& p = world.bodies.position[i];
            if ((p.array() < lo.array()).any() || (p.array() > hi.array()).any()) continue;
            sel.push_back(int(i));
        }
        if (sel.empty())
            throw InputError(path, "selects no ball at t = " + std::to_string(world.time) + " s: none of the " +
                                       std::to_string(world.bodies.size()) + " balls matches " + show(criteria));
        return sel;
    };
}

// {"bond": {"groups": [a, b], "gap": g}}: bonds every contact between the
// two groups with surface gap <= g (PFC's `contact method bond gap`).
std::function<void(World&)> Simulation::load_bond(const Node& n) {
    n.allow_keys({"groups", "gap"});
    const Node groups = n.at("groups");
    if (!groups.value().is_array() || groups.size() != 2)
        groups.fail("expected two group names, got " + show(groups.value()));
    int g[2];
    for (int s = 0; s < 2; ++s) {
        g[s] = world_->find_group(groups.at(s).string());
        if (g[s] < 0) groups.at(s).fail("unknown group \"" + groups.at(s).string() + "\"" + listed("groups", world_->group_names()));
    }
    const double gap = n.number_or("gap", 0.0, 0.0, kInf, false, true);
    const std::string path = n.path();
    // quiet_ read when the command runs: set_quiet() comes after the scene is loaded
    return [g0 = g[0], g1 = g[1], gap, path, this](World& w) {
        const std::size_t made = w.bond(g0, g1, gap);
        if (made == 0)
            throw InputError(path, "made no bond: no contact of a model with bonds (e.g. linear_pbond) between the two "
                                   "groups has a surface gap <= " + std::to_string(gap) + " m");
        if (!quiet_) spdlog::info("{}: {} bonds", path, made);
    };
}

void Simulation::load_commands(const Node& n) {
    n.expect_array();
    for (std::size_t i = 0; i < n.size(); ++i) {
        const Node c = n.at(i);
        c.expect_object();
        if (c.size() != 1) c.fail("a command is an object with one key: cycle, solve, set, bond, servo, histories or output");
        Command cmd{Command::cycle, c.path()};
        if (c.has("cycle")) {
            cmd.value = double(c.at("cycle").integer(0, 1L << 50));
        } else if (c.has("solve")) {
            const Node s = c.at("solve");
            s.allow_keys({"time", "ratio", "max_cycles", "stop_on_bond_break"});
            cmd.stop_on_bond_break = s.has("stop_on_bond_break") && s.at("stop_on_bond_break").boolean();
            if (s.has("time") == s.has("ratio"))
                s.fail("solve needs exactly one of: time (s), ratio; got " + show(s.value()));
            if (s.has("time")) {
                cmd.kind = Command::solve_time;
                cmd.value = s.at("time").positive();
            } else {
                cmd.kind = Command::solve_ratio;
                // below 1e-12 the force sums' round-off (~1e-16 of each
                // contact force, summed) keeps the ratio from ever getting there
                cmd.value = s.at("ratio").number(1e-12, 1.0);
            }
            cmd.max_cycles = s.has("max_cycles") ? s.at("max_cycles").integer(1, 1L << 50) : 10000000;
        } else if (c.has("set")) {
            cmd.kind = Command::set;
            cmd.apply = load_set(c.at("set"));
        } else if (c.has("histories")) {
            // PFC's `history purge`: the rows so far are dropped and a first
            // row is taken at this state (forces and energies evaluated anew),
            // so a case's metrics see only what follows
            cmd.kind = Command::set;
            c.at("histories").choice({"clear"});
            cmd.apply = [this](World& w) {
                w.mark_dirty();
                w.prepare();
                history_rows_.clear();
                history_stale_ = true;
                if (!history_cols_.empty()) history_rows_.push_back(sample_history_row());
            };
        } else if (c.has("output")) {
            cmd.kind = Command::output;
            c.at("output").choice({"vtk"});
        } else if (c.has("bond")) {
            cmd.kind = Command::set;
            cmd.apply = load_bond(c.at("bond"));
        } else if (c.has("servo")) {
            // a servo's switch lives in the run, not in the world: a restart
            // replays the servo commands the run has done
            cmd.kind = Command::set;
            cmd.replayed_on_restart = true;
            cmd.apply = [this, change = read_servo_command(c.at("servo"), servos_, *world_)](World&) { change(servos_); };
        } else {
            c.fail("unknown command \"" + c.value().begin().key() + "\"; commands: cycle, solve, set, bond, servo, histories, output");
        }
        commands_.push_back(std::move(cmd));
    }
}

std::vector<double> Simulation::history(const std::string& name) const {
    for (std::size_t c = 0; c < history_cols_.size(); ++c)
        if (history_cols_[c].name == name) {
            std::vector<double> out;
            for (const auto& row : history_rows_) out.push_back(row[c]);
            return out;
        }
    throw InputError("histories", "no history named \"" + name + "\"");
}

Simulation::DueOutputs Simulation::due_after_step() const {
    const World& w = *world_;
    const auto at = [&](double interval, double next) {
        return interval > 0 && !out_dir_.empty() && w.time + 1e-12 >= next;
    };
    return {history_every_ > 0 && !history_cols_.empty() && w.step_count % std::uint64_t(history_every_) == 0,
            at(vtk_.interval, next_vtk_time_), at(png_interval_, next_png_time_),
            at(checkpoint_every_, next_checkpoint_time_)};
}

std::vector<double> Simulation::sample_history_row() const {
    std::vector<double> row;
    row.reserve(history_cols_.size());
    for (const auto& c : history_cols_) row.push_back(c.derive ? c.derive(row) : c.sample(*world_));
    return row;
}

// The first time next + k * interval after `time` (an interval too small to
// move the sum is refused before the run, check_run_length()).
static double next_due(double next, double interval, double time) {
    const double k = std::floor((time + 1e-12 - next) / interval) + 1;
    return std::max(next + std::max(k, 1.0) * interval, std::nextafter(time, kInf));
}

void Simulation::after_step() {
    const World& w = *world_;
    const DueOutputs due = due_after_step();
    if (due.history) history_rows_.push_back(sample_history_row());
    // the rows go to history.csv with every other output, and every few
    // seconds between them: a killed run loses little of its history
    if (due.vtk || due.png || due.checkpoint || (due.history && history_flush_due())) flush_history();
    if (due.vtk) {
        write_vtk_snapshot();
        next_vtk_time_ += vtk_.interval;
    }
    if (due.png) {
        write_png_snapshot();
        next_png_time_ += png_interval_;
    }
    if (watch_ && std::chrono::steady_clock::now() - watch_written_ >= kWatchInterval) write_watch_png();
    if (due.checkpoint) {
        update_run_figures();
        write_outputs();  // before the checkpoint: a checkpoint on disk has its summary
        save_checkpoint(checkpoint_path());
        next_checkpoint_time_ = next_due(next_checkpoint_time_, checkpoint_every_, w.time);
    }
}

void Simulation::cycle(long n) {
    World& w = *world_;
    if (w.step_count == 0 && history_rows_.empty() && !history_cols_.empty()) {
        w.prepare();
        history_rows_.push_back(sample_history_row());
    }
    // The contact forces are written on the steps after which something
    // reads them (World::contact_forces_wanted): outputs and history rows
    // due, the cycle's last step (the next command, the run's summary) or a
    // stop. (Asked inside step(), where its time and count are those that
    // after_step() sees.)
    long k = 0;
    struct Unset {
        World& w;
        ~Unset() { w.contact_forces_wanted = nullptr; }
    } unset{w};
    w.contact_forces_wanted = [&] { return k + 1 >= n || stop_signal() != 0 || due_after_step().any(); };
    const auto one_step = [&] {
        if (!flows_.empty()) flows_.before_step(w);
        if (!servos_.empty()) drive_servos(servos_, w);
        w.step();
        ++run_.steps;
        after_step();
    };
    for (; k < n; ++k) {
        one_step();
        if (stop_signal()) {  // the step is complete: stop here, run() writes the checkpoint
            if (contact_forces_current(w)) break;
            ++k;  // (the signal came after the step asked): one more, which writes them
            one_step();
            break;
        }
        progress_.update(w.time, w.step_count);
    }
}

// Cost figures of the run so far.
void Simulation::update_run_figures() {
    const World& w = *world_;
    run_.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
    run_.cpu_seconds = double(std::clock() - cpu_started_) / CLOCKS_PER_SEC;
    run_.simulated_time = w.time;
    run_.particle_steps_per_second =
        run_.wall_seconds > 0 ? double(run_.steps) * double(w.bodies.size()) / run_.wall_seconds : 0;
}

// Cost figures of the run and its outputs, also for a run that stopped.
void Simulation::finish_run() {
    const World& w = *world_;
    update_run_figures();
    finished_ = !interrupted_;
    // histories.at_end: the state the run ends in (an equilibrium a ratio
    // solve reached, the step a bond broke) is a row too, unless the last
    // step was sampled already (rows are taken at step 0 and every `every`)
    if (history_at_end_ && !history_cols_.empty()) {
        const bool sampled = !history_rows_.empty() && w.step_count % std::uint64_t(history_every_) == 0;
        if (!sampled) history_rows_.push_back(sample_history_row());
    }
    if (scene_.contains("metrics")) metrics_ = evaluate_metrics(scene_["metrics"], *this, scene_dir_);
    if (out_dir_.empty()) return;
    // the state a run ends in is a frame of its series, also when the
    // interval does not divide the run (a stopped run resumes its series)
    if (finished_ && vtk_.interval > 0 && (vtk_series_.empty() || vtk_series_.back().first < w.time))
        write_vtk_snapshot();
    if (finished_ && png_interval_ > 0 && last_png_time_ < w.time) write_png_snapshot();
    if (finished_) redraw_png_series();
    if (watch_) write_watch_png();
    flush_history();
    write_outputs();
}

// One command, resumable: its progress is measured from the step it began
// at (kept in checkpoints), so a restarted run takes the same steps.
bool Simulation::run_command(const Command& c) {
    World& w = *world_;
    if (!command_started_) {
        command_started_ = true;
        command_start_step_ = w.step_count;
        command_end_time_ = c.kind == Command::solve_time ? w.time + c.value : 0.0;
        command_breaks_before_ = w.bond_breaks.size();
    }
    progress_.enabled = !quiet_;
    if (c.kind == Command::solve_time) progress_.start(Progress::Measure::time, w.time, command_end_time_, w.step_count);
    else if (c.kind == Command::cycle)
        progress_.start(Progress::Measure::steps, double(command_start_step_), double(command_start_step_) + c.value, w.step_count);
    else progress_.start(Progress::Measure::open, 0, 0, w.step_count);
    struct Finish {
        Progress& p;
        ~Finish() { p.finish(); }
    } finish{progress_};
    const auto done = [&] { return long(w.step_count - command_start_step_); };
    switch (c.kind) {
    case Command::cycle:
        cycle(long(c.value) - done());
        return done() >= long(c.value);
    case Command::solve_time: {
        const double end = command_end_time_;
        while (w.time < end - 1e-12 * std::fabs(end)) {
            if (c.stop_on_bond_break && w.bond_breaks.size() > command_breaks_before_) break;
            if (done() >= c.max_cycles)
                throw RunError(c.path + ": reached t = " + short_number(w.time) + " s of " + short_number(end) +
                               " s after max_cycles = " + std::to_string(c.max_cycles) +
                               " cycles; raise max_cycles or check the timestep");
            if (stop_signal()) return false;
            cycle(1);
        }
        return true;
    }
    case Command::solve_ratio: {
        if (w.step_count == 0) w.prepare();
        for (;;) {
            const long d = done();
            if (d % 10 == 0) {  // the ratio is checked every 10 cycles
                if (unbalanced_force_ratio(w) <= c.value) return true;
                if (d >= c.max_cycles)
                    throw RunError(c.path + ": ratio " + short_number(unbalanced_force_ratio(w)) + " still above " +
                                   short_number(c.value) + " after " + std::to_string(d) +
                                   " cycles (max_cycles); add local or viscous damping, or raise max_cycles");
            }
            if (stop_signal()) return false;
            cycle(10 - d % 10);
        }
    }
    case Command::set: c.apply(w); w.mark_dirty(); return true;
    case Command::output:
        if (out_dir_.empty()) return true;
        flush_history();
        write_vtk_snapshot();
        return true;
    }
    return true;
}

// Refused before the first step: an output due every step of a run, and a
// solve that would need more than twice its max_cycles at today's timestep
// (one that stops at a bond break ends when it breaks, so it is not judged).
// The step the run will start with and what sets it: the fixed step, the
// last step before a checkpoint, or the safety factor times the nominal
// stable step of the scene's contacts (no contact exists before the run).
Simulation::PlannedStep Simulation::planned_timestep() {
    World& w = *world_;
    if (w.fixed_dt > 0) return {w.fixed_dt, "scene.timestep.fixed"};
    if (resumed_ && w.last_dt > 0) return {w.last_dt, "the last step before the checkpoint"};
    const StableStep s = nominal_timestep(w);
    return {w.safety_factor * s.critical,
            "scene.timestep.safety_factor " + short_number(w.safety_factor) + " x the stable step, limited by " + s.limited_by};
}

void Simulation::check_run_length() {
    World& w = *world_;
    const PlannedStep step = planned_timestep();  // (named: lambdas below capture it)
    const double dt = step.dt;
    const std::string& set_by = step.set_by;
    if (!(dt > 0) || !std::isfinite(dt)) return;
    const auto check_interval = [&](double interval, const std::string& where) {
        if (interval > 0 && !out_dir_.empty() && interval < dt)
            throw InputError(where, "interval " + short_number(interval) + " s is shorter than the timestep " +
                                        short_number(dt) + " s: it would write every step; give at least " +
                                        short_number(dt) + " s");
    };
    check_interval(vtk_.interval, vtk_interval_path_);
    check_interval(png_interval_, "scene.output.png.interval");
    check_interval(checkpoint_every_, "--checkpoint-every");
    for (std::size_t i = next_command_; i < commands_.size(); ++i) {
        const Command& c = commands_[i];
        if (c.kind != Command::solve_time || c.stop_on_bond_break) continue;
        const double steps = (i == next_command_ && command_started_ ? command_end_time_ - w.time : c.value) / dt;
        if (steps > 2.0 * double(c.max_cycles))
            throw InputError(c.path + ".solve.time",
                             "value " + short_number(c.value) + " s takes about " + short_number(steps) + " steps of " +
                                 short_number(dt) + " s (" + set_by + "), more than max_cycles = " + std::to_string(c.max_cycles) +
                                 ": shorten the time, or raise max_cycles if the run is meant to be that long");
    }
}

// The output folder, made before the first step so that a name that cannot
// be a folder is refused by who gave it, not found at the first output.
void Simulation::make_output_dir() const {
    if (out_dir_.empty()) return;
    std::error_code ec;
    std::filesystem::create_directories(out_dir_, ec);
    if (ec || !std::filesystem::is_directory(out_dir_))
        throw InputError(out_dir_from_, "cannot make the output folder \"" + out_dir_ + "\": " +
                                            (ec ? ec.message() : "a file of that name exists"));
}

void Simulation::run() {
    started_ = std::chrono::steady_clock::now();
    cpu_started_ = std::clock();
    World& w = *world_;
    make_output_dir();
    check_run_length();
    if (!quiet_ && !resumed_) {
        w.prepare();
        const StableStep s = stable_timestep(w);
        const std::string by = s.limited_by.empty() ? "no contacts or models to limit it" : s.limited_by;
        if (w.fixed_dt > 0) spdlog::info("timestep fixed at {:g} s; stable limit {:g} s ({})", w.fixed_dt, s.critical, by);
        else spdlog::info("timestep automatic: {:g} x critical {:g} s ({})", w.safety_factor, s.critical, by);
    }
    if (!quiet_ && resumed_) {
        spdlog::info("restarted at step {} (t = {:g} s), command {} of {}", w.step_count, w.time, next_command_ + 1,
                     commands_.size());
        for (const auto& line : restart_log_) spdlog::info("{}", line);
    }
    remove_stale_temporaries();
    flush_history();  // a restart's rows replace those a killed run wrote after its checkpoint
    if (vtk_.interval > 0 && !out_dir_.empty() && w.step_count == 0 && !resumed_) {
        w.prepare();
        write_vtk_snapshot();
        next_vtk_time_ = vtk_.interval;
    }
    if (png_interval_ > 0 && !out_dir_.empty() && w.step_count == 0 && !resumed_) {
        w.prepare();
        write_png_snapshot();
        next_png_time_ = png_interval_;
    }
    try {
        while (next_command_ < commands_.size()) {
            if (!run_command(commands_[next_command_])) break;  // stopped mid-command by a signal
            ++next_command_;
            command_started_ = false;
            if (stop_signal()) break;
        }
        if (stop_signal() && next_command_ < commands_.size()) {
            interrupted_ = true;
            if (!out_dir_.empty()) save_checkpoint(checkpoint_path());
        }
    } catch (const RunError& e) {
        // the world is back at its last good state: keep it for inspection
        if (!out_dir_.empty()) write_vtk_snapshot();
        finish_run();
        const std::string file = write_last_good();
        if (file.empty()) throw;
        throw RunError(std::string(e.what()) + "\nthe last good state is saved in " + file +
                       "; continue from it with a smaller timestep, e.g.\n  plab restart " + file +
                       (w.fixed_dt > 0 ? " --set timestep.fixed=" + short_number(0.5 * w.fixed_dt)
                                       : " --set timestep.safety_factor=" + short_number(0.5 * w.safety_factor)));
    } catch (...) {
        finish_run();
        throw;
    }
    finish_run();
}

} // namespace plab
