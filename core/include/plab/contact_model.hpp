// C++ adapter over the plug-in ABI (abi.h): a model author writes a class
// with the law for ONE contact; this header generates the C description
// table and the batch loop, so the law is inlined into the loop and nothing
// but C crosses the library boundary.
//
//   struct MyModel {
//       static constexpr const char* name = "my_model";
//       static constexpr const char* doc = "...";
//       static constexpr const char* timestep_rule = "...";
//       static constexpr uint32_t range_kind = PLAB_RANGE_GAP;
//       static constexpr plab_property_desc properties[] = {plab::prop::number(...), ...};
//       enum Slot : int { ..., slot_count };            // history slots
//       static constexpr plab_history_desc history[] = {plab::history_desc(...), ...};  // slot_count entries
//       static constexpr uint32_t io = PLAB_IO_EFF_MASS;  // optional inputs read, outputs written (0: none)
//       static double activity_range(const double* props);
//       explicit MyModel(const double* props);
//       void law(plab::Contact& c) const;
//   };
//   PLAB_PLUGIN(plab::add_contact_model<MyModel>(r))
//
// `io` names what the law reads beyond normal, gap, distance, relative
// velocity, history and dt (PLAB_IO_RADII, _MASSES, _EFF_MASS, _EFF_RADIUS,
// _REL_ANGULAR_VELOCITY) and writes beyond the force, energies and
// translational stiffness (PLAB_IO_MOMENTS, _STIFFNESS_ROTATIONAL,
// _DT_LIMIT, _BREAK_ENERGY). The host packs only those columns, and before
// the first step refuses a law that reads or writes one it does not name.
//
// Optional members: `fields_read[]`, `fields_accumulated[]`
// (plab_field_desc arrays) to read body fields / accumulate into them;
// `persist_slot` (int) for a model with bonds; `rates_stage` (bool) for a
// model that accumulates field rates before forces (SPH; see abi.h);
// `flags` (uint32_t, PLAB_MODEL_* of abi.h) e.g. for a force between centres;
// `material` (a type, `using material = MyMaterial;`): the material whose
// properties the model takes from a scene's materials (below);
// `law_rows(const plab_contact_batch&, std::size_t k0, std::size_t k1) const`:
// the model's own loop over rows [k0, k1) when all of them are active, in
// place of the one the adapter generates from law() (below), for a law that
// must make choices once per batch rather than per contact (`sph`: its
// kernel and viscosity forms as template arguments); it must give what
// law() gives row by row, bit for bit.
//
// A history slot whose description has PLAB_HISTORY_TANGENTIAL is the first
// of three (x, y, z) holding a vector in the contact plane, e.g. a shear
// force: the host turns it into the current plane before law() reads it
// (abi.h), so a law adds its increment to the stored vector as it is.
//
// The batch loop: the host's packed batches hold active rows only, and on
// those the adapter runs law() in one loop that the compiler vectorises
// (law inlined, built for AVX2 and for the build's target). A law written
// as choices between values (`c ? a : b`, not branches around work) runs
// several contacts per instruction; any other law runs in the same loop
// one contact at a time. Every form gives the same bits.
//
// A material (abi.h plab_material_desc, ABI 2.1) is a class with the
// properties the models and passes of a package share:
//
//   struct MyMaterial {
//       static constexpr const char* name = "my_solid";
//       static constexpr const char* doc = "...";
//       static constexpr plab_property_desc properties[] = {youngs_modulus, friction};  // constexpr descriptions
//   };
//
// A model or pass with `using material = MyMaterial;` lists among its own
// `properties` those of the material it uses, with the same descriptions
// (`youngs_modulus`, ...), and gets, for each, the value a scene material of
// its groups gives; add_contact_model and add_pass register the material
// before the model or pass (a second registration, alike, is accepted).
//
// Descriptions are built with the constexpr functions below, which set each
// struct's `size` (abi.h): a property of each kind (plab::prop::number,
// integer, boolean, choice, group, optional_group), a history slot
// (plab::history_desc) and a body field (plab::field_desc).
#ifndef PLAB_CONTACT_MODEL_HPP
#define PLAB_CONTACT_MODEL_HPP

#include <plab/abi.h>
#include <plab/vec3.hpp>

#include <cmath>
#include <cstddef>
#include <limits>
#include <type_traits>
#include <utility>

#if defined(_WIN32)
#define PLAB_EXPORT __declspec(dllexport)
#else
#define PLAB_EXPORT __attribute__((visibility("default")))
#endif

// A batch loop built for each CPU target listed, the best one picked when
// the library loads, e.g. PLAB_TARGET_CLONES_FLAT("avx2", "default"), with
// every call in it inlined (flatten), so that what it calls is built for
// each target too. Clang refuses target_clones together with flatten;
// there the loop is built once, flattened, for the build's own target
// (-march=native by default): the same bits, as the clones use no FMA
// (plab_add_contact_model builds with -ffp-contract=off).
// PLAB_ROWS_INDEPENDENT before such a loop: its iterations touch different
// rows of columns that do not overlap (the host's), so the compiler may run
// them together without checking the columns' addresses.
#if defined(__clang__)
#define PLAB_TARGET_CLONES_FLAT(...) __attribute__((flatten))
#define PLAB_ROWS_INDEPENDENT _Pragma("clang loop vectorize(assume_safety)")
#elif defined(__GNUC__)
#define PLAB_TARGET_CLONES_FLAT(...) __attribute__((target_clones(__VA_ARGS__), flatten))
#define PLAB_ROWS_INDEPENDENT _Pragma("GCC ivdep")
#else
#define PLAB_TARGET_CLONES_FLAT(...)
#define PLAB_ROWS_INDEPENDENT
#endif

namespace plab {

// Property descriptions, one function per kind (abi.h PLAB_KIND_*). The law
// reads every kind as a double: a bool as 0/1, a choice as the index of its
// name, a group as the group's index (-1: none).
namespace prop {

// A real number in [lo, hi] (flags PLAB_MIN_EXCLUSIVE / PLAB_MAX_EXCLUSIVE);
// `mixing` (PLAB_MIX_*): how two materials' values combine in a contact
// between them.
constexpr plab_property_desc number(const char* key, const char* name, const char* unit, double default_value,
                                    double lo, double hi, uint32_t flags, const char* doc,
                                    uint32_t mixing = PLAB_MIX_NONE) {
    return {sizeof(plab_property_desc), PLAB_KIND_NUMBER, key, name, unit, default_value, lo, hi, flags, mixing,
            nullptr, 0, doc};
}
// A whole number in [lo, hi] (a count); mixing may be PLAB_MIX_MAX or MIN.
constexpr plab_property_desc integer(const char* key, const char* name, const char* unit, double default_value,
                                     double lo, double hi, const char* doc, uint32_t mixing = PLAB_MIX_NONE) {
    return {sizeof(plab_property_desc), PLAB_KIND_INTEGER, key, name, unit, default_value, lo, hi, 0u, mixing,
            nullptr, 0, doc};
}
// true / false in the scene, 1 / 0 to the law.
constexpr plab_property_desc boolean(const char* key, const char* name, bool default_value, const char* doc) {
    return {sizeof(plab_property_desc), PLAB_KIND_BOOL, key, name, "1", default_value ? 1.0 : 0.0, 0.0, 1.0, 0u,
            PLAB_MIX_NONE, nullptr, 0, doc};
}
// One of `names` in the scene (e.g. {"wendland_c2", "cubic", "quintic"}, a
// static array), the index of the name to the law; the default is an index.
template <std::size_t N>
constexpr plab_property_desc choice(const char* key, const char* name, const char* const (&names)[N],
                                    uint32_t default_index, const char* doc) {
    return {sizeof(plab_property_desc), PLAB_KIND_CHOICE, key, name, "1", double(default_index), 0.0, double(N - 1),
            0u, PLAB_MIX_NONE, names, uint32_t(N), doc};
}
// A group the scene must name; its index to the law.
constexpr plab_property_desc group(const char* key, const char* name, const char* doc) {
    return {sizeof(plab_property_desc), PLAB_KIND_GROUP, key, name, "1", -1.0, -1.0, 0.0, 0u, PLAB_MIX_NONE,
            nullptr, 0, doc};
}
// A group or none (null / "none" in the scene, the default): -1 to the law.
constexpr plab_property_desc optional_group(const char* key, const char* name, const char* doc) {
    return {sizeof(plab_property_desc), PLAB_KIND_GROUP, key, name, "1", -1.0, -1.0, 0.0, PLAB_GROUP_NONE_ALLOWED,
            PLAB_MIX_NONE, nullptr, 0, doc};
}

} // namespace prop

// A history slot: name, default, what it does when the ends swap (PLAB_SWAP_*),
// and PLAB_HISTORY_TANGENTIAL on the first of three slots of a vector in the
// contact plane (the host turns it with the plane).
constexpr plab_history_desc history_desc(const char* name, double default_value, uint32_t swap_rule, const char* doc,
                                         uint32_t flags = 0) {
    return {sizeof(plab_history_desc), name, default_value, swap_rule, doc, flags};
}
// A per-body field: name, SI unit, default.
constexpr plab_field_desc field_desc(const char* name, const char* unit, double default_value) {
    return {sizeof(plab_field_desc), name, unit, default_value};
}

// The C description of material Mat (static storage), and its registration.
template <class Mat> const plab_material_desc* material_desc() {
    static const plab_material_desc d = {sizeof(plab_material_desc), Mat::name, Mat::doc,
                                         uint32_t(sizeof(Mat::properties) / sizeof(Mat::properties[0])), Mat::properties};
    return &d;
}
template <class Mat> int add_material(const plab_registrar* r) {
    if (r->size < sizeof(plab_registrar)) return 1;  // a host older than these headers
    return r->register_material(r->host, material_desc<Mat>());
}

namespace detail {
// Row k of a column of xyz triples (abi.h: vectors are packed triples).
inline Vec3 row3(const double* col, uint32_t k) { return {col[3 * k], col[3 * k + 1], col[3 * k + 2]}; }
// ... of a vector in the plane of a 2D world (a normal, a velocity): its z
// is zero (abi.h), which the loop over a 2D batch then knows without a load.
inline Vec3 planar_row3(const double* col, uint32_t k, uint32_t dim) {
    return {col[3 * k], col[3 * k + 1], dim == 2 ? 0.0 : col[3 * k + 2]};
}
inline void put_row3(double* col, uint32_t k, const Vec3& v) {
    col[3 * k] = v.x; col[3 * k + 1] = v.y; col[3 * k + 2] = v.z;
}
} // namespace detail

// One contact of a batch: typed access to the host's columns at index k.
class Contact {
public:
    Contact(const plab_contact_batch& b, uint32_t k) : b_(b), k_(k) {}

    int dim() const { return static_cast<int>(b_.dim); }
    double dt() const { return b_.dt; }
    bool with_wall() const { return b_.end2_is_wall != 0; }
    int32_t end1() const { return b_.end1[k_]; }
    int32_t end2() const { return b_.end2[k_]; }
    // true in the rates stage of a model with `rates_stage` (abi.h)
    bool rates_stage() const { return b_.stage == PLAB_STAGE_RATES; }

    Vec3 normal() const { return detail::planar_row3(b_.normal, k_, b_.dim); }
    double gap() const { return b_.gap[k_]; }
    double overlap() const { return -b_.gap[k_]; }
    double distance() const { return b_.distance[k_]; }
    Vec3 rel_velocity() const { return detail::planar_row3(b_.rel_velocity, k_, b_.dim); }
    Vec3 rel_angular_velocity() const { return detail::row3(b_.rel_angular_velocity, k_); }
    double radius1() const { return b_.radius1[k_]; }
    double radius2() const { return b_.radius2[k_]; }
    double mass1() const { return b_.mass1[k_]; }
    double mass2() const { return b_.mass2[k_]; }
    double eff_mass() const { return b_.eff_mass[k_]; }
    double eff_radius() const { return b_.eff_radius[k_]; }

    double& history(int slot) const { return b_.history[std::size_t(k_) * b_.history_stride + slot]; }
    Vec3 history_vec(int first_slot) const {
        return {history(first_slot), history(first_slot + 1), history(first_slot + 2)};
    }
    void set_history_vec(int first_slot, const Vec3& v) const {
        history(first_slot) = v.x; history(first_slot + 1) = v.y; history(first_slot + 2) = v.z;
    }

    // body fields declared in `fields_read`, by position in that list; a wall
    // end has no body fields, so field2 of a ball–wall contact is NaN
    double field1(int f) const { return b_.body_fields[f][b_.end1[k_]]; }
    double field2(int f) const {
        return b_.end2_is_wall ? std::numeric_limits<double>::quiet_NaN() : b_.body_fields[f][b_.end2[k_]];
    }
    // true: field f holds its declared default at every body in this batch
    // (abi.h, body_fields_at_default), so a law may take the default without reading it
    bool field_at_default(int f) const { return f < 64 && ((b_.body_fields_at_default >> f) & 1u); }
    void accumulate1(int f, double v) const { b_.accumulate1[f][k_] += v; }
    void accumulate2(int f, double v) const { b_.accumulate2[f][k_] += v; }

    // force acting on end 2 (end 1 receives the opposite), N
    void set_force(const Vec3& f) const { detail::put_row3(b_.force, k_, f); }
    void set_moment1(const Vec3& m) const { detail::put_row3(b_.moment1, k_, m); }
    void set_moment2(const Vec3& m) const { detail::put_row3(b_.moment2, k_, m); }
    void set_strain_energy(double e) const { b_.strain_energy[k_] = e; }
    void add_slip_energy(double e) const { b_.slip_energy[k_] += e; }
    void add_dashpot_energy(double e) const { b_.dashpot_energy[k_] += e; }
    // stiffness seen by the host's stable-timestep estimate sqrt(m / sum k)
    // (the one-argument form leaves the rotational stiffness at the host's
    // zero, so a model that declares its `io` need not declare it)
    void set_stiffness(double translational) const { b_.stiffness_translational[k_] = translational; }
    void set_stiffness(double translational, double rotational) const {
        b_.stiffness_translational[k_] = translational;
        b_.stiffness_rotational[k_] = rotational;
    }
    void set_dt_limit(double dt) const { b_.dt_limit[k_] = dt; }
    void add_break_energy(double e) const { b_.break_energy[k_] += e; }

private:
    const plab_contact_batch& b_;
    uint32_t k_;
};

namespace detail {

template <class M, class = void> struct has_fields_read : std::false_type {};
template <class M> struct has_fields_read<M, std::void_t<decltype(M::fields_read)>> : std::true_type {};
template <class M, class = void> struct has_fields_acc : std::false_type {};
template <class M> struct has_fields_acc<M, std::void_t<decltype(M::fields_accumulated)>> : std::true_type {};
template <class M, class = void> struct has_persist : std::false_type {};
template <class M> struct has_persist<M, std::void_t<decltype(M::persist_slot)>> : std::true_type {};
template <class M, class = void> struct has_rates : std::false_type {};
template <class M> struct has_rates<M, std::void_t<decltype(M::rates_stage)>> : std::true_type {};
template <class M, class = void> struct has_flags : std::false_type {};
template <class M> struct has_flags<M, std::void_t<decltype(M::flags)>> : std::true_type {};
template <class M, class = void> struct has_io : std::false_type {};
template <class M> struct has_io<M, std::void_t<decltype(M::io)>> : std::true_type {};
template <class M, class = void> struct has_law_rows : std::false_type {};
template <class M>
struct has_law_rows<M, std::void_t<decltype(std::declval<const M&>().law_rows(std::declval<const plab_contact_batch&>(),
                                                                              std::size_t(), std::size_t()))>>
    : std::true_type {};
template <class M, class = void> struct has_history : std::false_type {};
template <class M> struct has_history<M, std::void_t<decltype(M::history)>> : std::true_type {};
template <class M, class = void> struct has_material : std::false_type {};
template <class M> struct has_material<M, std::void_t<typename M::material>> : std::true_type {};

// Registers the material of a model or pass M, if it has one.
template <class M> int add_material_of(const plab_registrar* r) {
    if constexpr (has_material<M>::value) return add_material<typename M::material>(r);
    return 0;
}

template <class T, std::size_t N> constexpr uint32_t count_of(const T (&)[N]) { return uint32_t(N); }

template <class M> void* create(const double* props) noexcept {
    try { return new M(props); } catch (...) { return nullptr; }
}
template <class M> void destroy(void* p) noexcept { delete static_cast<M*>(p); }

// law() on rows [k0, k1) of a batch whose rows are all active (the host's
// packed batches): one loop over the rows, with the law inlined into it,
// which the compiler vectorises where the law is written as choices between
// values. Each loop has the dimension and the history stride as constants
// (the stride is the model's slot count where the host's is that, as it
// always is): then a contact's slots are a fixed pattern of loads, not one
// gather per slot, and in 2D the z of its normal and relative velocity is a
// known zero (planar_row3), whose terms the compiler drops where the bits
// allow. Built for AVX2 and for the build's own target (four contacts per
// instruction on AVX2).
template <class M>
PLAB_TARGET_CLONES_FLAT("avx2", "default") void law_on_rows(const M& model, const plab_contact_batch& b, uint32_t k0,
                                                            uint32_t k1) {
    const auto rows = [&](plab_contact_batch& batch, uint32_t dim, uint32_t stride) {
        batch.dim = dim;
        batch.history_stride = stride;
        PLAB_ROWS_INDEPENDENT
        for (uint32_t k = k0; k < k1; ++k) model.law(Contact(batch, k));
    };
    constexpr uint32_t slots = [] {
        if constexpr (has_history<M>::value) return count_of(M::history);
        return 0u;
    }();
    plab_contact_batch fixed = b;  // (with the constants of each loop below)
    const bool planar = b.dim == 2;
    if (b.history_stride != slots) return planar ? rows(fixed, 2u, b.history_stride) : rows(fixed, 3u, b.history_stride);
    planar ? rows(fixed, 2u, slots) : rows(fixed, 3u, slots);
}

// The batch loop: inactive contacts get their history reset to the declared
// defaults (a separated contact is forgotten); active ones run the law. The
// rows are first sorted into the two kinds without a branch per row: the
// active flags of a Verlet list follow no pattern, and a mispredicted branch
// per contact costs about as much as the geometry of an inactive one.
template <class M> int compute(void* inst, const double*, const plab_contact_batch* b) noexcept {
    if (!inst) return 1;
    if (b->size < sizeof(plab_contact_batch)) return 4;  // a host older than these headers
    const M& model = *static_cast<const M*>(inst);
    constexpr uint32_t chunk = 256;
    uint32_t active[chunk], inactive[chunk];
    try {
        for (uint32_t k0 = 0; k0 < b->count; k0 += chunk) {
            const uint32_t k1 = b->count - k0 < chunk ? b->count : k0 + chunk;
            // a packed batch (the host's dense path) holds active rows only:
            // those go through the loop over the rows, without a list
            uint32_t n_active = 0, n_inactive = 0;
            for (uint32_t k = k0; k < k1; ++k) n_inactive += b->active[k] == 0;
            if (n_inactive == 0) {
                if constexpr (has_law_rows<M>::value) model.law_rows(*b, k0, k1);  // the model's own loop
                else law_on_rows(model, *b, k0, k1);
                continue;
            }
            n_inactive = 0;
            for (uint32_t k = k0; k < k1; ++k) {
                const bool a = b->active[k] != 0;
                active[n_active] = k;
                inactive[n_inactive] = k;
                n_active += a;
                n_inactive += !a;
            }
            if constexpr (has_history<M>::value)
                for (uint32_t r = 0; r < n_inactive; ++r) {
                    double* row = b->history + std::size_t(inactive[r]) * b->history_stride;
                    for (uint32_t s = 0; s < count_of(M::history); ++s) row[s] = M::history[s].default_value;
                }
            for (uint32_t r = 0; r < n_active; ++r) {
                Contact c(*b, active[r]);
                model.law(c);
            }
        }
    } catch (...) {
        return 2;
    }
    return 0;
}

} // namespace detail

// The C description of model M (static storage: valid while the library is loaded).
template <class M> const plab_contact_model_desc* contact_model_desc() {
    static_assert(detail::has_io<M>::value,
                  "a contact model declares its optional inputs and outputs: static constexpr uint32_t io = "
                  "PLAB_IO_... | ...; (0 for none; abi.h PLAB_IO_*)");
    static const plab_contact_model_desc d = [] {
        plab_contact_model_desc x{};
        x.size = sizeof(plab_contact_model_desc);
        x.name = M::name;
        x.doc = M::doc;
        x.property_count = detail::count_of(M::properties);
        x.properties = M::properties;
        if constexpr (detail::has_history<M>::value) {
            x.history_count = detail::count_of(M::history);
            x.history = M::history;
        }
        x.range_kind = M::range_kind;
        x.timestep_rule = M::timestep_rule;
        x.activity_range = &M::activity_range;
        if constexpr (detail::has_fields_read<M>::value) {
            x.fields_read_count = detail::count_of(M::fields_read);
            x.fields_read = M::fields_read;
        }
        if constexpr (detail::has_fields_acc<M>::value) {
            x.fields_accumulated_count = detail::count_of(M::fields_accumulated);
            x.fields_accumulated = M::fields_accumulated;
        }
        x.create = &detail::create<M>;
        x.destroy = &detail::destroy<M>;
        x.compute = &detail::compute<M>;
        x.persist_slot = -1;
        if constexpr (detail::has_persist<M>::value) x.persist_slot = M::persist_slot;
        if constexpr (detail::has_rates<M>::value) x.rates_stage = M::rates_stage ? 1u : 0u;
        if constexpr (detail::has_flags<M>::value) x.flags = M::flags;
        if constexpr (detail::has_io<M>::value) x.io = M::io | PLAB_IO_DECLARED;  // (else the assertion above)
        if constexpr (detail::has_material<M>::value) x.material = M::material::name;
        return x;
    }();
    return &d;
}

template <class M> int add_contact_model(const plab_registrar* r) {
    if (r->size < sizeof(plab_registrar)) return 1;  // a host older than these headers
    if (const int rc = detail::add_material_of<M>(r)) return rc;
    return r->register_contact_model(r->host, contact_model_desc<M>());
}

} // namespace plab

// Defines the two exported entry points of a plug-in library. `body` is an
// expression over the registrar `r` that returns 0 on success, e.g.
//   PLAB_PLUGIN(plab::add_contact_model<Linear>(r))
#define PLAB_PLUGIN(body)                                                         \
    extern "C" PLAB_EXPORT uint32_t plab_plugin_abi_version(void) { return PLAB_ABI_VERSION; } \
    extern "C" PLAB_EXPORT int plab_plugin_init(const plab_registrar* r) { return (body); }

#endif // PLAB_CONTACT_MODEL_HPP
