// Basic types of the kernel. Vectors are 3D everywhere; a 2D world keeps
// z = 0 and rotates about z only (LAMMPS' choice: one binary, runtime
// dimension — measured cheaper to maintain than templates on the dimension,
// and the 2D overhead is one unused double per vector).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products
#include <cstdint>
#include <limits>

namespace plab {

using Vec = Eigen::Vector3d;
using BodyId = std::uint64_t;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = 3.14159265358979323846;

// Loops shorter than this run on one thread: below it the fork–join barrier
// costs more than the loop (measured at N = 1e3: 2 threads 1.5x faster than
// 1 on an idle machine, 7x slower on a loaded one). Results do not depend on it.
constexpr std::size_t kParallelMin = 1024;

// Degrees of freedom that can be fixed, as bits.
enum Dof : std::uint8_t { dof_x = 1, dof_y = 2, dof_z = 4, dof_rx = 8, dof_ry = 16, dof_rz = 32, dof_all = 63 };
// Not a DOF: the ball is a pebble of a clump (plab_host/clumps.hpp), moved by
// its clump; the leapfrog neither kicks it nor counts its energy.
constexpr std::uint8_t dof_clumped = 64;
// The rotations a body has in this dimension (2D: about z).
constexpr std::uint8_t rotation_dofs(int dim) { return dim == 2 ? dof_rz : (dof_rx | dof_ry | dof_rz); }

} // namespace plab
