// Lists of the rows of a batch whose flag is set (in range, just left the
// range, active), made without a branch per row: in-range flags follow no
// pattern, so a branch would be mispredicted about every other row.
//
// The scalar loop stores every row and advances the count by its flag; each
// store's address waits for the previous row's flag, a chain one row long
// per iteration (a fifth of the range test on gran3d). Where the compiler
// may use AVX-512, sixteen flags at a time select their rows with a
// compress in a register (vpcompressd; the compress straight to memory is
// microcoded on Zen 4) and a full-width store. The lists are the same
// either way; the vector loop also writes up to a vector's width past the
// end of the list, never past position n of the output.
#pragma once

#include <cstddef>
#include <cstdint>

#if defined(__AVX512F__) && defined(__AVX512BW__) && defined(__AVX512VL__)
#include <immintrin.h>
#define PLAB_ROW_LISTS_AVX512 1
#endif

namespace plab {

// out[0, count) = base + r for each r < n with flag[r] != 0, in order; where
// `value` is given, value_out[0, count) = value[r] of the same rows. The
// outputs hold n entries. Returns count.
inline std::size_t list_flagged_rows(const std::uint8_t* flag, std::size_t n, std::uint32_t base,
                                     std::uint32_t* out, const double* value = nullptr,
                                     double* value_out = nullptr) {
    std::size_t count = 0, r = 0;
#ifdef PLAB_ROW_LISTS_AVX512
    const __m512i lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    for (; r + 16 <= n; r += 16) {
        const __m128i f = _mm_loadu_si128(reinterpret_cast<const __m128i*>(flag + r));
        const __mmask16 m = _mm_test_epi8_mask(f, f);
        const __m512i rows = _mm512_add_epi32(_mm512_set1_epi32(int(base + r)), lane);
        _mm512_storeu_si512(out + count, _mm512_maskz_compress_epi32(m, rows));
        if (value) {
            const __mmask8 lo = __mmask8(m), hi = __mmask8(m >> 8);
            const std::size_t n_lo = std::size_t(__builtin_popcount(lo));
            _mm512_storeu_pd(value_out + count, _mm512_maskz_compress_pd(lo, _mm512_loadu_pd(value + r)));
            _mm512_storeu_pd(value_out + count + n_lo, _mm512_maskz_compress_pd(hi, _mm512_loadu_pd(value + r + 8)));
        }
        count += std::size_t(__builtin_popcount(m));
    }
#endif
    for (; r < n; ++r) {
        out[count] = base + std::uint32_t(r);
        if (value) value_out[count] = value[r];
        count += flag[r] != 0;
    }
    return count;
}

} // namespace plab
