// Named measurements: history quantities that a built-in one cannot say (a
// time average of a field against its hydrostatic profile, where the first
// bond broke, how many pieces a structure is in). A scene records one as
//   {"name": "p_error", "quantity": "measure.hydrostatic_pressure_error", "with": {...}}
// Each is a function of the world, with its own state across samples, made
// from the column's "with" parameters; the validation cases judge them
// through the scene's `metrics` like any other history.
#pragma once

#include "../json_reader.hpp"

#include <plab_host/world.hpp>

#include <functional>
#include <map>
#include <string>

namespace plab {

using Measurement = std::function<double(const World&)>;
// `with` is the column's "with" object (path scene.histories.record[k].with),
// read with Node so that errors name the path; the world is fully loaded.
using MeasurementFactory = std::function<Measurement(const Node& with, const World& w)>;

struct MeasurementInfo {
    std::string doc;  // one line: what it measures, its unit, its parameters
    MeasurementFactory make;
};

// Every measurement, by name (measurements/*.cpp add theirs in
// register_measurements()).
const std::map<std::string, MeasurementInfo>& measurements();

// The group named by with.group; an error naming the path and the scene's
// groups when there is none of that name.
int measured_group(const Node& with, const World& w);

// One register_*() per file of measurements/, called by measurements().
void register_sph_measurements(std::map<std::string, MeasurementInfo>& into);
void register_coupling_measurements(std::map<std::string, MeasurementInfo>& into);
void register_bonded_measurements(std::map<std::string, MeasurementInfo>& into);
void register_structure_measurements(std::map<std::string, MeasurementInfo>& into);
void register_granular_measurements(std::map<std::string, MeasurementInfo>& into);

} // namespace plab
