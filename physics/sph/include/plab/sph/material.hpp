// The SPH package's material, "sph_fluid" (abi.h plab_material_desc): the
// constants of a weakly compressible fluid that the `sph` model, the SPH
// passes and the SPH–DEM coupling plug-ins share. A scene states them once
// per fluid, for its groups,
//
//   "materials": {"water": {"groups": ["fluid", "boundary"], "rest_density": 1000,
//                           "speed_of_sound": 19.8, "gamma": 7, "smoothing_length": 0.0033,
//                           "kernel": "wendland_c2"}}
//
// and a model or pass that takes its shared properties from this material
// (`using material = plab::sph::FluidMaterial;`, plab/contact_model.hpp)
// gets the values of those it declares among its own properties, with these
// descriptions:
//
//   static constexpr plab_property_desc properties[] = {
//       plab::sph::fluid::smoothing_length, plab::sph::fluid::kernel, ..., my_own_property};
//
// The host refuses a model or pass that declares one of these keys
// differently (kind, unit, default, range, mixing, choices). Part of the
// SDK (<plab/sph/material.hpp>).
#ifndef PLAB_SPH_MATERIAL_HPP
#define PLAB_SPH_MATERIAL_HPP

#include <plab/contact_model.hpp>
#include <plab/sph/kernels.hpp>

#include <limits>

namespace plab::sph {

namespace fluid {

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

inline constexpr plab_property_desc smoothing_length = plab::prop::number(
    "smoothing_length", "smoothing length h", "m", 0.005, 0.0, kInfinity, PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE,
    "kernel support is 2h (Wendland C2, cubic spline) or 3h (quintic)");
inline constexpr plab_property_desc kernel = plab::prop::choice(
    "kernel", "kernel function", kernel_names, 1,
    "wendland_c2: Wendland C2 (eq. 12, the thesis' choice); cubic: cubic spline (eq. 11); quintic: quintic spline");
inline constexpr plab_property_desc rest_density = plab::prop::number(
    "rest_density", "reference density rho0", "kg/m3", 1000.0, 0.0, kInfinity, PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE,
    "rho0 of the equation of state and the viscous step limit; the density of a body whose density field is not set");
inline constexpr plab_property_desc speed_of_sound = plab::prop::number(
    "speed_of_sound", "numerical speed of sound c0", "m/s", 20.0, 0.0, kInfinity, PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE,
    "B = rho0 c0^2/gamma of the equation of state, the CFL limit and Monaghan viscosity; about 10 x the largest flow "
    "speed (a scene material: \"auto\" with expected_max_speed)");
inline constexpr plab_property_desc gamma = plab::prop::number(
    "gamma", "polytropic exponent", "1", 7.0, 0.0, kInfinity, PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE,
    "Tait exponent of the equation of state, 7 for water");
inline constexpr plab_property_desc expected_max_speed = plab::prop::number(
    "expected_max_speed", "largest flow speed the scene expects", "m/s", 0.0, 0.0, kInfinity, PLAB_MAX_EXCLUSIVE,
    "from the material (2 sqrt(g H) for a dam break of height H); only for the advice when the density band "
    "is left; 0: not stated");

} // namespace fluid

struct FluidMaterial {
    static constexpr const char* name = "sph_fluid";
    static constexpr const char* doc =
        "a weakly compressible SPH fluid: rest density, speed of sound, Tait exponent, smoothing length and kernel, "
        "and the flow speed the scene expects (docs/sph.md)";
    static constexpr plab_property_desc properties[] = {
        fluid::rest_density, fluid::speed_of_sound, fluid::gamma,
        fluid::smoothing_length, fluid::kernel, fluid::expected_max_speed,
    };
};

} // namespace plab::sph

#endif // PLAB_SPH_MATERIAL_HPP
