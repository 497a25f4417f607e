// The host's turn of a model's tangential history (abi.h,
// PLAB_HISTORY_TANGENTIAL): before each call of compute(), every vector a
// model declares to lie in the contact plane (a shear force) is turned into
// its row's current plane, so that no law rotates its own. The arithmetic is
// plab::rotate_into_plane() (vec3.hpp), the one the SDK's test harnesses use.
#pragma once

#include "forces/row_lists.hpp"

#include <plab/abi.h>
#include <plab/vec3.hpp>

#include <cstddef>
#include <cstdint>

namespace plab {

namespace detail {
// One tangential vector, at `first` in rows of history (Stride doubles a
// row; 0: `stride`), turned into the plane of each row's unit normal (xyz
// triples): rows row[0, n) where Listed, else rows 0 to n - 1. The rows go
// in blocks, copied into one array per component, turned there and copied
// back: the turn then takes whole vectors of rows, where on the rows'
// triples it would shuffle every vector in and out. (restrict parameters:
// the compiler proves the columns apart only so.)
template <std::size_t Stride, bool Listed>
void turn_rows(double* __restrict history, std::size_t stride, std::size_t first, const double* __restrict normal,
               const std::uint32_t* __restrict row, std::size_t n) {
    constexpr std::size_t B = 8;  // rows a block: two vectors of four on AVX2
    const std::size_t w = Stride ? Stride : stride;
    for (std::size_t a0 = 0; a0 < n; a0 += B) {
        const std::size_t m = n - a0 < B ? n - a0 : B;
        double vx[B], vy[B], vz[B], nx[B], ny[B], nz[B];  // the block's vectors and normals
        for (std::size_t r = 0; r < m; ++r) {
            const std::size_t k = Listed ? row[a0 + r] : a0 + r;
            const double *h = history + k * w + first, *nk = normal + 3 * k;
            vx[r] = h[0]; vy[r] = h[1]; vz[r] = h[2];
            nx[r] = nk[0]; ny[r] = nk[1]; nz[r] = nk[2];
        }
        for (std::size_t r = m; r < B; ++r) vx[r] = vy[r] = vz[r] = nx[r] = ny[r] = nz[r] = 0.0;  // (zero stays zero)
        for (std::size_t r = 0; r < B; ++r) {
            const Vec3 t = rotate_into_plane({vx[r], vy[r], vz[r]}, {nx[r], ny[r], nz[r]});
            vx[r] = t.x; vy[r] = t.y; vz[r] = t.z;
        }
        for (std::size_t r = 0; r < m; ++r) {
            double* h = history + (Listed ? row[a0 + r] : a0 + r) * w + first;
            h[0] = vx[r]; h[1] = vy[r]; h[2] = vz[r];
        }
    }
}

// Every tangential vector of model d in the rows turn_rows() takes.
template <bool Listed>
void turn_slots(const plab_contact_model_desc& d, double* history, std::size_t stride, const double* normal,
                const std::uint32_t* row, std::size_t n) {
    for (std::uint32_t s = 0; s + 2 < d.history_count; ++s) {
        if (!(d.history[s].flags & PLAB_HISTORY_TANGENTIAL)) continue;
        if (stride == 3) turn_rows<3, Listed>(history, 3, s, normal, row, n);  // (a shear force alone)
        else turn_rows<0, Listed>(history, stride, s, normal, row, n);
    }
}
} // namespace detail

// Rows [0, n) of a model's history, `stride` doubles a row, with their unit
// normals: each tangential vector of model d turned into its row's contact
// plane; where `active` is given, only in the rows it flags (an inactive
// row's normal is not computed).
inline void turn_tangential_history(const plab_contact_model_desc& d, double* history, std::size_t stride,
                                    const double* normal, const std::uint8_t* active, std::size_t n) {
    if (!active) return detail::turn_slots<false>(d, history, stride, normal, nullptr, n);
    constexpr std::size_t chunk = 512;
    std::uint32_t row[chunk];
    for (std::size_t o = 0; o < n; o += chunk) {
        const std::size_t m = n - o < chunk ? n - o : chunk;
        detail::turn_slots<true>(d, history, stride, normal, row, list_flagged_rows(active + o, m, std::uint32_t(o), row));
    }
}

} // namespace plab
