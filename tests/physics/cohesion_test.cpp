// hertz's simplified JKR cohesion (<plab/dem/cohesion.hpp>, k_c): the
// attractive force is k_c times the contact area of the two overlapping
// circles, it does no net work over an elastic impact, and a ball too slow
// to break free sticks. Driven as the host calls the law (plab::testing::Probe)
// on the library the build ships.
#include <plab/testing.hpp>
#include <plab_host/plugins.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <memory>

namespace {

using plab::testing::Probe;

constexpr double E = 1e8, nu = 0.25;  // a soft solid: the cohesion matters at small overlaps
const double E_eff = E / (2 * (1 - nu * nu));

const plab_contact_model_desc* hertz() {
    static const std::unique_ptr<plab::PluginHost> host = [] {
        auto h = std::make_unique<plab::PluginHost>();
        h->load(std::string(PLAB_PLUGIN_OUTPUT_DIR) + "/plab_hertz.so");
        return h;
    }();
    return host->model("hertz");
}

// The largest surface gap in `steps` steps after a head-on approach at
// `speed`, integrated as Probe::impact does (leapfrog on the gap): a ball
// that sticks never gets further than the cohesion's range, zero.
double largest_gap_after_touch(Probe& p, double speed, double dt, long steps) {
    const double m = p.eff_mass();
    double gap = 0.5 * speed * dt, v = -speed, largest = -1;
    bool touched = false;
    for (long k = 0; k < steps; ++k) {
        v += dt * p.force(gap, {v, 0, 0}, dt).x / m;
        gap += dt * v;
        touched |= gap < 0;
        if (touched) largest = std::max(largest, gap);
    }
    return largest;
}

// the chord's half-length a of two circles of radii r1, r2 whose centres are d apart
double half_chord(double r1, double r2, double d) {
    const double x = (d * d + r1 * r1 - r2 * r2) / (2 * d);  // from centre 1 to the chord
    return std::sqrt(r1 * r1 - x * x);
}

} // namespace

TEST_CASE("hertz cohesion: the attraction is k_c times the contact area, 3D and 2D, ball-ball and ball-wall", "[hertz][cohesion]") {
    const double k_c = 2e5, d = 1e-5;
    for (int dim : {2, 3}) {
        for (bool wall : {false, true}) {
            INFO("dim " << dim << (wall ? ", ball-wall" : ", ball-ball"));
            Probe glued(hertz(), {{"E", E}, {"nu", nu}, {"k_c", k_c}});
            Probe plain(hertz(), {{"E", E}, {"nu", nu}});
            for (Probe* p : {&glued, &plain}) {
                p->dim = dim;
                p->wall = wall;
                p->radius2 = 0.003;  // unequal balls
            }
            const double a = wall ? std::sqrt(2 * glued.radius1 * d - d * d)
                                  : half_chord(glued.radius1, glued.radius2, glued.radius1 + glued.radius2 - d);
            const double area = dim == 2 ? 2 * a : M_PI * a * a;
            const double attraction = plain.force(-d).x - glued.force(-d).x;
            CHECK(attraction == Approx(k_c * area).epsilon(1e-9));
        }
    }
}

TEST_CASE("hertz cohesion is conservative: an elastic impact fast enough to part returns every joule", "[hertz][cohesion]") {
    Probe p(hertz(), {{"E", E}, {"nu", nu}, {"e", 1.0}, {"k_c", 2e5}});
    const plab::testing::Impact im = p.impact(0.5, 1e-8);
    CHECK(im.restitution == Approx(1.0).epsilon(1e-4));  // the potential's trapezoid in the overlap, step 1e-8 s
    p.force(1e-9);
    CHECK(p.outputs().strain_energy == 0.0);  // apart: no potential left
}

TEST_CASE("hertz cohesion: a ball too slow to escape the attraction sticks, a faster one bounces with less speed", "[hertz][cohesion]") {
    // with damping (e = 0.5) the rebound has less energy than the cohesion's well: a slow ball stays
    Probe slow(hertz(), {{"E", E}, {"nu", nu}, {"e", 0.5}, {"k_c", 1e6}});
    CHECK(largest_gap_after_touch(slow, 1e-3, 1e-6, 20000) <= 0.0);  // ~10 contact times of the dry ball: it stays
    Probe fast(hertz(), {{"E", E}, {"nu", nu}, {"e", 0.5}, {"k_c", 1e6}}), dry(hertz(), {{"E", E}, {"nu", nu}, {"e", 0.5}});
    const double e_glued = fast.impact(1.0, 1e-8).restitution, e_dry = dry.impact(1.0, 1e-8).restitution;
    CHECK(e_dry == Approx(0.5).epsilon(1e-3));
    CHECK(e_glued < e_dry);
    CHECK(e_glued > 0.0);
}
