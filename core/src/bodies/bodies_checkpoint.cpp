#include "bodies/bodies_checkpoint.hpp"

#include <string>

namespace plab {

void save_bodies(const Bodies& b, CheckpointWriter& out) {
    out.section("bodies");
    out.column(b.id);
    for (const auto* v : {&b.position, &b.velocity, &b.angular_velocity, &b.force, &b.moment, &b.applied_force,
                          &b.applied_moment})
        out.vecs(*v);
    for (const auto* v : {&b.radius, &b.mass, &b.inertia, &b.local_damping, &b.viscous_damping}) out.column(*v);
    out.column(b.group);
    out.column(b.fixity);
    out.u64(b.next_id);
}

void load_bodies(Bodies& b, int group_count, CheckpointReader& in) {
    in.section("bodies");
    b.id = in.column<BodyId>();
    for (auto* v : {&b.position, &b.velocity, &b.angular_velocity, &b.force, &b.moment, &b.applied_force,
                    &b.applied_moment})
        *v = in.vecs();
    for (auto* v : {&b.radius, &b.mass, &b.inertia, &b.local_damping, &b.viscous_damping}) *v = in.column<double>();
    b.group = in.column<int>();
    b.fixity = in.column<std::uint8_t>();
    b.next_id = in.u64();
    const std::size_t n = b.id.size();
    if (b.applied_force.size() != b.applied_moment.size() || (b.has_applied_loads() && b.applied_force.size() != n))
        in.fail("applied loads for " + std::to_string(b.applied_force.size()) + " of " + std::to_string(n) + " bodies");
    for (std::size_t len : {b.position.size(), b.velocity.size(), b.angular_velocity.size(), b.force.size(),
                            b.moment.size(), b.radius.size(),
                            b.mass.size(), b.inertia.size(), b.local_damping.size(), b.viscous_damping.size(),
                            b.group.size(), b.fixity.size()})
        if (len != n) in.fail("body columns of different lengths (" + std::to_string(len) + " vs " + std::to_string(n) + ")");
    for (int g : b.group)
        if (g < 0 || g >= group_count) in.fail("a body has group index " + std::to_string(g));
}

void save_walls(const Walls& w, CheckpointWriter& out) {
    out.section("walls");
    out.u64(w.walls.size());
    for (const Wall& x : w.walls) {
        out.str(x.name);
        out.u64(std::uint64_t(x.group));
        for (const Vec* v : {&x.velocity, &x.angular_velocity, &x.centre, &x.force, &x.moment}) out.vec(*v);
        out.column(x.facets);
    }
    out.u64(w.facets.size());
    for (const Facet& f : w.facets) {
        out.u32(std::uint32_t(f.kind));
        out.u64(std::uint64_t(f.wall));
        out.u64(f.id);
        for (const Vec* v : {&f.a, &f.b, &f.c}) out.vec(*v);
    }
    out.u64(w.next_facet_id);
}

void load_walls(Walls& w, int group_count, CheckpointReader& in) {
    in.section("walls");
    const std::uint64_t n = in.u64();
    if (n != w.walls.size())
        in.fail("it holds " + std::to_string(n) + " walls, the scene makes " + std::to_string(w.walls.size()));
    for (Wall& x : w.walls) {
        const std::string name = in.str();
        if (name != x.name) in.fail("wall '" + name + "' where the scene has '" + x.name + "'");
        x.group = int(in.u64());
        if (x.group < 0 || x.group >= group_count) in.fail("wall '" + name + "' has an unknown group");
        for (Vec* v : {&x.velocity, &x.angular_velocity, &x.centre, &x.force, &x.moment}) *v = in.vec();
        x.facets = in.column<int>();
    }
    w.facets.resize(in.u64());
    for (Facet& f : w.facets) {
        const std::uint32_t kind = in.u32();
        if (kind > std::uint32_t(FacetKind::plane)) in.fail("unknown facet kind " + std::to_string(kind));
        f.kind = FacetKind(kind);
        f.wall = int(in.u64());
        if (f.wall < 0 || std::size_t(f.wall) >= w.walls.size()) in.fail("a facet names wall " + std::to_string(f.wall));
        f.id = in.u64();
        for (Vec* v : {&f.a, &f.b, &f.c}) *v = in.vec();
    }
    for (const Wall& x : w.walls)
        for (int fi : x.facets)
            if (fi < 0 || std::size_t(fi) >= w.facets.size()) in.fail("wall '" + x.name + "' lists facet " + std::to_string(fi));
    w.next_facet_id = in.u64();
}

void save_fields(const BodyFields& fields, CheckpointWriter& out) {
    out.section("fields");
    out.u64(fields.size());
    for (std::size_t f = 0; f < fields.size(); ++f) {
        out.str(fields.names()[f]);
        out.column(fields.column(int(f)));
    }
}

void load_fields(BodyFields& fields, std::size_t body_count, CheckpointReader& in) {
    in.section("fields");
    const std::uint64_t n_fields = in.u64();
    std::vector<bool> seen(fields.size(), false);
    for (std::uint64_t f = 0; f < n_fields; ++f) {
        const std::string name = in.str();
        std::vector<double> values = in.column<double>();
        const int idx = fields.index(name);
        if (idx < 0) in.fail("body field '" + name + "' is registered by no plug-in this scene loads");
        if (values.size() != body_count) in.fail("body field '" + name + "' has the wrong length");
        fields.column(idx) = std::move(values);
        seen[idx] = true;
    }
    for (std::size_t f = 0; f < seen.size(); ++f)
        if (!seen[f]) fields.column(int(f)).assign(body_count, fields.default_value(int(f)));
}

} // namespace plab
