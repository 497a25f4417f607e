// The hypoelastic SPH solid (physics/sph_solid; Islam 2023 eqs. 12-20):
// the Jaumann rate rotates a stress without changing it (eq. 17,
// objectivity), the principal decomposition behind the artificial stress,
// a uniformly stretched block carries Hooke's stress (with the kernel
// correction, eq. 20, also at its free edges and corners), a rigidly rotating block
// gets no deviatoric stress, the pair forces conserve momentum, in 2D and
// 3D; a Poisson's ratio of 0.5 is refused naming its path and range.
#include "simulation.hpp"

#include <plab/sph_solid/elasticity.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using namespace plab;
using sph_solid::SymTensor;
using sph_solid::Tensor;

namespace {

double max_abs_difference(const SymTensor& a, const SymTensor& b) {
    return std::max({std::fabs(a.xx - b.xx), std::fabs(a.yy - b.yy), std::fabs(a.zz - b.zz), std::fabs(a.xy - b.xy),
                     std::fabs(a.yz - b.yz), std::fabs(a.zx - b.zx)});
}

// Q S Qᵀ for the rotation by angle t about the unit axis (Rodrigues)
SymTensor rotated(const SymTensor& s, const Vec3& axis, double t) {
    const double c = std::cos(t), sn = std::sin(t);
    const double u[3] = {axis.x, axis.y, axis.z};
    double q[3][3];
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
            const int e = 3 - a - b;  // the third index when a != b
            const double cross = a == b ? 0.0 : ((b - a + 3) % 3 == 1 ? -1.0 : 1.0) * u[e];
            q[a][b] = (a == b ? c : 0.0) + (1 - c) * u[a] * u[b] + sn * cross;
        }
    double out[3][3];
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
            out[a][b] = 0;
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) out[a][b] += q[a][i] * sph::component(s, i, j) * q[b][j];
        }
    return {out[0][0], out[1][1], out[2][2], out[0][1], out[1][2], out[2][0]};
}

} // namespace

TEST_CASE("sph_solid: the Jaumann rate turns a stress with a rigid spin and creates none", "[sph_solid]") {
    const double shear = 1e6, omega = 2.0;
    const Vec3 axis = Vec3{1, 2, 2} / 3.0;  // a unit axis off the coordinate axes
    Tensor spin;                            // l = ω [axis]×: v = ω axis × x
    spin.m[0][1] = -omega * axis.z; spin.m[0][2] = omega * axis.y;
    spin.m[1][0] = omega * axis.z;  spin.m[1][2] = -omega * axis.x;
    spin.m[2][0] = -omega * axis.y; spin.m[2][1] = omega * axis.x;
    // no deviatoric stress from a spin alone
    const SymTensor none = sph_solid::jaumann_rate(SymTensor{}, spin, shear);
    CHECK(max_abs_difference(none, SymTensor{}) == 0.0);
    // a stress carried through a quarter turn by the rate (RK4) is the
    // stress rotated, S(t) = Q S0 Qᵀ
    const SymTensor s0{3e5, -1e5, -2e5, 4e4, -7e4, 1.5e5};
    SymTensor s = s0;
    const double t_end = 0.5 * M_PI / omega;
    const int steps = 400;
    const double dt = t_end / steps;
    const auto rate = [&](const SymTensor& x) { return sph_solid::jaumann_rate(x, spin, shear); };
    for (int k = 0; k < steps; ++k) {
        const SymTensor k1 = rate(s), k2 = rate(s + 0.5 * dt * k1), k3 = rate(s + 0.5 * dt * k2), k4 = rate(s + dt * k3);
        s = s + (dt / 6) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    }
    CHECK(max_abs_difference(s, rotated(s0, axis, omega * t_end)) <= 1e-8 * 3e5);
    // ... whereas the rate without its spin terms leaves it as it was, wrong by the rotation
    CHECK(max_abs_difference(s0, rotated(s0, axis, omega * t_end)) > 0.1 * 3e5);
}

TEST_CASE("sph_solid: principal stresses rebuild the tensor, and artificial stress acts on tension only", "[sph_solid]") {
    const SymTensor s{3e5, -1e5, -2e5, 4e4, -7e4, 1.5e5};
    const sph_solid::Principal p = sph_solid::principal(s);
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
            double rebuilt = 0;
            for (int k = 0; k < 3; ++k) rebuilt += p.q[a][k] * p.value[k] * p.q[b][k];
            CHECK(rebuilt == Approx(sph::component(s, a, b)).margin(1e-9 * 3e5));
        }
    // uniaxial tension along x: R = -ε σ/ρ² along x only; compression gives none
    const double rho = 1000, eps = 0.3;
    const SymTensor r = sph_solid::artificial_stress(SymTensor{2e5, -1e5, 0, 0, 0, 0}, rho, eps);
    CHECK(r.xx == Approx(-eps * 2e5 / (rho * rho)));
    CHECK(r.yy == 0.0);
    const SymTensor c = sph_solid::artificial_stress(SymTensor{-2e5, -1e5, -1e5, 0, 0, 0}, rho, eps);
    CHECK(max_abs_difference(c, SymTensor{}) == 0.0);
}

namespace {

constexpr double kE = 2e6, kNu = 0.3, kRho = 1000, kDp = 0.002;

// A block of SPH solid, 10 particles a side (6 in 3D), every particle fixed
// and moving with the velocity `profile` (expressions of x, y, z) for
// `cycles` steps of dt.
json moving_block(int dim, const json& profile, int cycles, double dt, bool fixed = true) {
    const int n = dim == 2 ? 10 : 6;
    const double side = n * kDp;
    const json box = dim == 2 ? json{{"min", {0, 0}}, {"max", {side, side}}}
                              : json{{"min", {0, 0, 0}}, {"max", {side, side, side}}};
    json body = {{"type", "lattice"}, {"group", "solid"}, {"packing", dim == 2 ? "square" : "cubic"}, {"box", box},
                 {"radius", kDp / 2}, {"spacing", kDp}, {"mass", kRho * std::pow(kDp, dim)}, {"fix", {"rotation"}}};
    const json all = dim == 2 ? json{{"min", {-1, -1}}, {"max", {1, 1}}} : json{{"min", {-1, -1, -1}}, {"max", {1, 1, 1}}};
    json set = {{"region", all}, {"velocity_profile", profile}};
    if (fixed) set["fix"] = {"all"};
    return {{"dimension", dim},
            {"plugins", {"sph_solid"}},
            {"bodies", {body}},
            {"materials", {{"steel", {{"groups", {"solid"}}, {"rest_density", kRho}, {"youngs_modulus", kE},
                                      {"poissons_ratio", kNu}, {"smoothing_length", 1.3 * kDp},
                                      {"particle_spacing", kDp}}}}},
            {"contact_models", {{{"groups", {"solid", "solid"}}, {"model", "sph_solid"}, {"properties", {{"alpha", 0.0}}}}}},
            {"passes", {{{"name", "sph_solid_stress"}, {"material", "steel"}, {"properties", {{"artificial_stress", 0.0}}}}}},
            {"timestep", {{"fixed", dt}}},
            {"commands", {{{"set", set}}, {{"cycle", cycles}}}}};
}

SymTensor field_tensor(const World& w, const std::string& prefix, std::size_t i) {
    const auto at = [&](const char* c) { return w.fields.column(w.fields.index(prefix + c))[i]; };
    return {at("_xx"), at("_yy"), at("_zz"), at("_xy"), at("_yz"), at("_zx")};
}

} // namespace

TEST_CASE("sph_solid: a uniformly stretched block carries Hooke's stress, at its edges too", "[sph_solid]") {
    const double bulk = kE / (3 * (1 - 2 * kNu)), shear = kE / (2 * (1 + kNu));
    const double rate = 1.0, dt = 1e-5;  // 1/s: a strain of 1e-3 in 100 steps
    const int cycles = 100;
    for (int dim : {2, 3}) {
        INFO("dim " << dim);
        Simulation sim(moving_block(dim, dim == 2 ? json{"1.0 * x", "0"} : json{"1.0 * x", "0", "0"}, cycles, dt));
        sim.set_quiet(true);
        sim.run();
        const World& w = sim.world();
        // uniaxial strain along x: the velocity field stretches by (1 + rate t);
        // l = rate/(1 + rate t) integrates to ln(1 + rate t)
        const double strain = std::log1p(rate * cycles * dt);
        for (std::size_t i = 0; i < w.bodies.size(); ++i) {
            INFO("particle " << i << " at " << w.bodies.position[i].transpose());
            // deviatoric stress 2G (2/3, -1/3, -1/3) ε, corrected gradients being exact for a linear field
            // (the explicit steps integrate ln(1 + rate t) to 1e-5 of it)
            const SymTensor s = field_tensor(w, "sph_solid_deviatoric_stress", i);
            const SymTensor expected{2 * shear * 2 * strain / 3, -2 * shear * strain / 3, -2 * shear * strain / 3, 0, 0, 0};
            CHECK(max_abs_difference(s, expected) <= 1e-5 * 2 * shear * strain);
            // Hooke: σ_xx = (K + 4G/3) ε, σ_yy = σ_zz = (K - 2G/3) ε, to first order in ε
            // (p = K (ρ/ρ0 - 1) = -K ε/(1 + ε): relative error ε/2 = 5e-4)
            const SymTensor sigma = field_tensor(w, "sph_solid_stress", i);
            CHECK(sigma.xx == Approx((bulk + 4 * shear / 3) * strain).epsilon(2e-3));
            CHECK(sigma.yy == Approx((bulk - 2 * shear / 3) * strain).epsilon(2e-3));
            CHECK(sigma.zz == Approx((bulk - 2 * shear / 3) * strain).epsilon(2e-3));
        }
    }
}

TEST_CASE("sph_solid: a rigidly rotating block gets no deviatoric stress (objectivity)", "[sph_solid]") {
    const double omega = 1.0, dt = 1e-5;
    const int cycles = 100;  // a turn of 1e-3 rad
    const double shear = kE / (2 * (1 + kNu));
    for (int dim : {2, 3}) {
        INFO("dim " << dim);
        // v = ω e_z × (x - c) (2D), ω (e_x + e_y + e_z)/√3 × (x - c) (3D), c the block's centre
        const double c = 0.5 * (dim == 2 ? 10 : 6) * kDp;
        const std::string cs = std::to_string(c), w = std::to_string(omega), w3 = std::to_string(omega / std::sqrt(3.0));
        const json profile = dim == 2 ? json{"-" + w + " * (y - " + cs + ")", w + " * (x - " + cs + ")"}
                                      : json{w3 + " * ((y - " + cs + ") - (z - " + cs + "))",
                                             w3 + " * ((z - " + cs + ") - (x - " + cs + "))",
                                             w3 + " * ((x - " + cs + ") - (y - " + cs + "))"};
        Simulation sim(moving_block(dim, profile, cycles, dt));
        sim.set_quiet(true);
        sim.run();
        const World& world = sim.world();
        // the particles move on straight lines (their velocities are held), which
        // stretches the block by (ω t)²/2 = 5e-7; a velocity gradient with a
        // symmetric part of the spin's size would give 2G ω t = 2G 1e-3
        for (std::size_t i = 0; i < world.bodies.size(); ++i) {
            INFO("particle " << i);
            CHECK(max_abs_difference(field_tensor(world, "sph_solid_deviatoric_stress", i), SymTensor{}) <=
                  1e-3 * 2 * shear * omega * cycles * dt);
        }
    }
}

TEST_CASE("sph_solid: pair forces conserve linear momentum to round-off", "[sph_solid]") {
    for (int dim : {2, 3}) {
        INFO("dim " << dim);
        // a free block, every particle with its own velocity: it vibrates and stresses build
        const json profile = dim == 2 ? json{"0.3 * sin(2000 * x + 700 * y)", "0.2 * cos(1500 * x - 900 * y)"}
                                      : json{"0.3 * sin(2000 * x + 700 * y)", "0.2 * cos(1500 * x - 900 * z)",
                                             "0.1 * sin(800 * z + 1300 * y)"};
        Simulation sim(moving_block(dim, profile, 0, 1e-5, false));
        sim.set_quiet(true);
        sim.run();  // the velocities set
        World& w = sim.world();
        const auto momentum = [&]() {
            Vec p = Vec::Zero();
            for (std::size_t i = 0; i < w.bodies.size(); ++i) p += w.bodies.mass[i] * w.bodies.velocity[i];
            return p;
        };
        double scale = 0;
        for (std::size_t i = 0; i < w.bodies.size(); ++i) scale += w.bodies.mass[i] * w.bodies.velocity[i].norm();
        const Vec p0 = momentum();
        for (int k = 0; k < 200; ++k) w.step();
        double stress = 0;
        for (std::size_t i = 0; i < w.bodies.size(); ++i)
            stress = std::max(stress, std::fabs(field_tensor(w, "sph_solid_stress", i).xx));
        CHECK(stress > 1e3);  // the block is stressed: the forces are not trivially zero
        CHECK((momentum() - p0).norm() <= 1e-12 * scale);
    }
}

TEST_CASE("sph_solid: a Poisson's ratio of 0.5 is refused, naming the path and the range", "[sph_solid][scene]") {
    json scene = moving_block(2, json{"0", "0"}, 1, 1e-5);
    scene["materials"]["steel"]["poissons_ratio"] = 0.5;
    CHECK_THROWS_WITH(Simulation(scene), Catch::Matchers::Contains("poissons_ratio") &&
                                             Catch::Matchers::Contains("0.5"));
}
