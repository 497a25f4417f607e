// Test harness for contact-model authors: drives a model through the C ABI
// (exactly as the host calls it) for one contact whose geometry the test
// chooses, without the plab kernel. Header-only; for tests, not plug-ins
// (it uses exceptions and std:: containers, which never cross the ABI here
// because model and test live in the same program).
//
//   plab::testing::Probe p(plab::contact_model_desc<Hertz>(), {{"E", 7e10}});
//   // a choice by name: the index its law reads (a bool is 0/1, a group its index)
//   plab::testing::Probe q(desc, {{"dp_mode", plab::testing::choice_index(desc, "dp_mode", "no_tension")}});
//   p.mass1 = 0.01; p.radius1 = 0.005; p.wall = true;
//   plab::Vec3 f = p.force(-1e-6);                  // force on end 2 at 1 um overlap
//   plab::testing::Impact im = p.impact(1.0, 1e-8); // head-on impact at 1 m/s
#ifndef PLAB_TESTING_HPP
#define PLAB_TESTING_HPP

#include <plab/contact_model.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace plab::testing {

struct Impact {
    double duration = 0;     // time from first touch to separation, s
    double max_overlap = 0;  // m
    double restitution = 0;  // separation speed / approach speed
    long steps = 0;          // steps in contact
};

// The index of the choice `name` of the choice property `key` of a model
// (abi.h PLAB_KIND_CHOICE): the value its law reads.
inline double choice_index(const plab_contact_model_desc* d, const std::string& key, const std::string& name) {
    for (uint32_t p = 0; p < d->property_count; ++p) {
        const plab_property_desc& q = d->properties[p];
        if (key != q.key) continue;
        if (q.kind != PLAB_KIND_CHOICE) throw std::invalid_argument("property '" + key + "' is not a choice");
        for (uint32_t c = 0; c < q.choice_count; ++c)
            if (name == q.choices[c]) return double(c);
        throw std::invalid_argument("'" + name + "' is not a choice of property '" + key + "'");
    }
    throw std::invalid_argument("model " + std::string(d->name) + " has no property '" + key + "'");
}

class Probe {
public:
    // Property values: the model's defaults, then `overrides` by key (as the
    // law reads them: a bool 0/1, a choice its index, see choice_index()).
    Probe(const plab_contact_model_desc* desc, const std::vector<std::pair<std::string, double>>& overrides = {})
        : d_(desc) {
        for (uint32_t p = 0; p < d_->property_count; ++p) props_.push_back(d_->properties[p].default_value);
        for (const auto& [key, value] : overrides) {
            const std::size_t p = index_of(key);
            const plab_property_desc& q = d_->properties[p];
            const bool whole = std::floor(value) == value;
            if ((q.kind == PLAB_KIND_BOOL && value != 0 && value != 1) ||
                (q.kind == PLAB_KIND_CHOICE && !(whole && value >= 0 && value < q.choice_count)) ||
                (q.kind == PLAB_KIND_INTEGER && !whole))
                throw std::invalid_argument("value " + std::to_string(value) + " is not a value property '" + key +
                                            "' can take (a bool 0/1, a choice's index, a whole number)");
            props_[p] = value;
        }
        instance_ = d_->create(props_.data());
        reset_history();
    }
    ~Probe() { if (d_->destroy) d_->destroy(instance_); }
    Probe(const Probe&) = delete;
    Probe& operator=(const Probe&) = delete;

    // The two ends (defaults: two 5 mm glass spheres); `wall`: end 2 is a
    // wall facet of infinite mass.
    int dim = 3;
    double radius1 = 0.005, radius2 = 0.005;
    double mass1 = 2500 * 4.0 / 3.0 * M_PI * 0.005 * 0.005 * 0.005, mass2 = mass1;
    bool wall = false;

    double eff_mass() const { return wall ? mass1 : mass1 * mass2 / (mass1 + mass2); }
    double eff_radius() const { return wall ? radius1 : radius1 * radius2 / (radius1 + radius2); }
    void reset_history() {
        history_.assign(d_->history_count + 1, 0.0);
        for (uint32_t h = 0; h < d_->history_count; ++h) history_[h] = d_->history[h].default_value;
    }
    double history(int slot) const { return history_.at(std::size_t(slot)); }

    // One call of the model for a contact at surface gap `gap` (negative:
    // overlap) along `normal` (end 1 -> end 2), relative velocity v2 - v1 at
    // the contact point. Advances the history by `dt` (0: evaluate only).
    // Returns the force on end 2; outputs() holds the rest.
    Vec3 force(double gap, const Vec3& rel_velocity = {}, double dt = 0.0, const Vec3& normal = {1, 0, 0}) {
        const double n[3] = {normal.x, normal.y, normal.z};
        const double v[3] = {rel_velocity.x, rel_velocity.y, rel_velocity.z}, w[3] = {0, 0, 0};
        const double m1 = mass1, m2 = wall ? std::numeric_limits<double>::infinity() : mass2;
        const double r1 = radius1, r2 = wall ? 0.0 : radius2, me = eff_mass(), re = eff_radius();
        const double dist = r1 + r2 + gap;
        const int32_t e1 = 0, e2 = 1;
        const uint8_t active = gap <= d_->activity_range(props_.data()) ? 1 : 0;
        out_ = Outputs{};
        plab_contact_batch b{sizeof(plab_contact_batch)};
        b.dim = uint32_t(dim); b.count = 1; b.end2_is_wall = wall ? 1u : 0u;
        b.history_stride = d_->history_count; b.dt = dt;
        b.end1 = &e1; b.end2 = &e2; b.active = &active;
        b.normal = n; b.gap = &gap; b.distance = &dist; b.rel_velocity = v; b.rel_angular_velocity = w;
        b.radius1 = &r1; b.radius2 = &r2; b.mass1 = &m1; b.mass2 = &m2; b.eff_mass = &me; b.eff_radius = &re;
        b.history = history_.data();
        b.force = out_.force; b.moment1 = out_.moment1; b.moment2 = out_.moment2;
        b.strain_energy = &out_.strain_energy; b.slip_energy = &out_.slip_energy;
        b.dashpot_energy = &out_.dashpot_energy; b.stiffness_translational = &out_.stiffness;
        b.stiffness_rotational = &out_.rotational_stiffness; b.dt_limit = &out_.dt_limit;
        b.break_energy = &out_.break_energy; b.stage = PLAB_STAGE_FORCES;
        if (active) turn_tangential_history(normal);
        if (d_->compute(instance_, props_.data(), &b) != 0) throw std::runtime_error("compute() returned an error");
        return {out_.force[0], out_.force[1], out_.force[2]};
    }

    struct Outputs {
        double force[3] = {0, 0, 0}, moment1[3] = {0, 0, 0}, moment2[3] = {0, 0, 0};
        double strain_energy = 0, slip_energy = 0, dashpot_energy = 0, stiffness = 0, rotational_stiffness = 0;
        double dt_limit = std::numeric_limits<double>::infinity(), break_energy = 0;
    };
    const Outputs& outputs() const { return out_; }

    // A head-on impact at closing speed `speed` (m/s), no gravity, integrated
    // with the host's leapfrog at step `dt` along the relative coordinate
    // gap(t): gap'' = F / m_eff. The model sees the half-step velocity, as in
    // plab. Touch and separation times are interpolated between steps.
    Impact impact(double speed, double dt) {
        reset_history();
        const double m = eff_mass();
        double gap = speed * dt * 0.5, v_half = -speed, t = 0, t_in = -1, max_overlap = 0;
        Impact out;
        for (long k = 0; k < 100000000L; ++k) {
            const double fn = force(gap, {v_half, 0, 0}, dt).x;  // along the normal (x)
            const double v_next = v_half + dt * fn / m;
            const double gap_next = gap + dt * v_next;
            if (t_in < 0 && gap_next < 0) t_in = t + dt * gap / (gap - gap_next);
            if (t_in >= 0) ++out.steps;
            if (t_in >= 0 && gap_next >= 0) {
                out.duration = t + dt * gap / (gap - gap_next) - t_in;
                out.restitution = v_next / speed;
                out.max_overlap = max_overlap;
                return out;
            }
            max_overlap = std::max(max_overlap, -gap_next);
            gap = gap_next;
            v_half = v_next;
            t += dt;
        }
        throw std::runtime_error("the ends never separated (a model with tension or a stuck contact?)");
    }

private:
    // What the host does before each call (abi.h, PLAB_HISTORY_TANGENTIAL):
    // each tangential vector of the history turned into the contact plane.
    void turn_tangential_history(const Vec3& normal) {
        for (uint32_t s = 0; s + 2 < d_->history_count; ++s)
            if (d_->history[s].flags & PLAB_HISTORY_TANGENTIAL) {
                const Vec3 t = rotate_into_plane({history_[s], history_[s + 1], history_[s + 2]}, normal);
                history_[s] = t.x; history_[s + 1] = t.y; history_[s + 2] = t.z;
            }
    }
    std::size_t index_of(const std::string& key) const {
        for (uint32_t p = 0; p < d_->property_count; ++p)
            if (key == d_->properties[p].key) return p;
        throw std::invalid_argument("model " + std::string(d_->name) + " has no property '" + key + "'");
    }
    const plab_contact_model_desc* d_;
    std::vector<double> props_, history_;
    void* instance_ = nullptr;
    Outputs out_;
};

} // namespace plab::testing

#endif // PLAB_TESTING_HPP
