// The host's turn of a model's tangential history (abi.h,
// PLAB_HISTORY_TANGENTIAL): before each call of compute(), every vector a
// model declares to lie in the contact plane (a shear force) is turned into
// its row's current plane, so that no law rotates its own. The arithmetic is
// plab::rotate_into_plane() (vec3.hpp), the one the SDK's test harnesses use.
#pragma once

#include <plab/abi.h>
#include <plab/vec3.hpp>

#include <cstddef>
#include <cstdint>

namespace plab {

namespace detail {
// One tangential vector, at `first` in each of rows [0, n) of history
// (Stride doubles a row; 0: `stride`), turned into the plane of the row's
// unit normal (xyz triples). Masked: only the rows whose active flag is set
// (an inactive row's normal is not computed); the others keep their values.
// (restrict parameters: the compiler proves the columns apart only so, and
// runs the rows a vector at a time.)
template <std::size_t Stride, bool Masked>
void turn_rows(double* __restrict history, std::size_t stride, std::size_t first, const double* __restrict normal,
               const std::uint8_t* __restrict active, std::size_t n) {
    const std::size_t w = Stride ? Stride : stride;
    for (std::size_t a = 0; a < n; ++a) {
        double* h = history + a * w + first;
        const Vec3 v{h[0], h[1], h[2]};
        const Vec3 t = rotate_into_plane(v, {normal[3 * a], normal[3 * a + 1], normal[3 * a + 2]});
        const bool keep = Masked && !active[a];
        h[0] = keep ? v.x : t.x;
        h[1] = keep ? v.y : t.y;
        h[2] = keep ? v.z : t.z;
    }
}
} // namespace detail

// Rows [0, n) of a model's history, `stride` doubles a row, with their unit
// normals: each tangential vector of model d turned into its row's contact
// plane; where `active` is given, only in the rows it flags.
inline void turn_tangential_history(const plab_contact_model_desc& d, double* history, std::size_t stride,
                                    const double* normal, const std::uint8_t* active, std::size_t n) {
    for (std::uint32_t s = 0; s + 2 < d.history_count; ++s) {
        if (!(d.history[s].flags & PLAB_HISTORY_TANGENTIAL)) continue;
        if (active) detail::turn_rows<0, true>(history, stride, s, normal, active, n);
        else if (stride == 3) detail::turn_rows<3, false>(history, 3, s, normal, nullptr, n);  // (a shear force alone)
        else detail::turn_rows<0, false>(history, stride, s, normal, nullptr, n);
    }
}

} // namespace plab
