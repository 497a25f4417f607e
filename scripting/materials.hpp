// Scene materials (`scene.materials`): constants stated once per group and
// given by the loader to the contact models and passes that use them. A
// weakly compressible SPH fluid otherwise repeats rho0, c0, gamma, h and the
// kernel in the `sph` model and in every pass (docs/scene-format.md,
// docs/sph.md).
//
//   "materials": {"water": {"groups": ["fluid", "boundary"],
//                           "rest_density": 1000, "speed_of_sound": 19.8, ...}}
//
// What a scene material can give is declared by the plug-ins: a package
// registers a material (abi.h plab_material_desc, e.g. the SPH package's
// "sph_fluid": rest_density, speed_of_sound, gamma, smoothing_length, kernel,
// expected_max_speed), and a model or pass that names it in its description
// takes from a scene material the values of those of its properties that the
// package material declares, and no others. A model or pass that names no
// material takes nothing from the scene's materials.
//
// A contact rule takes the materials of the groups it names; a pass names
// its material (`"material": "water"`). When the two sides of a rule have
// materials with different values of a property, the property's mixing rule
// (abi.h PLAB_MIX_*, e.g. kn harmonic: 2 a b/(a + b)) gives the contact's
// value; a property without one (mixing none) is then an error naming both
// paths. A value given explicitly that
// differs from the material's is an error naming both JSON paths; a material
// key that no model or pass using the material takes is an error (a typo
// would otherwise be silently ignored). Properties named gravity_x/y/z are
// filled from the scene's `gravity` the same way. This is a loader feature:
// plug-ins see ordinary property values.
//
// The speed of sound of a weakly compressible fluid follows from the flow:
// `"expected_max_speed"` is a number (m/s), `{"speed": v}` (a moving wall or
// piston) or `{"dam_break_height": H}` (2 sqrt(|g| H), the surge tip of a
// collapsing column, Ritter's shallow-water solution), and
// `"speed_of_sound": "auto"` is 10 x it (Monaghan 1994: Mach 0.1 keeps the
// density error near 1 %); a number below 10 x it is refused. What set c0 is
// kept for the run summary and `plab check` (speed_of_sound_report()).
#pragma once

#include "json_reader.hpp"

#include <plab/abi.h>
#include <plab_host/world.hpp>

#include <string>
#include <vector>

namespace plab {

class Materials {
public:
    // Reads scene.materials; the groups must exist (load after bodies, walls).
    void load(const Node& n, const World& w);
    bool empty() const { return materials_.empty(); }
    // Index of the material of a group, -1: none.
    int of_group(int group) const;
    // Index of a material by the name at node n (a pass's "material").
    int find(const Node& n) const;

    // Fills `values` (in the declaration order of `props`) for the keys that
    // `owner.properties` does not give: the properties that the model's or
    // pass's package material (`material`, nullptr: none) declares from the
    // materials of each side of a contact rule (`sides`: one or two lists of
    // material indices; a pass has one), mixed by the property's rule where
    // the two sides differ; then gravity_x/y/z from the scene gravity.
    // Explicit values must agree. `groups`: the scene's group names, for
    // group properties.
    void fill(const Node& owner, const std::vector<std::vector<int>>& sides, const plab_property_desc* props,
              uint32_t count, const plab_material_desc* material, const Vec& gravity,
              const std::vector<std::string>& groups, std::vector<double>& values);
    // A key of a material that no user declared: an error naming its path.
    void check_all_used() const;
    // Per material with a speed of sound: its value, the rule that set it
    // and from what numbers (summary.json "speed_of_sound", plab check).
    const json& speed_of_sound_report() const { return sound_report_; }

private:
    struct Material {
        std::string name, path;
        json values;  // the material object, speed_of_sound and expected_max_speed as numbers
        std::vector<int> groups;
        std::vector<std::string> used;
        // the keys its users could take (their properties that their
        // package material declares), for the message about a key none takes
        std::vector<std::string> takeable;
    };
    std::vector<Material> materials_;
    std::vector<int> group_material_;
    json sound_report_ = json::array();
    void resolve_speed_of_sound(const Node& m, const Vec& gravity, Material& mat);
};

} // namespace plab
