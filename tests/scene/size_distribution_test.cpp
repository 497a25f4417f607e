// Radius distributions of a random fill (scripting/size_distribution.hpp,
// issue 36): 20 000 draws against each distribution's own statistics, the
// number and mass weightings, a sieve curve's mass passing, and the fill
// that places exactly the radii drawn. Tolerances: a few standard errors of
// 20 000 draws.
#include "size_distribution.hpp"
#include "simulation.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <vector>

using namespace plab;
using Catch::Matchers::Contains;

namespace {

constexpr long kDraws = 20000;

std::vector<double> draws(const json& radius, int dim = 3, const std::string& dir = ".") {
    const SizeDistribution d(Node(radius, "scene.bodies[0].radius"), dim, dir);
    Rng rng(42);
    std::vector<double> r;
    for (long k = 0; k < kDraws; ++k) r.push_back(d.draw(rng));
    return r;
}

double mean_of(const std::vector<double>& x) { return std::accumulate(x.begin(), x.end(), 0.0) / double(x.size()); }
double std_of(const std::vector<double>& x) {
    const double m = mean_of(x);
    double s = 0;
    for (double v : x) s += (v - m) * (v - m);
    return std::sqrt(s / double(x.size() - 1));
}
// the mass fraction of the draws at most r (mass ∝ r^dim)
double mass_passing(const std::vector<double>& x, double r, int dim) {
    double below = 0, total = 0;
    for (double v : x) {
        const double m = std::pow(v, dim);
        total += m;
        if (v <= r) below += m;
    }
    return below / total;
}

std::string refused(const json& radius) {
    try {
        SizeDistribution(Node(radius, "scene.bodies[0].radius"), 3, ".");
    } catch (const std::exception& e) {
        return e.what();
    }
    return "";
}

} // namespace

TEST_CASE("normal and lognormal radii have the mean, spread and median asked for", "[scene][sizes]") {
    const auto n = draws({{"distribution", "normal"}, {"mean", 1e-3}, {"std", 1e-4}, {"min", 6e-4}, {"max", 1.4e-3}});
    CHECK(mean_of(n) == Approx(1e-3).epsilon(0.003));  // (4 sigma either side: the truncation moves neither)
    CHECK(std_of(n) == Approx(1e-4).epsilon(0.02));
    CHECK(*std::min_element(n.begin(), n.end()) >= 6e-4);
    auto l = draws({{"distribution", "lognormal"}, {"median", 2e-3}, {"sigma", 0.3}, {"min", 5e-4}, {"max", 8e-3}});
    std::vector<double> logs;
    for (double v : l) logs.push_back(std::log(v));
    std::nth_element(l.begin(), l.begin() + kDraws / 2, l.end());
    CHECK(l[kDraws / 2] == Approx(2e-3).epsilon(0.02));
    CHECK(std_of(logs) == Approx(0.3).epsilon(0.02));
    const auto u = draws({{"distribution", "uniform"}, {"min", 1e-3}, {"max", 2e-3}});
    CHECK(mean_of(u) == Approx(1.5e-3).epsilon(0.005));
}

TEST_CASE("discrete radii follow their fractions by number, or by mass (weighted 1/r^3, 1/r^2 in 2D)", "[scene][sizes]") {
    const json radii = {1e-3, 2e-3};
    const auto by_number = draws({{"distribution", "discrete"}, {"radii", radii}, {"fractions", {0.25, 0.75}}});
    CHECK(std::count(by_number.begin(), by_number.end(), 1e-3) / double(kDraws) == Approx(0.25).epsilon(0.03));
    for (int dim : {2, 3}) {
        INFO("dim " << dim);
        const auto by_mass = draws({{"distribution", "discrete"}, {"radii", radii}, {"fractions", {0.5, 0.5}}, {"by", "mass"}}, dim);
        CHECK(mass_passing(by_mass, 1e-3, dim) == Approx(0.5).epsilon(0.03));
    }
    CHECK_THAT(refused({{"distribution", "discrete"}, {"radii", radii}, {"fractions", {0.5, 0.6}}}),
               Contains("scene.bodies[0].radius.fractions") && Contains("add up to 1.1"));
}

TEST_CASE("a sieve curve's radii pass each sieve with the curve's mass fraction", "[scene][sizes]") {
    const auto dir = std::filesystem::temp_directory_path() / "plab_sieve_test";
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "gradation.csv") << "# sieve diameter (m), percent passing\nd,passing\n0.002,0\n0.004,30\n0.008,80\n0.016,100\n";
    const auto r = draws({{"distribution", "sieve"}, {"file", "gradation.csv"}, {"diameter_column", 0}, {"passing_column", 1}}, 3,
                         dir.string());
    CHECK(mass_passing(r, 0.002, 3) == Approx(0.30).margin(0.02));  // radius = diameter / 2
    CHECK(mass_passing(r, 0.004, 3) == Approx(0.80).margin(0.02));
    CHECK(*std::min_element(r.begin(), r.end()) >= 0.001);
    CHECK(*std::max_element(r.begin(), r.end()) <= 0.008);
    std::ofstream(dir / "bad.csv") << "0.002,10\n0.004,100\n";
    CHECK_THAT(refused({{"distribution", "sieve"}, {"file", (dir / "bad.csv").string()}, {"diameter_column", 0}, {"passing_column", 1}}),
               Contains("scene.bodies[0].radius.file") && Contains("pass 0 at its smallest sieve"));
}

TEST_CASE("a random fill with a distribution places the radii drawn, largest first, the same for the same seed", "[scene][sizes]") {
    auto fill = [](long seed) {
        json scene = json::parse(R"({"dimension": 2, "commands": [],
            "bodies": [{"type": "random_fill", "box": {"min": [0, 0], "max": [0.1, 0.1]}, "count": 300, "density": 2500,
                        "radius": {"distribution": "lognormal", "median": 0.001, "sigma": 0.4, "min": 0.0004, "max": 0.003}}]})");
        scene["bodies"][0]["seed"] = seed;
        Simulation sim(scene);
        return sim.world().bodies.radius;
    };
    const std::vector<double> a = fill(5), b = fill(5), c = fill(6);
    REQUIRE(a.size() == 300);
    CHECK(std::is_sorted(a.begin(), a.end(), std::greater<>()));
    CHECK(a == b);
    CHECK(a != c);
    CHECK_THAT(refused({{"distribution", "normal"}, {"mean", 1e-3}, {"std", 1e-4}, {"min", 2e-3}, {"max", 3e-3}}),
               Contains("scene.bodies[0].radius.min") && Contains("4 standard deviations"));
}

namespace {

// The balls' volume over the box's (2D: areas) after a fill of `body`.
double filled_fraction(json body, int dim) {
    json scene = {{"dimension", dim}, {"commands", json::array()}, {"bodies", {body}}};
    Simulation sim(scene);
    double balls = 0;
    for (double r : sim.world().bodies.radius) balls += dim == 2 ? M_PI * r * r : 4.0 / 3.0 * M_PI * r * r * r;
    return balls / (dim == 2 ? 0.01 : 0.001);
}

json fill_to(double phi, const json& radius, int dim) {
    return {{"type", "random_fill"}, {"box", {{"min", json::array({0, 0, 0})}, {"max", json::array({0.1, 0.1, 0.1})}}},
            {"solid_fraction", phi}, {"radius", radius}, {"density", 2500}, {"seed", 3}};
}

} // namespace

TEST_CASE("a random fill to a solid fraction holds that fraction of the box, by one ball at most", "[scene][sizes]") {
    for (int dim : {2, 3}) {
        INFO(dim << "D");
        const double phi = dim == 2 ? 0.4 : 0.25, r_max = 0.003;
        const double one_ball = (dim == 2 ? M_PI * r_max * r_max / 0.01 : 4.0 / 3.0 * M_PI * std::pow(r_max, 3) / 0.001);
        json box_2d = fill_to(phi, {{"distribution", "uniform"}, {"min", 0.002}, {"max", r_max}}, dim);
        if (dim == 2) box_2d["box"] = {{"min", {0, 0}}, {"max", {0.1, 0.1}}};
        const double with_sizes = filled_fraction(box_2d, dim);
        CHECK(with_sizes >= phi);
        CHECK(with_sizes < phi + one_ball);
        // one radius: the count whose volume is nearest the fraction
        json single = box_2d;
        single["radius"] = r_max;
        CHECK(filled_fraction(single, dim) == Approx(phi).margin(one_ball / 2));
    }
    json dense = fill_to(0.6, 0.001, 2);
    dense["box"] = {{"min", {0, 0}}, {"max", {0.1, 0.1}}};
    CHECK_THROWS_WITH(Simulation(json{{"dimension", 2}, {"bodies", {dense}}}),
                      Contains("scene.bodies[0].solid_fraction") && Contains("(0, 0.50]") && Contains("jams"));
    json both = dense;
    both["count"] = 10;
    CHECK_THROWS_WITH(Simulation(json{{"dimension", 2}, {"bodies", {both}}}), Contains("one of: count, solid_fraction"));
}
