// Scene materials (`scene.materials`): constants stated once and copied by
// the loader into the same-named properties of the contact models and passes
// that use them. A weakly compressible SPH fluid otherwise repeats rho0, c0,
// gamma, h and the kernel in the `sph` model and in every pass
// (docs/scene-format.md, docs/sph.md).
//
//   "materials": {"water": {"groups": ["fluid", "boundary"],
//                           "rest_density": 1000, "speed_of_sound": 19.8, ...}}
//
// A contact rule takes the materials of the groups it names; a pass names
// its material (`"material": "water"`). A value given explicitly that
// differs from the material's is an error naming both JSON paths; a material
// key that no model or pass using the material declares is an error (a typo
// would otherwise be silently ignored). Properties named gravity_x/y/z are
// filled from the scene's `gravity` the same way. This is a loader feature:
// plug-ins see ordinary property values.
#pragma once

#include "json_reader.hpp"

#include <plab/abi.h>
#include <plab_core/world.hpp>

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
    // `owner.properties` does not give: from the given materials, then from
    // the scene gravity for gravity_x/y/z. Explicit values must agree.
    void fill(const Node& owner, const std::vector<int>& materials, const plab_property_desc* props,
              uint32_t count, const Vec& gravity, std::vector<double>& values);
    // A key of a material that no user declared: an error naming its path.
    void check_all_used() const;

private:
    struct Material {
        std::string name, path;
        const json* values = nullptr;  // the material object (keys other than "groups")
        std::vector<int> groups;
        std::vector<std::string> used;
    };
    std::vector<Material> materials_;
    std::vector<int> group_material_;
};

} // namespace plab
