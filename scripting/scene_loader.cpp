// Scene → World: plug-ins, bodies (generators), walls, the contact-model
// assignment table, passes and the timestep. Every check names its JSON path.
#include "calibration.hpp"
#include "generators.hpp"
#include "materials.hpp"
#include "simulation.hpp"
#include "variables.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

namespace plab {

namespace {

std::string join(const std::vector<std::string>& v) {
    std::string s;
    for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
    return s;
}

// Names usable in "plugins" for the libraries in the search path
// ("plab_linear.so" -> "linear").
std::string plugin_names(const PluginHost& host) {
    std::vector<std::string> names;
    for (const auto& path : host.discover()) {
        std::string stem = std::filesystem::path(path).stem().string();
        for (const std::string prefix : {"plab_", "lib"})
            if (stem.rfind(prefix, 0) == 0) { stem = stem.substr(prefix.size()); break; }
        names.push_back(stem);
    }
    return names.empty() ? std::string("none") : join(names);
}

} // namespace

Simulation::Simulation(const json& scene, const std::string& scene_dir, std::shared_ptr<PluginHost> host)
    : scene_(resolve_variables(scene)), scene_dir_(scene_dir), host_(host ? std::move(host) : std::make_shared<PluginHost>()),
      materials_(std::make_unique<Materials>()) {
    load(Node(scene_, "scene"));
    world_->on_snapshot = [this] { keep_last_good(); };  // (a Simulation is never moved)
}

Simulation::~Simulation() = default;

void Simulation::load(const Node& root) {
    root.allow_keys({"description", "dimension", "domain", "gravity", "plugins", "bodies", "walls", "materials",
                     "contact_models", "passes", "timestep", "skin", "histories", "output", "commands", "validation",
                     "stability", "metrics", "variables", "limits", "servos", "inlets", "outlets"});
    const int dim = int(root.at("dimension").integer(2, 3));
    world_ = std::make_unique<World>(dim, host_);
    if (root.has("domain")) {
        const Node d = root.at("domain");
        d.allow_keys({"min", "max", "periodic", "shear"});
        domain_min_ = d.at("min").vec(dim);
        domain_max_ = d.at("max").vec(dim);
        for (int c = 0; c < dim; ++c)
            if (!(domain_min_[c] < domain_max_[c]))
                d.at("max").fail("domain max must exceed min in every direction (component " + std::to_string(c) + ")");
        if (d.has("periodic")) load_periodic_axes(d.at("periodic"));
        if (d.has("shear")) load_shear(d.at("shear"));
        if (dim == 2) { domain_min_.z() = -kInf; domain_max_.z() = kInf; }
    }
    world_->gravity = root.vec_or("gravity", dim, Vec::Zero());
    load_stability(root.has("stability") ? root.at("stability") : Node(json::object(), "scene.stability"));
    if (root.has("skin")) world_->set_skin(root.at("skin").number(0.0, kInf, false, true));
    load_plugins(root.has("plugins") ? root.at("plugins") : Node(json::array(), "scene.plugins"));
    if (root.has("limits")) {
        const Node l = root.at("limits");
        l.allow_keys({"max_bodies"});
        limits_.max_bodies = l.at("max_bodies").integer(1, 1L << 40);
    }
    if (root.has("bodies")) load_bodies(root.at("bodies"));
    if (root.has("walls")) load_walls(root.at("walls"));
    if (root.has("servos")) servos_ = read_servos(root.at("servos"), *world_);
    if (root.has("inlets")) flows_.read_inlets(root.at("inlets"), *world_, scene_dir_);
    if (root.has("outlets")) flows_.read_outlets(root.at("outlets"), *world_);
    if (root.has("materials")) materials_->load(root.at("materials"), *world_);
    if (root.has("contact_models")) load_contact_models(root.at("contact_models"));
    if (root.has("passes")) load_passes(root.at("passes"));
    materials_->check_all_used();
    load_timestep(root.has("timestep") ? root.at("timestep") : Node(json::object(), "scene.timestep"));
    if (root.has("histories")) load_histories(root.at("histories"));
    if (root.has("output")) load_output(root.at("output"));
    if (root.has("commands")) load_commands(root.at("commands"));
    if (world_->bodies.cell.sheared) start_shear();
    if (world_->bodies.cell.any() && world_->clumps.size())
        root.at("domain").at("periodic").fail("a periodic cell with clumps is not supported yet (a clump's pebbles would be wrapped apart); valid: no clumps, or no periodic axis");
}

void Simulation::load_plugins(const Node& n) {
    n.expect_array();
    for (std::size_t i = 0; i < n.size(); ++i) {
        const Node p = n.at(i);
        const std::string name = p.string();
        if (const std::string now = PluginHost::merged_into(name); !now.empty())
            spdlog::warn("{}: \"{}\" is part of the library \"{}\" now (physics packages, docs/architecture.md), "
                         "which it loads; list \"{}\" instead", p.path(), name, now, now);
        std::string file;
        try {
            file = host_->resolve(name, scene_dir_);
        } catch (const PluginError& e) {
            // a misspelt name is the usual cause: show the names that would work
            throw InputError(p.path(), std::string(e.what()) + "; plug-ins found: " + plugin_names(*host_));
        }
        try {
            host_->load(file);
        } catch (const PluginError& e) {
            throw InputError(p.path(), e.what());
        }
    }
}

// domain.periodic: the axes along which the domain is a periodic cell
// (plab_host/bodies.hpp, PeriodicCell), each named once.
void Simulation::load_periodic_axes(const Node& n) {
    n.expect_array();
    PeriodicCell& cell = world_->bodies.cell;
    for (std::size_t i = 0; i < n.size(); ++i) {
        const int c = world_->dim == 3 ? int(n.at(i).choice({"x", "y", "z"}).front() - 'x')
                                       : int(n.at(i).choice({"x", "y"}).front() - 'x');
        if (cell.periodic[c]) n.at(i).fail("axis listed twice; valid: each of x, y" + std::string(world_->dim == 3 ? ", z" : "") + " at most once");
        cell.periodic[c] = true;
    }
    cell.lo = domain_min_;
    cell.hi = domain_max_;
    if (world_->dim == 2) { cell.lo.z() = 0; cell.hi.z() = 1; }
}

// domain.shear: Lees–Edwards simple shear of the periodic cell (flow along
// x, gradient along y; plab_host/bodies.hpp, PeriodicCell).
void Simulation::load_shear(const Node& n) {
    n.allow_keys({"rate", "initial_velocity"});
    PeriodicCell& cell = world_->bodies.cell;
    if (!cell.periodic[0] || !cell.periodic[1])
        n.fail("a sheared cell needs x (the flow) and y (the gradient) periodic; valid: domain.periodic listing x and y");
    cell.sheared = true;
    cell.shear_rate = n.at("rate").number();
    shear_start_affine_ = n.has("initial_velocity") ? n.at("initial_velocity").choice({"affine", "as_given"}) == "affine" : true;
}

// After the bodies: the balls start on the shear's flow (v_x += rate (y -
// y_mid), "affine") unless told not to.
void Simulation::start_shear() {
    Bodies& b = world_->bodies;
    if (shear_start_affine_)
        for (std::size_t i = 0; i < b.size(); ++i) b.velocity[i].x() += b.cell.affine_velocity(b.position[i]);
}

void Simulation::check_domain(const std::string& where, std::size_t first) const {
    const Bodies& b = world_->bodies;
    for (std::size_t i = first; i < b.size(); ++i) {
        const Vec& p = b.position[i];
        for (int c = 0; c < world_->dim; ++c)
            if (b.cell.periodic[c] ? (p[c] < domain_min_[c] || p[c] >= domain_max_[c])  // (a ball may straddle the boundary)
                                   : (p[c] - b.radius[i] < domain_min_[c] || p[c] + b.radius[i] > domain_max_[c])) {
                std::ostringstream s;
                s << "ball at " << p.head(world_->dim).transpose() << " (radius " << b.radius[i]
                  << ") lies outside the domain [" << domain_min_.head(world_->dim).transpose() << "] .. ["
                  << domain_max_.head(world_->dim).transpose() << "]";
                throw InputError(where, s.str());
            }
    }
}

void Simulation::load_bodies(const Node& n) {
    n.expect_array();
    std::vector<std::pair<Box, std::string>> regions;
    for (std::size_t i = 0; i < n.size(); ++i) {
        const Node g = n.at(i);
        const std::size_t before = world_->bodies.size();
        LatticeCells cells;
        const std::optional<Box> region = generate_bodies(g, *world_, limits_, &cells, scene_dir_);
        if (cells.group >= 0) {
            cells.first = before;
            cells.end = world_->bodies.size();
            cells.path = g.path();
            if (!cells.note.empty()) {
                spdlog::info("{} ({}): {}", g.path(), world_->group_names()[std::size_t(cells.group)], cells.note);
                structures_.push_back({{"bodies", g.path()}, {"lattice", cells.note}});
            }
            lattices_.push_back(cells);
        }
        if (region) {
            for (const auto& [other, where] : regions)
                if (region->overlaps(other, world_->dim)) {
                    const int d = world_->dim;
                    std::ostringstream s;
                    s << "generator region [" << region->lo.head(d).transpose() << "] .. [" << region->hi.head(d).transpose()
                      << "] overlaps the region [" << other.lo.head(d).transpose() << "] .. [" << other.hi.head(d).transpose()
                      << "] of " << where << "; balls from the two would overlap — move or shrink one";
                    g.fail(s.str());
                }
            regions.emplace_back(*region, g.path());
        }
        check_domain(g.path(), before);
    }
}

void Simulation::load_walls(const Node& n) {
    n.expect_array();
    for (std::size_t i = 0; i < n.size(); ++i) generate_wall(n.at(i), *world_, scene_dir_);
    check_coincident_facets(n, *world_);
}

// Rules apply in order; a later rule overrides an earlier one for the group
// pairs it names ("*" matches every group).
void Simulation::load_contact_models(const Node& n) {
    n.expect_array();
    World& w = *world_;
    for (std::size_t i = 0; i < n.size(); ++i) {
        const Node rule = n.at(i);
        rule.allow_keys({"groups", "model", "properties", "calibrate", "max_overlap"});
        const Node groups = rule.at("groups");
        if (!groups.value().is_array() || groups.size() != 2)
            groups.fail("expected two group names, e.g. [\"grains\", \"walls\"] (\"*\" for any), got " + show(groups.value()));
        std::vector<int> sides[2];
        for (int s = 0; s < 2; ++s) {
            const std::string name = groups.at(s).string();
            if (name == "*") {
                for (std::size_t g = 0; g < w.group_names().size(); ++g) sides[s].push_back(int(g));
            } else {
                const int g = w.find_group(name);
                if (g < 0)
                    groups.at(s).fail("unknown group \"" + name + "\"; groups in this scene: " + join(w.group_names()));
                sides[s].push_back(g);
            }
        }
        const std::string model = rule.at("model").string();
        int instance = -1;
        if (model != "null") {
            const plab_contact_model_desc* d = host_->model(model);
            if (!d) {
                auto names = host_->model_names();
                rule.at("model").fail("unknown contact model \"" + model + "\"; models loaded by this scene's plugins: " +
                                      (names.empty() ? std::string("none (list plug-ins under \"plugins\")") : join(names)) +
                                      ", or \"null\" for no contact");
            }
            // the rule's materials: those of the groups it names, per side
            // (materials.hpp: two sides of different materials mix)
            std::vector<std::vector<int>> mats(2);
            for (int s = 0; s < 2; ++s)
                for (int g : sides[s])
                    if (const int m = materials_->of_group(g);
                        m >= 0 && std::find(mats[s].begin(), mats[s].end(), m) == mats[s].end())
                        mats[s].push_back(m);
            const std::vector<std::string>& groups = w.group_names();
            // what a scene material may give the model: its package material's properties
            const plab_material_desc* material = d->material ? host_->material(d->material) : nullptr;
            if (rule.has("calibrate")) {
                // calibrated values first; explicit properties override them
                const Node cal = rule.at("calibrate");
                cal.at("method").choice({"hexagonal_2d"});
                json merged = rule.value();
                json props = hexagonal_2d_calibration(cal, w.dim);
                calibrate_density(cal, sides);
                if (rule.has("properties")) props.update(rule.value()["properties"]);
                merged["properties"] = props;
                const Node merged_rule(merged, rule.path());
                std::vector<double> values =
                    read_properties(merged_rule, d->properties, d->property_count, "model " + model, groups);
                materials_->fill(merged_rule, mats, d->properties, d->property_count, material, w.gravity, groups, values);
                check_required_properties(merged_rule, d->properties, d->property_count, values, "model " + model, groups);
                instance = w.add_instance(model, std::move(values));
            } else {
                std::vector<double> values = read_properties(rule, d->properties, d->property_count, "model " + model, groups);
                materials_->fill(rule, mats, d->properties, d->property_count, material, w.gravity, groups, values);
                check_required_properties(rule, d->properties, d->property_count, values, "model " + model, groups);
                instance = w.add_instance(model, std::move(values));
            }
        } else if (rule.has("properties")) {
            rule.at("properties").fail("the null model has no properties");
        }
        if (rule.has("max_overlap")) {
            if (instance < 0) rule.at("max_overlap").fail("the null model makes no contact to limit");
            // fraction of the smaller radius beyond which the detector stops the run
            w.set_max_overlap(std::size_t(instance), rule.at("max_overlap").number(0.0, kInf, true, true));
        }
        for (int a : sides[0])
            for (int b : sides[1]) w.assign(a, b, instance);
    }
}

// calibrate.density "section" (the default): the balls of the rule's
// groups get the density that puts the material's mass in each ball's cell,
// rho_ball = rho cell / ball. The calibrated continuum (eqs. 36-39) is the
// union of the cells, so its mass per area is rho only so. A hexagonal
// lattice of touching discs gives each disc the hexagon 2 sqrt(3) R^2
// (a pitch 2R by a row pitch sqrt(3) R) around its pi R^2: a factor
// 2 sqrt(3) / pi = 1.1027 (discs fill pi / (2 sqrt(3)) = 90.7 % of it). A 3D
// calibration would take its packing's factor alike: hcp 4 sqrt(2) R^3 over
// 4/3 pi R^3 = 3 sqrt(2) / pi = 1.3505, cubic 8 R^3 over it, 6 / pi = 1.9099.
// (No 3D calibration exists yet: hexagonal_2d refuses a 3D scene.)
// "ball" keeps the balls' density (a scene that sets the masses itself).
void Simulation::calibrate_density(const Node& cal, const std::vector<int>* sides) {
    if (cal.has("density") && cal.at("density").choice({"section", "ball"}) == "ball") return;
    World& w = *world_;
    // a disc's mass is per metre of thickness (bodies.hpp), the calibrated
    // stiffnesses per `thickness` t (eqs. 36-37): the mass of t of the plate
    const double thickness = cal.number_or("thickness", 1.0, 0.0, kInf, true, true);
    for (int s = 0; s < 2; ++s)
        for (int g : sides[s]) {
            std::size_t in_lattices = 0, in_group = 0;
            for (std::size_t i = 0; i < w.bodies.size(); ++i) in_group += w.bodies.group[i] == g;
            for (LatticeCells& c : lattices_) {
                if (c.group != g) continue;
                in_lattices += c.end - c.first;
                check_calibrated_lattice(cal, c, w.group_names()[std::size_t(g)]);
                if (c.density_set) continue;  // another rule has (the same factor)
                const double factor = c.cell_volume * thickness / Bodies::mass_of(w.dim, c.radius, 1.0);
                for (std::size_t i = c.first; i < c.end; ++i) {
                    w.bodies.mass[i] *= factor;
                    w.bodies.inertia[i] *= factor;
                }
                c.density_set = true;
                std::ostringstream m;
                m << "ball density x " << factor << " (2 sqrt(3)/pi x thickness " << thickness
                  << " m: the hexagonal cell 2 sqrt(3) R^2 over the disc pi R^2) for the " << c.end - c.first << " balls of "
                  << c.path << ", so that their cells hold the material's density";
                spdlog::info("{}: {}", cal.path(), m.str());
                structures_.push_back({{"calibrate", cal.path()}, {"bodies", c.path}, {"density_factor", factor}, {"note", m.str()}});
            }
            if (in_lattices != in_group)
                cal.fail("group \"" + w.group_names()[std::size_t(g)] + "\" has " + std::to_string(in_group - in_lattices) +
                         " balls not made by a lattice generator; the calibration gives a lattice the material's density "
                         "over its cells and has none for them: make the group of lattices only, or give calibrate.density "
                         "= \"ball\" to keep the balls' density");
        }
    w.mark_dirty();
}

// The lattice a hexagonal_2d calibration describes: touching discs of its
// radius in a hexagonal packing; one filling a box is warned about.
void Simulation::check_calibrated_lattice(const Node& cal, const LatticeCells& c, const std::string& group) const {
    const double hexagon = 2 * std::sqrt(3.0) * c.radius * c.radius;
    if (c.packing != "hexagonal" || std::fabs(c.cell_volume - hexagon) > 1e-9 * hexagon)
        cal.at("method").fail("the hexagonal_2d calibration is for a hexagonal lattice of touching discs; group \"" + group +
                              "\" from " + c.path + " is a " + c.packing + " lattice" +
                              (c.packing == "hexagonal" ? " with a spacing above 2 radius" : "") +
                              "; make it a hexagonal one, or give calibrate.density = \"ball\" to keep its density");
    const double radius = cal.at("radius").positive();
    if (std::fabs(c.radius - radius) > 1e-9 * radius) {
        std::ostringstream m;
        m << "value " << radius << " m is not the radius " << c.radius << " m of group \"" << group << "\" (" << c.path
          << "); the calibration's stiffness (eqs. 36-39) and its density are for that radius";
        cal.at("radius").fail(m.str());
    }
    if (c.note.empty() && !c.density_set)
        spdlog::warn("{}: {} fills a box; the section the calibration describes (the balls' cells) is not the box (a box "
                     "2 n R wide holds rows of n and n - 1 balls: 2 (n - 1/2) R of cells); \"solid\" names that section's "
                     "size (docs/bonded-structures.md)", cal.path(), c.path);
}

// The instability detector's limits (core/src/monitor/stability.hpp);
// the domain is the scene's `domain` when it has one.
void Simulation::load_stability(const Node& n) {
    n.allow_keys({"enabled", "energy_gain", "domain_margin"});
    StabilityLimits& s = world_->stability_limits();
    if (n.has("enabled")) s.enabled = n.at("enabled").boolean();
    s.energy_gain = n.number_or("energy_gain", s.energy_gain, 0.0, kInf, true, true);
    s.domain_margin = n.number_or("domain_margin", s.domain_margin, 0.0, kInf, false, true);
    s.domain_min = domain_min_;
    s.domain_max = domain_max_;
}

void Simulation::load_passes(const Node& n) {
    n.expect_array();
    if (world_->bodies.cell.sheared && n.size())  // (a pass's view has no shear)
        n.fail("passes (SPH, coupling) in a sheared cell are not supported: their plab_pass_view has no shear; "
               "valid: no passes, or no domain.shear");
    for (std::size_t i = 0; i < n.size(); ++i) {
        const Node p = n.at(i);
        p.allow_keys({"name", "material", "properties"});
        const std::string name = p.at("name").string();
        const plab_pass_desc* d = host_->pass(name);
        if (!d) {
            auto names = host_->pass_names();
            p.at("name").fail("unknown pass \"" + name + "\"; passes loaded by this scene's plugins: " +
                              (names.empty() ? std::string("none") : join(names)));
        }
        const std::vector<std::string>& groups = world_->group_names();
        std::vector<double> values = read_properties(p, d->properties, d->property_count, "pass " + name, groups);
        std::vector<std::vector<int>> mats(1);
        if (p.has("material")) {
            if (!d->material)
                p.at("material").fail("pass " + name + " takes no properties from a material (it names no package "
                                      "material: plab plugins --describe " + name + ")");
            mats[0].push_back(materials_->find(p.at("material")));
        }
        const plab_material_desc* material = d->material ? host_->material(d->material) : nullptr;
        materials_->fill(p, mats, d->properties, d->property_count, material, world_->gravity, groups, values);
        check_required_properties(p, d->properties, d->property_count, values, "pass " + name, groups);
        world_->add_pass(name, std::move(values));
    }
}

void Simulation::load_timestep(const Node& n) {
    n.allow_keys({"fixed", "fixed_fraction", "safety_factor", "allow_unstable"});
    World& w = *world_;
    w.safety_factor = n.number_or("safety_factor", 0.8, 0.0, 1.0, true, false);
    StableStep s;
    try {
        s = nominal_timestep(w);  // also refuses a model that reports no stable step
    } catch (const PluginError& e) {
        throw InputError("scene.contact_models", e.what());
    }
    if (n.has("fixed") && n.has("fixed_fraction")) n.fail("give \"fixed\" (s) or \"fixed_fraction\" (of the stable step), not both");
    // the stable step is that of the balls present: an inlet's come later
    if (!n.has("fixed") && flows_.has_inlets() && w.bodies.size() == 0)
        n.fail("a scene that starts without balls and pours them from an inlet needs \"fixed\" (s): the automatic "
               "step, and \"fixed_fraction\", take the stable step of the balls present, and there are none");
    // a fixed step as a fraction of the nominal stable one (one contact of the
    // lightest ball of each assigned pair of groups), as LIGGGHTS users give
    // dt as a fraction of the Rayleigh time
    if (n.has("fixed_fraction")) w.fixed_dt = n.at("fixed_fraction").number(0.0, 1.0, true, false) * s.critical;
    if (!n.has("fixed")) return;
    w.fixed_dt = n.at("fixed").positive();
    const bool allow = n.has("allow_unstable") && n.at("allow_unstable").boolean();
    if (w.fixed_dt > s.critical) {
        std::ostringstream msg;
        msg << "fixed timestep " << w.fixed_dt << " s is " << w.fixed_dt / s.critical << "x the stable limit "
            << s.critical << " s (" << s.limited_by << "); valid range (0, " << s.critical << "]";
        // the hint to allow it only makes sense while it is refused
        if (!allow) n.at("fixed").fail(msg.str() + ", or set timestep.allow_unstable = true");
        timestep_note_ = "warning: " + msg.str();
        if (!quiet_) spdlog::warn("{}: {}", n.at("fixed").path(), msg.str());
    }
}

} // namespace plab
