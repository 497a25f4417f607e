// Scene generators: single balls, regular lattices, random non-overlapping
// fills, and walls; plus reading a plug-in's properties from a scene.
#pragma once

#include "json_reader.hpp"

#include <plab/abi.h>
#include <plab_host/world.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace plab {

struct Box {
    Vec lo, hi;
    bool overlaps(const Box& o, int dim) const {
        for (int c = 0; c < dim; ++c)
            if (hi[c] <= o.lo[c] || o.hi[c] <= lo[c]) return false;
        return true;
    }
};

// Deterministic across platforms (std:: distributions are not).
class Rng {
public:
    explicit Rng(std::uint64_t seed) : s_(seed * 0x9E3779B97F4A7C15ull + 1) {}
    std::uint64_t next() {  // splitmix64
        std::uint64_t z = (s_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    double uniform(double a, double b) { return a + (b - a) * double(next() >> 11) * 0x1.0p-53; }
    // (what a checkpoint keeps of it)
    std::uint64_t state() const { return s_; }
    void set_state(std::uint64_t s) { s_ = s; }

private:
    std::uint64_t s_;
};

// The scene's "limits": what a generator may make before it is refused.
struct GeneratorLimits {
    long max_bodies = 10000000;  // ~10 GB at about 1 kB a ball
};

// The cells of a lattice's packing, for a calibration that gives the
// lattice the material's density over them (scene_loader.cpp).
struct LatticeCells {
    int group = -1;
    std::string packing;     // "square", "hexagonal", "cubic", "hcp"
    double radius = 0;
    double cell_volume = 0;  // per ball: its Voronoi cell, m^2 (2D, per unit thickness) or m^3
    std::string note;        // a `solid` lattice: its counts and equivalent size, for the log
    std::size_t first = 0, end = 0;  // its balls' indices [first, end) when made
    std::string path;        // its bodies[i]
    bool density_set = false;  // a calibration has given it the material's density over its cells
};

// Adds the balls of one `bodies[i]` entry; returns the region it filled
// (lattice and random fill) so overlapping regions can be refused; a
// lattice also describes its cells in `cells`.
// (`scene_dir`: where the files a generator reads, a sieve curve, are looked for)
std::optional<Box> generate_bodies(const Node& n, World& w, const GeneratorLimits& limits = {}, LatticeCells* cells = nullptr,
                                   const std::string& scene_dir = ".");
// A wall; a mesh wall's relative "file" is found in `scene_dir`.
void generate_wall(const Node& n, World& w, const std::string& scene_dir = ".");
// Refuses two facets in the same place (the walls at `walls`, by index).
void check_coincident_facets(const Node& walls, const World& w);

// Property values in declaration order, as the plug-in sees them: scene
// values checked by kind (abi.h PLAB_KIND_*: a number in its range, a whole
// number, true/false, a choice's name, a group's name from `groups`, the
// scene's group names in index order), defaults for the rest; an unknown key
// lists the known ones. Refusals name the JSON path, the value and the valid
// set; an old numeric code of a bool, choice or group names its spelling.
std::vector<double> read_properties(const Node& owner, const plab_property_desc* props, uint32_t count,
                                    const std::string& what, const std::vector<std::string>& groups);
// One property value checked by its kind.
double read_property(const Node& v, const plab_property_desc& d, const std::vector<std::string>& groups);
// A group property that must name a group and still holds -1 once the scene
// and the materials are read: an error at owner.properties.KEY.
void check_required_properties(const Node& owner, const plab_property_desc* props, uint32_t count,
                               const std::vector<double>& values, const std::string& what,
                               const std::vector<std::string>& groups);
// The value as a scene writes it: a number, true/false, a choice's name, a
// group's name or "none".
std::string property_value_text(const plab_property_desc& d, double value, const std::vector<std::string>& groups);

// Degrees of freedom named in a "fix" list ("x", "y", "z", "rx", "ry", "rz",
// "translation", "rotation", "all").
std::uint8_t read_fixity(const Node& n);
// An entry's "angular_velocity" (2D: a number, the spin about z; absent: zero).
Vec read_angular_velocity(const Node& n, int dim);
// A file the scene names, found in the scene's folder unless absolute.
std::string scene_path(const std::string& scene_dir, const std::string& file);

} // namespace plab
