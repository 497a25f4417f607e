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
#pragma once

#include "json_reader.hpp"

#include <plab_host/world.hpp>

#include <vector>

namespace plab {

struct Servo {
    int wall = -1;
    Vec direction = Vec::Zero();
    double stress = 0, area = 0, gain = 0.5, max_speed = 0;
};

std::vector<Servo> read_servos(const Node& n, const World& w);
// The stress on a servo's wall now: its balls' force against `direction`, over its area (Pa).
double servo_stress(const Servo& s, const World& w);
// Sets each servo wall's velocity for the next step.
void drive_servos(const std::vector<Servo>& servos, World& w);

} // namespace plab
