// The contract every contact model must keep, run on every model the host
// finds in the build's plug-in folder: a well-formed description, zero force
// outside the activity range, opposite force when the ends swap,
// objectivity under rotation, the same result for batch size 1 and N, no
// NaN at extreme inputs, and a positive stable timestep.
#include <plab_host/plugins.hpp>
#include <plab_host/types.hpp>
#include <forces/tangential_history.hpp>  // (the host's turn of tangential history, tested from inside)

#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <cmath>
#include <cstring>
#include <random>

using namespace plab;

namespace {

// One synthetic contact's inputs (what the host's geometry would produce).
struct ContactInput {
    Vec normal = Vec::UnitX();
    double gap = -1e-4;
    Vec rel_velocity = Vec::Zero(), rel_angular_velocity = Vec::Zero();
    double r1 = 0.01, r2 = 0.012, m1 = 0.01, m2 = 0.015;
    std::vector<double> history;
    int32_t body1 = -1, body2 = -1;  // body indices of the ends; -1: from the row (below)
};

struct ContactOutput {
    Vec force, moment1, moment2;
    double strain = 0, slip = 0, dashpot = 0, k_t = 0, k_r = 0, dt_limit = 0;
    std::vector<double> history;
};

// Calls compute() once over a batch of the given contacts, like the host
// (which first turns the tangential history of the active rows into their
// contact planes). Body field f of body i is body_fields[f][i] when given
// (64 bodies), else a plausible 1000 for every field and body.
std::vector<ContactOutput> compute(const plab_contact_model_desc& d, void* state, const std::vector<double>& props,
                                   int dim, double dt, const std::vector<ContactInput>& in,
                                   const std::vector<std::vector<double>>* body_fields = nullptr,
                                   uint64_t fields_at_default = 0) {
    const std::size_t n = in.size(), hs = d.history_count;
    std::vector<int32_t> e1(n), e2(n);
    std::vector<uint8_t> active(n);
    std::vector<double> normal(3 * n), gap(n), dist(n), rv(3 * n), rw(3 * n), r1(n), r2(n), m1(n), m2(n), me(n), re(n),
        hist(n * hs + 1), force(3 * n, 0.0), mo1(3 * n, 0.0), mo2(3 * n, 0.0), strain(n, 0.0), slip(n, 0.0), dash(n, 0.0),
        kt(n, 0.0), kr(n, 0.0), dtl(n, INFINITY), brk(n, 0.0);
    std::vector<double> field_values(64, 1000.0);  // a plausible value for any body field
    std::vector<const double*> fields(d.fields_read_count + 1, field_values.data());
    if (body_fields)
        for (uint32_t f = 0; f < d.fields_read_count; ++f) fields[f] = (*body_fields)[f].data();
    std::vector<std::vector<double>> acc(2 * d.fields_accumulated_count + 2, std::vector<double>(n, 0.0));
    std::vector<double*> acc1, acc2;
    for (uint32_t f = 0; f <= d.fields_accumulated_count; ++f) { acc1.push_back(acc[2 * f].data()); acc2.push_back(acc[2 * f + 1].data()); }
    for (std::size_t k = 0; k < n; ++k) {
        const ContactInput& c = in[k];
        e1[k] = c.body1 >= 0 ? c.body1 : int32_t(2 * k % 64);
        e2[k] = c.body2 >= 0 ? c.body2 : int32_t((2 * k + 1) % 64);
        for (int a = 0; a < 3; ++a) {
            normal[3 * k + a] = c.normal[a];
            rv[3 * k + a] = c.rel_velocity[a];
            rw[3 * k + a] = c.rel_angular_velocity[a];
        }
        gap[k] = c.gap;
        dist[k] = c.gap + c.r1 + c.r2;
        r1[k] = c.r1; r2[k] = c.r2; m1[k] = c.m1; m2[k] = c.m2;
        me[k] = c.m1 * c.m2 / (c.m1 + c.m2);
        re[k] = c.r1 * c.r2 / (c.r1 + c.r2);
        const double range = d.activity_range(props.data());
        active[k] = d.range_kind == PLAB_RANGE_GAP ? c.gap <= range : dist[k] <= range;
        for (std::size_t h = 0; h < hs; ++h) hist[k * hs + h] = c.history.empty() ? d.history[h].default_value : c.history[h];
        if (d.persist_slot >= 0 && hist[k * hs + d.persist_slot] > 0) active[k] = 1;  // as the host: a bond holds
    }
    plab_contact_batch b{sizeof(plab_contact_batch)};
    b.dim = uint32_t(dim); b.count = uint32_t(n); b.history_stride = uint32_t(hs); b.dt = dt;
    b.end1 = e1.data(); b.end2 = e2.data(); b.active = active.data();
    b.normal = normal.data(); b.gap = gap.data(); b.distance = dist.data();
    b.rel_velocity = rv.data(); b.rel_angular_velocity = rw.data();
    b.radius1 = r1.data(); b.radius2 = r2.data(); b.mass1 = m1.data(); b.mass2 = m2.data();
    b.eff_mass = me.data(); b.eff_radius = re.data(); b.body_fields = fields.data(); b.history = hist.data();
    b.force = force.data(); b.moment1 = mo1.data(); b.moment2 = mo2.data(); b.strain_energy = strain.data();
    b.slip_energy = slip.data(); b.dashpot_energy = dash.data(); b.stiffness_translational = kt.data();
    b.stiffness_rotational = kr.data(); b.dt_limit = dtl.data(); b.accumulate1 = acc1.data(); b.accumulate2 = acc2.data();
    b.break_energy = brk.data();
    b.stage = PLAB_STAGE_FORCES;
    b.body_fields_at_default = fields_at_default;
    turn_tangential_history(d, hist.data(), hs, normal.data(), active.data(), n);
    REQUIRE(d.compute(state, props.data(), &b) == 0);
    std::vector<ContactOutput> out(n);
    for (std::size_t k = 0; k < n; ++k) {
        out[k].force = Vec(&force[3 * k]);
        out[k].moment1 = Vec(&mo1[3 * k]);
        out[k].moment2 = Vec(&mo2[3 * k]);
        out[k].strain = strain[k];
        out[k].slip = slip[k];
        out[k].dashpot = dash[k];
        out[k].k_t = kt[k];
        out[k].k_r = kr[k];
        out[k].dt_limit = dtl[k];
        out[k].history.assign(hist.begin() + long(k * hs), hist.begin() + long((k + 1) * hs));
    }
    return out;
}

// Property values that exercise a model: defaults, with zero defaults of
// numbers moved into the range (friction 0 → 0.5, damping 0 → 0.3 of its
// range); bools, choices and groups keep their defaults.
std::vector<double> exercising_properties(const plab_contact_model_desc& d) {
    std::vector<double> v;
    for (uint32_t p = 0; p < d.property_count; ++p) {
        const auto& q = d.properties[p];
        double x = q.default_value;
        const bool numeric = q.kind == PLAB_KIND_NUMBER || q.kind == PLAB_KIND_INTEGER;
        if (numeric && x == 0 && std::isfinite(q.min_value))
            x = std::isfinite(q.max_value) ? q.min_value + 0.3 * (q.max_value - q.min_value) : q.min_value + 0.5;
        if (q.kind == PLAB_KIND_INTEGER) x = std::floor(x);  // counts are whole numbers
        v.push_back(x);
    }
    return v;
}

// Every value of a property with few: a choice's indices, a bool's 0 and 1,
// a small integer range; none for the others.
std::vector<double> every_value(const plab_property_desc& q) {
    std::vector<double> out;
    if (q.kind == PLAB_KIND_CHOICE)
        for (uint32_t c = 0; c < q.choice_count; ++c) out.push_back(c);
    else if (q.kind == PLAB_KIND_BOOL)
        out = {0.0, 1.0};
    else if (q.kind == PLAB_KIND_INTEGER && q.max_value - q.min_value <= 4)
        for (double v = q.min_value; v <= q.max_value; v += 1) out.push_back(v);
    return out;
}

// A contact in the middle of the activity range with sliding and spin.
ContactInput typical(const plab_contact_model_desc& d, const std::vector<double>& props, int dim, std::mt19937& rng) {
    std::uniform_real_distribution<double> u(-1, 1);
    ContactInput c;
    c.normal = dim == 2 ? Vec(u(rng), u(rng), 0).normalized() : Vec(u(rng), u(rng), u(rng)).normalized();
    const double range = d.activity_range(props.data());
    c.gap = d.range_kind == PLAB_RANGE_GAP ? std::min(range, 0.0) - 2e-4 : 0.5 * range - c.r1 - c.r2;
    c.rel_velocity = Vec(u(rng), u(rng), dim == 3 ? u(rng) : 0.0) * 0.5;
    c.rel_angular_velocity = dim == 2 ? Vec(0, 0, u(rng) * 10) : Vec(u(rng), u(rng), u(rng)) * 10;
    for (uint32_t h = 0; h < d.history_count; ++h) c.history.push_back(d.history[h].default_value);
    if (d.persist_slot >= 0 && rng() % 2) c.history[d.persist_slot] = 1;  // half the contacts bonded
    return c;
}

ContactInput swapped(const plab_contact_model_desc& d, ContactInput c) {
    c.normal = -c.normal;
    c.rel_velocity = -c.rel_velocity;
    c.rel_angular_velocity = -c.rel_angular_velocity;
    std::swap(c.r1, c.r2);
    std::swap(c.m1, c.m2);
    for (uint32_t h = 0; h < d.history_count; ++h)
        if (d.history[h].swap_rule == PLAB_SWAP_NEGATE) c.history[h] = -c.history[h];
    return c;
}

// Rotate every vector input; vector history slots come as x, y, z triples
// (slots named *_x, *_y, *_z), scalar slots stay.
ContactInput rotated(const plab_contact_model_desc& d, ContactInput c, const Eigen::Matrix3d& R) {
    c.normal = R * c.normal;
    c.rel_velocity = R * c.rel_velocity;
    c.rel_angular_velocity = R * c.rel_angular_velocity;
    for (uint32_t h = 0; h + 2 < d.history_count; ++h) {
        const std::string n = d.history[h].name;
        if (n.size() > 2 && n.substr(n.size() - 2) == "_x") {
            const Vec v = R * Vec(c.history[h], c.history[h + 1], c.history[h + 2]);
            for (int a = 0; a < 3; ++a) c.history[h + a] = v[a];
            h += 2;
        }
    }
    return c;
}

struct Model {
    const plab_contact_model_desc* d;
    std::vector<double> props;
    void* state;
    std::shared_ptr<PluginHost> own_host;  // the host that loaded d, when not the caller's
    ~Model() { if (d->destroy && state) d->destroy(state); }
};

void add_models(std::vector<std::unique_ptr<Model>>& out, PluginHost& host, std::shared_ptr<PluginHost> own) {
    for (const auto& name : host.model_names()) {
        const plab_contact_model_desc* d = host.model(name);
        auto m = std::make_unique<Model>(Model{d, exercising_properties(*d), nullptr, own});
        m->state = d->create ? d->create(m->props.data()) : nullptr;
        out.push_back(std::move(m));
    }
}

// The build's models, and the tutorial's hertz, a model written out of
// tree: it has the name of the shipped `hertz`, which one host refuses
// twice, so it is loaded by a host of its own.
std::vector<std::unique_ptr<Model>> every_model(PluginHost& host) {
    std::vector<std::unique_ptr<Model>> out;
    for (const auto& path : host.discover()) host.load(path);
    add_models(out, host, nullptr);
    auto teaching = std::make_shared<PluginHost>();
    teaching->load(std::string(PLAB_TEACHING_PLUGIN_DIR) + "/plab_hertz.so");
    const std::size_t shipped = out.size();
    add_models(out, *teaching, teaching);  // (it has loaded that library alone)
    REQUIRE(out.size() == shipped + 1);     // the tutorial's one model
    return out;
}

double scale(const Vec& v) { return std::max(1e-12, v.norm()); }

// The body fields a model reads, at the harness' plausible 1000, with the
// tensors among them turned by R: a tensor is a run of fields named
// *_xx, *_yy, *_zz, *_xy, *_yz, *_zx (symmetric) or *_xx, *_xy, *_xz, *_yx,
// ... *_zz (full, row by row), turned as R T Rᵀ (the SPH solid's stress);
// scalars stay. Without R: the fields as the harness has them.
std::vector<std::vector<double>> body_fields_turned(const plab_contact_model_desc& d, const Eigen::Matrix3d& R) {
    std::vector<std::vector<double>> f(d.fields_read_count, std::vector<double>(64, 1000.0));
    const auto suffix = [&](uint32_t k) {
        const std::string n = k < d.fields_read_count ? d.fields_read[k].name : "";
        return n.size() > 3 ? n.substr(n.size() - 3) : std::string();
    };
    static const int sym[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {2, 0}};
    for (uint32_t k = 0; k < d.fields_read_count; ++k) {
        if (suffix(k) != "_xx") continue;
        const bool full = suffix(k + 1) == "_xy", symmetric = suffix(k + 1) == "_yy";
        if (!full && !symmetric) continue;
        Eigen::Matrix3d t = Eigen::Matrix3d::Constant(1000.0);  // (symmetric too)
        const Eigen::Matrix3d turned = R * t * R.transpose();
        for (int c = 0; c < (full ? 9 : 6); ++c) {
            const double v = full ? turned(c / 3, c % 3) : turned(sym[c][0], sym[c][1]);
            std::fill(f[k + c].begin(), f[k + c].end(), v);
        }
        k += full ? 8 : 5;
    }
    return f;
}

} // namespace

TEST_CASE("contract: every model found has a well-formed description", "[contract]") {
    PluginHost host;
    auto models = every_model(host);
    REQUIRE(!models.empty());
    for (auto& m : models) {
        INFO("model " << m->d->name);
        CHECK(check_model_desc(*m->d).empty());
        for (uint32_t p = 0; p < m->d->property_count; ++p) CHECK(in_range(m->d->properties[p], m->props[p]));
    }
}

TEST_CASE("contract: zero force and reset history outside the activity range", "[contract]") {
    PluginHost host;
    std::mt19937 rng(1);
    for (auto& m : every_model(host))
        for (int dim : {2, 3}) {
            INFO("model " << m->d->name << " dim " << dim);
            ContactInput c = typical(*m->d, m->props, dim, rng);
            const double range = m->d->activity_range(m->props.data());
            c.gap = m->d->range_kind == PLAB_RANGE_GAP ? range + 1e-4 : range + 1e-4 - c.r1 - c.r2;
            for (uint32_t h = 0; h < m->d->history_count; ++h)  // stale history must be forgotten
                if (int32_t(h) != m->d->persist_slot) c.history[h] += 1.0;
            if (m->d->persist_slot >= 0) c.history[m->d->persist_slot] = 0;  // (a bond would hold at any gap)
            const auto out = compute(*m->d, m->state, m->props, dim, 1e-6, {c});
            CHECK(out[0].force.norm() == 0.0);
            CHECK(out[0].moment1.norm() == 0.0);
            for (uint32_t h = 0; h < m->d->history_count; ++h) CHECK(out[0].history[h] == m->d->history[h].default_value);
        }
}

TEST_CASE("contract: swapping the two ends gives the opposite force", "[contract]") {
    PluginHost host;
    std::mt19937 rng(2);
    for (auto& m : every_model(host))
        for (int dim : {2, 3})
            for (int trial = 0; trial < 20; ++trial) {
                INFO("model " << m->d->name << " dim " << dim << " trial " << trial);
                const ContactInput c = typical(*m->d, m->props, dim, rng);
                // build up history over a few steps, then compare one step both ways
                ContactInput a = c, b = swapped(*m->d, c);
                for (int s = 0; s < 5; ++s) {
                    a.history = compute(*m->d, m->state, m->props, dim, 1e-5, {a})[0].history;
                    b.history = compute(*m->d, m->state, m->props, dim, 1e-5, {b})[0].history;
                }
                const auto fa = compute(*m->d, m->state, m->props, dim, 1e-5, {a})[0];
                const auto fb = compute(*m->d, m->state, m->props, dim, 1e-5, {b})[0];
                CHECK((fa.force + fb.force).norm() <= 1e-12 * scale(fa.force));
                CHECK((fa.moment1 - fb.moment2).norm() <= 1e-12 * scale(fa.moment1) + 1e-300);
            }
}

TEST_CASE("contract: the force rotates with the contact (objectivity)", "[contract]") {
    PluginHost host;
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-M_PI, M_PI);
    for (auto& m : every_model(host))
        for (int dim : {2, 3})
            for (int trial = 0; trial < 20; ++trial) {
                INFO("model " << m->d->name << " dim " << dim << " trial " << trial);
                const Eigen::Matrix3d R = dim == 2 ? Eigen::AngleAxisd(u(rng), Vec::UnitZ()).toRotationMatrix()
                                                   : (Eigen::AngleAxisd(u(rng), Vec::UnitZ()) *
                                                      Eigen::AngleAxisd(u(rng), Vec::UnitY()) *
                                                      Eigen::AngleAxisd(u(rng), Vec::UnitX())).toRotationMatrix();
                ContactInput a = typical(*m->d, m->props, dim, rng);
                for (int s = 0; s < 5; ++s) a.history = compute(*m->d, m->state, m->props, dim, 1e-5, {a})[0].history;
                const ContactInput b = rotated(*m->d, a, R);
                // tensor body fields (the SPH solid's stress) turn with the frame too
                const auto fields_a = body_fields_turned(*m->d, Eigen::Matrix3d::Identity());
                const auto fields_b = body_fields_turned(*m->d, R);
                const auto fa = compute(*m->d, m->state, m->props, dim, 1e-5, {a}, &fields_a)[0];
                const auto fb = compute(*m->d, m->state, m->props, dim, 1e-5, {b}, &fields_b)[0];
                CHECK((R * fa.force - fb.force).norm() <= 1e-10 * scale(fa.force));
                CHECK((R * fa.moment2 - fb.moment2).norm() <= 1e-10 * scale(fa.moment2) + 1e-300);
                CHECK(fa.strain == Approx(fb.strain).epsilon(1e-10));
            }
}

TEST_CASE("contract: batch size 1 and N give the same result", "[contract]") {
    PluginHost host;
    std::mt19937 rng(4);
    for (auto& m : every_model(host)) {
        INFO("model " << m->d->name);
        std::vector<ContactInput> many;
        for (int k = 0; k < 700; ++k) many.push_back(typical(*m->d, m->props, 3, rng));
        const auto batch = compute(*m->d, m->state, m->props, 3, 1e-5, many);
        for (std::size_t k = 0; k < many.size(); k += 37) {
            const auto one = compute(*m->d, m->state, m->props, 3, 1e-5, {many[k]})[0];
            CHECK(one.force == batch[k].force);
            CHECK(one.history == batch[k].history);
        }
    }
}

TEST_CASE("contract: no NaN at extreme inputs", "[contract]") {
    PluginHost host;
    std::mt19937 rng(5);
    for (auto& m : every_model(host))
        for (double overlap_fraction : {1e-12, 0.5, 0.99})
            for (double speed : {0.0, 1e-9, 1e3})
                for (double radius : {1e-6, 10.0}) {
                    INFO("model " << m->d->name << " overlap " << overlap_fraction << " speed " << speed << " r " << radius);
                    ContactInput c = typical(*m->d, m->props, 3, rng);
                    c.r1 = c.r2 = radius;
                    c.m1 = c.m2 = 2500 * 4.19 * radius * radius * radius;
                    const double range = m->d->activity_range(m->props.data());
                    c.gap = m->d->range_kind == PLAB_RANGE_GAP ? std::min(range, 0.0) - overlap_fraction * radius
                                                               : (1 - overlap_fraction) * range - 2 * radius;
                    c.rel_velocity = c.rel_velocity.normalized() * speed;
                    const auto out = compute(*m->d, m->state, m->props, 3, 1e-6, {c})[0];
                    CHECK(out.force.allFinite());
                    CHECK(out.moment1.allFinite());
                    CHECK(std::isfinite(out.strain));
                    for (double h : out.history) CHECK(std::isfinite(h));
                }
}

TEST_CASE("contract: every active contact reports a positive stable timestep", "[contract]") {
    PluginHost host;
    std::mt19937 rng(6);
    for (auto& m : every_model(host)) {
        INFO("model " << m->d->name);
        const auto out = compute(*m->d, m->state, m->props, 3, 1e-6, {typical(*m->d, m->props, 3, rng)})[0];
        const bool has_stiffness = out.k_t > 0 && std::isfinite(out.k_t);
        const bool has_limit = out.dt_limit > 0 && std::isfinite(out.dt_limit);
        CHECK((has_stiffness || has_limit));
        CHECK(out.k_r >= 0);
    }
}

// A batch whose rows are all active (the host's packed batches) runs
// through the adapter's loop over law(), vectorised for a law written as
// choices (`linear`), or a model's own (law_rows, `sph`). It must give, bit
// for bit, what the same rows give one by one in a batch that also holds
// inactive rows: forces, history, energies, stiffness and step limit. Two
// steps, so that the second starts from a stored shear force (turned by the
// harness, as by the host, into a turned contact plane),
// with speeds from sticking to sliding, distances across the activity range,
// body fields that differ from body to body, in 2D and 3D, for every value of
// a mode property and with the properties whose default is zero at zero (a
// term switched off).
TEST_CASE("contract: a batch of active rows only gives what the same rows give among inactive ones, bit for bit",
          "[contract]") {
    const auto same_bits = [](double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; };
    PluginHost host;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1, 1), u01(0, 1);
    for (auto& m : every_model(host)) {
        const plab_contact_model_desc& d = *m->d;
        if (d.persist_slot >= 0) continue;  // inactive rows made by their gap or distance
        std::vector<std::vector<double>> prop_sets{m->props};
        for (uint32_t p = 0; p < d.property_count; ++p)  // every value of a mode (a choice, a bool, a small integer)
            for (double v : every_value(d.properties[p])) {
                prop_sets.push_back(m->props);
                prop_sets.back()[p] = v;
            }
        prop_sets.push_back(m->props);
        for (uint32_t p = 0; p < d.property_count; ++p)
            if (d.properties[p].default_value == 0) prop_sets.back()[p] = 0;
        // each body's fields: densities around 1000, pressures of both signs, small velocities
        std::vector<std::vector<double>> fields(d.fields_read_count, std::vector<double>(64));
        for (auto& f : fields)
            for (double& x : f) x = 1000 * (1 + 0.3 * u(rng));
        for (auto& f : fields)
            if (&f != &fields[0])
                for (double& x : f) x *= u(rng) * 1e-3;
        for (const auto& props : prop_sets)
            for (int dim : {2, 3}) {
                void* state = d.create ? d.create(props.data()) : nullptr;
                const double range = d.activity_range(props.data());
                std::vector<ContactInput> rows;
                for (int k = 0; k < 300; ++k) {
                    ContactInput c = typical(d, props, dim, rng);
                    c.rel_velocity *= std::pow(10.0, 2 * u(rng));  // 0.005 to 50 m/s: sticking and sliding
                    if (d.range_kind == PLAB_RANGE_DISTANCE) c.gap = u01(rng) * range - c.r1 - c.r2;
                    c.body1 = int32_t(rng() % 64);
                    c.body2 = int32_t(rng() % 64);
                    rows.push_back(c);
                }
                for (int step = 0; step < 2; ++step) {
                    std::vector<ContactInput> mixed;  // each row, then an inactive one
                    for (const ContactInput& c : rows) {
                        mixed.push_back(c);
                        ContactInput far = c;
                        far.gap = range + 1e-3 - (d.range_kind == PLAB_RANGE_DISTANCE ? c.r1 + c.r2 : 0.0);
                        mixed.push_back(far);
                    }
                    const auto dense = compute(d, state, props, dim, 1e-4, rows, &fields);
                    const auto one_by_one = compute(d, state, props, dim, 1e-4, mixed, &fields);
                    for (std::size_t k = 0; k < rows.size(); ++k) {
                        const ContactOutput &a = dense[k], &b = one_by_one[2 * k];
                        INFO("model " << d.name << ", dim " << dim << ", step " << step << ", row " << k);
                        for (int c = 0; c < 3; ++c) CHECK(same_bits(a.force[c], b.force[c]));
                        for (std::size_t h = 0; h < a.history.size(); ++h) CHECK(same_bits(a.history[h], b.history[h]));
                        CHECK(same_bits(a.strain, b.strain));
                        CHECK(same_bits(a.slip, b.slip));
                        CHECK(same_bits(a.dashpot, b.dashpot));
                        CHECK(same_bits(a.k_t, b.k_t));
                        CHECK(same_bits(a.dt_limit, b.dt_limit));
                    }
                    for (std::size_t k = 0; k < rows.size(); ++k) {  // the next step: stored history, turned plane
                        rows[k].history = dense[k].history;
                        // (in 2D about z: a 2D batch's vectors have z = 0, vec3.hpp, and a
                        // model may work on x and y alone, as `linear` does)
                        const Vec axis = Vec(u(rng), u(rng), u(rng)).normalized();
                        const Eigen::Matrix3d R(Eigen::AngleAxisd(0.05 * u(rng), dim == 2 ? Vec::UnitZ() : axis));
                        rows[k].normal = R * rows[k].normal;
                    }
                }
                if (d.destroy && state) d.destroy(state);
            }
    }
}

// ABI 7: the host may say that read fields hold their declared default at
// every body (body_fields_at_default), and a model may then skip reading
// them (sph: the wall velocity corrections). A true claim must change no
// bit: every field at its default, and only the fields after the first two
// at theirs (the first two, sph's density and pressure, varied).
TEST_CASE("contract: a true claim that read fields hold their defaults changes no bit of the result", "[contract]") {
    const auto same_bits = [](double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; };
    PluginHost host;
    std::mt19937 rng(12);
    std::uniform_real_distribution<double> u(-1, 1);
    for (auto& m : every_model(host)) {
        const plab_contact_model_desc& d = *m->d;
        if (d.fields_read_count == 0) continue;
        for (uint32_t varied : {0u, std::min(2u, d.fields_read_count)}) {
            std::vector<std::vector<double>> fields;
            uint64_t claim = 0;
            for (uint32_t f = 0; f < d.fields_read_count; ++f) {
                fields.emplace_back(64, d.fields_read[f].default_value);
                if (f < varied)
                    for (double& x : fields.back()) x = (f == 0 ? 1000 : 1e4) * (1 + 0.3 * u(rng));
                else
                    claim |= uint64_t(1) << f;
            }
            for (int dim : {2, 3}) {
                std::vector<ContactInput> rows;
                for (int k = 0; k < 200; ++k) {
                    ContactInput c = typical(d, m->props, dim, rng);
                    c.rel_velocity *= std::pow(10.0, 2 * u(rng));
                    c.body1 = int32_t(rng() % 64);
                    c.body2 = int32_t(rng() % 64);
                    rows.push_back(c);
                }
                const auto plain = compute(d, m->state, m->props, dim, 1e-4, rows, &fields);
                const auto claimed = compute(d, m->state, m->props, dim, 1e-4, rows, &fields, claim);
                for (std::size_t k = 0; k < rows.size(); ++k) {
                    INFO("model " << d.name << ", dim " << dim << ", varied " << varied << ", row " << k);
                    for (int c = 0; c < 3; ++c) CHECK(same_bits(plain[k].force[c], claimed[k].force[c]));
                    CHECK(same_bits(plain[k].dt_limit, claimed[k].dt_limit));
                    CHECK(plain[k].history == claimed[k].history);
                }
            }
        }
    }
}
