// C++ adapter for passes: plug-in work over bodies in a cycle phase (PySPH's
// equation groups; SPHinXsys' local dynamics). A pass class declares its
// phase, stage, properties and per-body fields, and `run(View&)`.
//
//   struct MyPass {
//       static constexpr const char* name = "my_pass";
//       static constexpr const char* doc = "...";
//       static constexpr uint32_t phase = PLAB_PHASE_POST_FORCE, stage = 0;
//       static constexpr plab_property_desc properties[] = {plab::prop::...};  // optional
//       static constexpr plab_field_desc fields[] = {plab::field_desc(...), ...};
//       using material = MyMaterial;  // optional: properties shared with other plug-ins (contact_model.hpp)
//       explicit MyPass(const double* props);
//       void run(const plab_pass_view& v);
//       // optional, for a pass that keeps state between cycles (checkpoints):
//       std::vector<unsigned char> save_state() const;
//       bool load_state(const unsigned char* data, std::size_t size);
//   };
//   PLAB_PLUGIN(plab::add_pass<MyPass>(r))
//
// A pass that checks a physical bound (SPH density near rho0) throws
// plab::UnstableState from run(): the host stops the run with its message
// and keeps the last good state (abi.h, PLAB_PASS_UNSTABLE).
#ifndef PLAB_PASS_HPP
#define PLAB_PASS_HPP

#include <plab/contact_model.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <string>
#include <vector>

namespace plab {

// The state a pass checks is unphysical. The message names the quantity,
// the body, the value against its bound and a likely cause; it stays inside
// the plug-in (copied into the view's diagnostic buffer, never thrown across).
struct UnstableState {
    std::string message;
};

namespace detail {
template <class P, class = void> struct has_properties : std::false_type {};
template <class P> struct has_properties<P, std::void_t<decltype(P::properties)>> : std::true_type {};

template <class P, class = void> struct has_state : std::false_type {};
template <class P> struct has_state<P, std::void_t<decltype(&P::save_state), decltype(&P::load_state)>> : std::true_type {};

template <class P> uint64_t save_pass_state(const void* state, unsigned char* out, uint64_t capacity) noexcept {
    try {
        const std::vector<unsigned char> bytes = static_cast<const P*>(state)->save_state();
        if (bytes.size() <= capacity) std::copy(bytes.begin(), bytes.end(), out);
        return bytes.size();
    } catch (...) { return 0; }
}
template <class P> int load_pass_state(void* state, const unsigned char* data, uint64_t size) noexcept {
    try { return static_cast<P*>(state)->load_state(data, std::size_t(size)) ? 0 : 1; } catch (...) { return 2; }
}

template <class P> int run_pass(void* state, const double*, const plab_pass_view* v) noexcept {
    if (!state) return 1;
    if (v->size < sizeof(plab_pass_view)) return 4;  // a host older than these headers
    try {
        static_cast<P*>(state)->run(*v);
    } catch (const UnstableState& u) {
        if (v->diagnostic && v->diagnostic_capacity > 0) {
            const std::size_t n = std::min<std::size_t>(u.message.size(), v->diagnostic_capacity - 1);
            std::memcpy(v->diagnostic, u.message.data(), n);
            v->diagnostic[n] = '\0';
        }
        return PLAB_PASS_UNSTABLE;
    } catch (...) {
        return 2;
    }
    return 0;
}
} // namespace detail

template <class P> const plab_pass_desc* pass_desc() {
    static const plab_pass_desc d = [] {
        plab_pass_desc x{};
        x.size = sizeof(plab_pass_desc);
        x.name = P::name;
        x.doc = P::doc;
        x.phase = P::phase;
        x.stage = P::stage;
        if constexpr (detail::has_properties<P>::value) {
            x.property_count = detail::count_of(P::properties);
            x.properties = P::properties;
        }
        x.field_count = detail::count_of(P::fields);
        x.fields = P::fields;
        x.create = &detail::create<P>;
        x.destroy = &detail::destroy<P>;
        x.run = &detail::run_pass<P>;
        if constexpr (detail::has_material<P>::value) x.material = P::material::name;
        return x;
    }();
    return &d;
}

template <class P> int add_pass(const plab_registrar* r) {
    if (r->size < sizeof(plab_registrar)) return 1;  // a host older than these headers
    if (const int rc = detail::add_material_of<P>(r)) return rc;
    const int rc = r->register_pass(r->host, pass_desc<P>());
    if constexpr (detail::has_state<P>::value) {
        static const plab_pass_state_hooks hooks{sizeof(plab_pass_state_hooks), P::name, &detail::save_pass_state<P>, &detail::load_pass_state<P>};
        if (rc == 0) return r->register_pass_state(r->host, &hooks);
    }
    return rc;
}

// d, the vector between two bodies of a pass view from their positions,
// turned into its minimum image in the view's periodic cell (no change
// without one, or from a host older than ABI 2.4).
inline void minimum_image(const plab_pass_view& v, double d[3]) {
    if (v.size < offsetof(plab_pass_view, periodic_length) + sizeof(v.periodic_length) || !v.periodic_length) return;
    for (int c = 0; c < 3; ++c) {
        const double L = v.periodic_length[c];
        if (L > 0) d[c] -= L * std::nearbyint(d[c] / L);
    }
}

// x_to - x_from of two bodies of a pass view, as its minimum image in a
// periodic cell: the pair's separation the way its contact sees it.
inline Vec3 separation(const plab_pass_view& v, int32_t from, int32_t to) {
    double d[3];
    for (int c = 0; c < 3; ++c) d[c] = v.position[3 * to + c] - v.position[3 * from + c];
    minimum_image(v, d);
    return {d[0], d[1], d[2]};
}

} // namespace plab

#endif // PLAB_PASS_HPP
