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

Servo read_servo(const Node& n, const World& w) {
    n.allow_keys({"wall", "stress", "direction", "area", "gain", "max_speed"});
    Servo s;
    const std::string name = n.at("wall").string();
    s.wall = w.walls.find(name);
    if (s.wall < 0) n.at("wall").fail("unknown wall \"" + name + "\"; the walls: " + wall_list(w));
    s.direction = n.at("direction").vec(w.dim);
    if (!(s.direction.norm() > 0)) n.at("direction").fail("the direction must not be zero");
    s.direction.normalize();
    s.stress = n.at("stress").number(0.0, kInf, false, true);
    s.area = n.at("area").positive();
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

double servo_stress(const Servo& s, const World& w) { return -w.walls.walls[std::size_t(s.wall)].force.dot(s.direction) / s.area; }

void drive_servos(const std::vector<Servo>& servos, World& w) {
    for (const Servo& s : servos) {
        const double error = s.stress - servo_stress(s, w), stiffness = wall_contact_stiffness(w, s.wall);
        // (before the first step: the step it will take)
        const double dt = w.last_dt > 0 ? w.last_dt : w.fixed_dt > 0 ? w.fixed_dt : w.safety_factor * nominal_timestep(w).critical;
        double speed = stiffness > 0 && dt > 0 ? s.gain * s.area * error / (stiffness * dt) : std::copysign(s.max_speed, error);
        speed = std::clamp(speed, -s.max_speed, s.max_speed);
        w.walls.walls[std::size_t(s.wall)].velocity = speed * s.direction;
    }
}

} // namespace plab
