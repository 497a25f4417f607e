#include "servo.hpp"

#include <plab_host/contacts.hpp>

#include <algorithm>
#include <cmath>

namespace plab {

namespace {

std::string wall_list(const World& w) {
    std::string s;
    for (const Wall& x : w.walls.walls) s += (s.empty() ? "" : ", ") + x.name;
    return s.empty() ? "none" : s;
}

int read_wall(const Node& n, const World& w) {
    const std::string name = n.string();
    const int wall = w.walls.find(name);
    if (wall < 0) n.fail("unknown wall \"" + name + "\"; the walls: " + wall_list(w));
    return wall;
}

// The unit normal of a planar facet (a segment's in the x-y plane).
Vec facet_normal(const Facet& f) {
    if (f.kind == FacetKind::plane) return f.b;
    if (f.kind == FacetKind::segment) return Vec(f.a.y() - f.b.y(), f.b.x() - f.a.x(), 0).normalized();
    return (f.b - f.a).cross(f.c - f.a).normalized();
}

// A wall whose facets all lie in one plane (line), so that it has a normal.
void require_planar(const Node& n, const World& w, int wall) {
    const std::vector<int>& facets = w.walls.walls[std::size_t(wall)].facets;
    if (facets.empty()) n.fail("the wall has no facets");
    const Facet& first = w.walls.facets[std::size_t(facets[0])];
    const Vec normal = facet_normal(first);
    for (int f : facets) {
        const Facet& g = w.walls.facets[std::size_t(f)];
        const bool parallel = std::fabs(std::fabs(facet_normal(g).dot(normal)) - 1) < 1e-9;
        if (!parallel || std::fabs((g.a - first.a).dot(normal)) > 1e-9 * (1 + (g.a - first.a).norm()))
            n.fail("wall \"" + w.walls.walls[std::size_t(wall)].name + "\" is not planar: a distance between walls needs one plane (2D: one line) each");
    }
}

Servo read_servo(const Node& n, const World& w) {
    n.allow_keys({"wall", "stress", "direction", "area", "gain", "max_speed"});
    Servo s;
    s.wall = read_wall(n.at("wall"), w);
    s.direction = n.at("direction").vec(w.dim);
    if (!(s.direction.norm() > 0)) n.at("direction").fail("the direction must not be zero");
    s.direction.normalize();
    s.stress = n.at("stress").number(0.0, kInf, false, true);
    const Node area = n.at("area");
    if (area.value().is_object()) {
        area.allow_keys({"walls"});
        const Node pairs = area.at("walls");
        pairs.expect_array();
        if (pairs.size() != std::size_t(w.dim - 1))
            pairs.fail(std::string("expected ") + (w.dim == 2 ? "one pair" : "two pairs") + " of walls in " + std::to_string(w.dim) +
                       "D, got " + std::to_string(pairs.size()));
        for (std::size_t i = 0; i < pairs.size(); ++i) s.area_walls.push_back(read_wall_pair(pairs.at(i), w));
    } else {
        s.area = area.positive();
    }
    s.gain = n.number_or("gain", 0.5, 0.0, 1.0, true, false);
    s.max_speed = n.at("max_speed").positive();
    return s;
}

// Σk of the wall's active contacts (each model's stiffness for the stable step).
double wall_contact_stiffness(const World& w, int wall) {
    double sum = 0;
    for (std::size_t m = 0; m < w.model_count(); ++m) {
        const ContactTable t = w.model(m).walls();
        for (std::size_t k = 0; k < t.size(); ++k)
            if (t.active(k) && w.walls.facets[t.end2(k)].wall == wall) sum += t.stiffness(k);
    }
    return sum;
}

} // namespace

std::vector<Servo> read_servos(const Node& n, const World& w) {
    n.expect_array();
    std::vector<Servo> out;
    for (std::size_t i = 0; i < n.size(); ++i) {
        out.push_back(read_servo(n.at(i), w));
        for (std::size_t j = 0; j + 1 < out.size(); ++j)
            if (out[j].wall == out.back().wall) n.at(i).at("wall").fail("this wall has a servo already (servos[" + std::to_string(j) + "])");
    }
    return out;
}

Vec wall_normal(const World& w, int wall) { return facet_normal(w.walls.facets[std::size_t(w.walls.walls[std::size_t(wall)].facets[0])]); }

std::pair<int, int> read_wall_pair(const Node& n, const World& w) {
    if (!n.value().is_array() || n.size() != 2) n.fail("expected two wall names, got " + show(n.value()));
    const int a = read_wall(n.at(0), w), b = read_wall(n.at(1), w);
    if (a == b) n.at(1).fail("the two walls must differ");
    require_planar(n.at(0), w, a);
    require_planar(n.at(1), w, b);
    if (std::fabs(std::fabs(wall_normal(w, a).dot(wall_normal(w, b))) - 1) > 1e-9) n.fail("the two walls are not parallel");
    return {a, b};
}

double wall_distance(const World& w, int a, int b) {
    const Facet& fa = w.walls.facets[std::size_t(w.walls.walls[std::size_t(a)].facets[0])];
    const Facet& fb = w.walls.facets[std::size_t(w.walls.walls[std::size_t(b)].facets[0])];
    return std::fabs((fb.a - fa.a).dot(wall_normal(w, a)));
}

double servo_area(const Servo& s, const World& w) {
    if (s.area_walls.empty()) return s.area;
    double area = 1;  // (2D: times 1 m)
    for (const auto& [a, b] : s.area_walls) area *= wall_distance(w, a, b);
    return area;
}

double servo_stress(const Servo& s, const World& w) { return -w.walls.walls[std::size_t(s.wall)].force.dot(s.direction) / servo_area(s, w); }

std::function<void(std::vector<Servo>&)> read_servo_command(const Node& n, const std::vector<Servo>& servos, const World& w) {
    n.allow_keys({"wall", "stress", "off"});
    const int wall = read_wall(n.at("wall"), w);
    std::size_t index = servos.size();
    for (std::size_t i = 0; i < servos.size(); ++i)
        if (servos[i].wall == wall) index = i;
    if (index == servos.size()) n.at("wall").fail("this wall has no servo in scene.servos");
    if (n.has("stress") == n.has("off")) n.fail("a servo command takes one of: stress (Pa, a new target), off (true)");
    if (n.has("off")) {
        if (!n.at("off").boolean()) n.at("off").fail("off takes true (a servo is turned on by giving its stress)");
        return [index](std::vector<Servo>& s) { s[index].on = false; };
    }
    const double stress = n.at("stress").number(0.0, kInf, false, true);
    return [index, stress](std::vector<Servo>& s) {
        s[index].on = true;
        s[index].stress = stress;
    };
}

void drive_servos(const std::vector<Servo>& servos, World& w) {
    for (const Servo& s : servos) {
        if (!s.on) continue;
        const double area = servo_area(s, w);
        const double error = s.stress - servo_stress(s, w), stiffness = wall_contact_stiffness(w, s.wall);
        // (before the first step: the step it will take)
        const double dt = w.last_dt > 0 ? w.last_dt : w.fixed_dt > 0 ? w.fixed_dt : w.safety_factor * nominal_timestep(w).critical;
        double speed = stiffness > 0 && dt > 0 ? s.gain * area * error / (stiffness * dt) : std::copysign(s.max_speed, error);
        speed = std::clamp(speed, -s.max_speed, s.max_speed);
        w.walls.walls[std::size_t(s.wall)].velocity = speed * s.direction;
    }
}

} // namespace plab
