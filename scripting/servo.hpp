// Servo-controlled walls (issue 36): a wall whose velocity is set before
// every step so that the stress the balls put on it reaches a target, as
// PFC's servo mechanism and LIGGGHTS's mesh/surface/stress/servo do. The
// scene's "servos" list:
//   {"wall": "top", "stress": 1e5, "direction": [0, -1], "area": 0.1,
//    "gain": 0.5, "max_speed": 0.05}
// `direction` (unit after normalising) is the way the wall moves to press
// the balls harder; the stress is the balls' force on the wall against it,
// over `area` (m², a 2D wall's length x 1 m). PFC's gain: the velocity
//   v = G (σ_target − σ) direction,  G = α A / (Σk Δt),
// Σk the stiffness of the wall's contacts and Δt the last step, moves the
// wall in one step by α times the gap to the target's displacement; with no
// contact it closes in at max_speed, and |v| never exceeds max_speed.
// The area may follow the sample instead: "area": {"walls": [["left",
// "right"]]} is the distance between two parallel walls (3D: the product of
// two such distances; 2D: times 1 m), as PFC's biaxial servo takes the
// current width. The command {"servo": {"wall", "stress" | "off"}} retargets
// a servo or lets the wall go (it keeps its velocity until a `set`).
#pragma once

#include "json_reader.hpp"

#include <plab_host/world.hpp>

#include <functional>
#include <utility>
#include <vector>

namespace plab {

struct Servo {
    int wall = -1;
    Vec direction = Vec::Zero();
    double stress = 0, area = 0, gain = 0.5, max_speed = 0;
    std::vector<std::pair<int, int>> area_walls;  // when set: the area is the product of these walls' distances
    bool on = true;
};

std::vector<Servo> read_servos(const Node& n, const World& w);
// The distance between two parallel planar walls (2D segments, 3D triangles
// or planes), along the first one's normal, now (m).
double wall_distance(const World& w, int a, int b);
// The unit normal of a planar wall (its first facet's; 2D: in the x-y plane).
Vec wall_normal(const World& w, int wall);
// Two walls whose distance wall_distance() can take: an error at `n` otherwise.
std::pair<int, int> read_wall_pair(const Node& n, const World& w);
// The area a servo's stress is taken over now (m^2).
double servo_area(const Servo& s, const World& w);
// {"wall": name, "stress": Pa} or {"wall": name, "off": true}: the change a
// servo command makes, checked against the scene's servos.
std::function<void(std::vector<Servo>&)> read_servo_command(const Node& n, const std::vector<Servo>& servos, const World& w);
// The stress on a servo's wall now: its balls' force against `direction`, over its area (Pa).
double servo_stress(const Servo& s, const World& w);
// Sets each servo wall's velocity for the next step.
void drive_servos(const std::vector<Servo>& servos, World& w);

} // namespace plab
