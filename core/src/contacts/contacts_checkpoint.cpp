#include "contacts/contacts_checkpoint.hpp"

#include "contacts/contact_keys.hpp"

#include <string>
#include <tuple>

namespace plab {

namespace {

// The keys are written though the world derives them from the ends
// (contacts/contact_keys.hpp): the file stays readable as before, and a restart checks
// that its rows name the same bodies.
void save_set(const Bodies& bodies, const Walls& walls, const ModelInstance& inst, const ContactSet& cs,
              CheckpointWriter& out) {
    auto& s = const_cast<ContactSet&>(cs);  // double_columns() hands out pointers; nothing is changed
    out.column(s.end1);
    out.column(s.end2);
    std::vector<BodyId> key1(s.size()), key2(s.size());
    for (std::size_t k = 0; k < s.size(); ++k) std::tie(key1[k], key2[k]) = row_key(bodies, walls, s, k);
    out.column(key1);
    out.column(key2);
    out.column(s.active);
    out.column(s.interior);
    // history by slot: one column per slot name (save_contacts writes the names)
    for (int h = 0; h < inst.stride; ++h) {
        std::vector<double> col(s.size());
        for (std::size_t k = 0; k < s.size(); ++k) col[k] = s.history[k * inst.stride + h];
        out.column(col);
    }
    const auto cols = s.double_columns();
    out.u64(cols.size());
    for (const auto& [name, col] : cols) {
        out.str(name);
        out.column(*col);
    }
    out.u64(s.acc1.size());
    for (const auto& a : s.acc1) out.column(a);
    for (const auto& a : s.acc2) out.column(a);
}

// `slot_of_file[h]`: the model's slot for the file's slot h.
// `key1`, `key2`: the file's keys of the rows, for the caller to check
// against the ends.
void load_set(const ModelInstance& inst, ContactSet& s, const std::vector<int>& slot_of_file, CheckpointReader& in,
              std::vector<BodyId>& key1, std::vector<BodyId>& key2) {
    s.end1 = in.column<std::int32_t>();
    s.end2 = in.column<std::int32_t>();
    key1 = in.column<BodyId>();
    key2 = in.column<BodyId>();
    const std::size_t n = s.end1.size();
    s.resize_columns(n, int(inst.fields_accumulated.size()));
    s.active = in.column<std::uint8_t>();
    s.interior = in.column<std::uint8_t>();
    if (s.end2.size() != n || key1.size() != n || key2.size() != n || s.active.size() != n)
        in.fail("contact columns of model '" + inst.model + "' have different lengths");
    s.history.assign(n * inst.stride, 0.0);
    for (int h = 0; h < inst.stride; ++h)  // slots the file lacks start at their default
        for (std::size_t k = 0; k < n; ++k) s.history[k * inst.stride + h] = inst.desc->history[h].default_value;
    for (int model_slot : slot_of_file) {
        const std::vector<double> col = in.column<double>();
        if (col.size() != n) in.fail("a history column of model '" + inst.model + "' has the wrong length");
        for (std::size_t k = 0; k < n; ++k) s.history[k * inst.stride + model_slot] = col[k];
    }
    auto cols = s.double_columns();
    const std::uint64_t n_cols = in.u64();
    for (std::uint64_t c = 0; c < n_cols; ++c) {
        const std::string name = in.str();
        std::vector<double> values = in.column<double>();
        for (auto& [known, col] : cols)
            if (name == known) {
                if (col->empty() && s.packed) break;  // a column a packed set does not keep
                if (values.size() != col->size()) in.fail("contact column '" + name + "' has the wrong length");
                *col = std::move(values);
            }
    }
    const std::uint64_t n_acc = in.u64();
    if (n_acc != s.acc1.size()) in.fail("model '" + inst.model + "' accumulates a different number of fields");
    for (auto& a : s.acc1) a = in.column<double>();
    for (auto& a : s.acc2) a = in.column<double>();
}

std::string slot_list(const plab_contact_model_desc& d) {
    std::string s;
    for (std::uint32_t h = 0; h < d.history_count; ++h) s += (h ? ", " : "") + std::string(d.history[h].name);
    return s.empty() ? "none" : s;
}

} // namespace

void save_assignment(const AssignmentTable& a, CheckpointWriter& out) {
    out.section("assignment");
    out.u64(a.group_names().size());
    for (const auto& g : a.group_names()) out.str(g);
    out.column(a.table());
}

void load_assignment(AssignmentTable& a, std::size_t instance_count, CheckpointReader& in) {
    in.section("assignment");
    const std::uint64_t n_groups = in.u64();
    std::vector<std::string> groups;
    for (std::uint64_t g = 0; g < n_groups; ++g) groups.push_back(in.str());
    if (groups != a.group_names()) in.fail("its groups differ from the scene's (the scene is not the one that wrote it)");
    std::vector<int> cmat = in.column<int>();
    if (cmat.size() != a.table().size()) in.fail("the assignment table has the wrong size");
    for (int inst : cmat)
        if (inst < -1 || inst >= int(instance_count)) in.fail("the assignment table names model instance " + std::to_string(inst));
    a.set_table(std::move(cmat));
}

void save_contacts(const Instances& instances, const Bodies& bodies, const Walls& walls, CheckpointWriter& out) {
    out.section("contacts");
    out.u64(instances.size());
    for (const auto& inst : instances) {
        out.str(inst->model);
        out.column(inst->props);
        out.u64(std::uint64_t(inst->stride));
        for (int h = 0; h < inst->stride; ++h) out.str(inst->desc->history[h].name);
        save_set(bodies, walls, *inst, inst->balls, out);
        save_set(bodies, walls, *inst, inst->walls, out);
    }
}

void load_contacts(Instances& instances, const Bodies& bodies, const Walls& walls, const PluginHost& host,
                   const std::function<bool(const ModelInstance&)>& packs_balls, CheckpointReader& in) {
    in.section("contacts");
    const std::uint64_t n_inst = in.u64();
    if (n_inst != instances.size())
        in.fail("it holds " + std::to_string(n_inst) + " contact-model instances, the scene makes " +
                std::to_string(instances.size()));
    for (auto& inst : instances) {
        const std::string model = in.str();
        if (model != inst->model) in.fail("model '" + model + "' where the scene has '" + inst->model + "'");
        in.column<double>();  // the properties it ran with; the scene's (with --set) apply from here on
        const std::uint64_t n_slots = in.u64();
        std::vector<int> slot_of_file;
        for (std::uint64_t h = 0; h < n_slots; ++h) {
            const std::string slot = in.str();
            int found = -1;
            for (int m = 0; m < inst->stride; ++m)
                if (slot == inst->desc->history[m].name) found = m;
            if (found < 0)
                in.fail("history slot '" + slot + "' of model '" + model + "' is not declared by the loaded library " +
                        host.library_of_model(model) + " (its slots: " + slot_list(*inst->desc) +
                        "); the contact history it holds would be lost — restart with the plug-in that wrote it");
            slot_of_file.push_back(found);
        }
        inst->balls.packed = packs_balls(*inst);
        std::vector<BodyId> key1, key2;
        for (ContactSet* s : {&inst->balls, &inst->walls}) {
            load_set(*inst, *s, slot_of_file, in, key1, key2);
            for (std::size_t k = 0; k < s->size(); ++k) {
                const bool ok = s->end1[k] >= 0 && std::size_t(s->end1[k]) < bodies.size() && s->end2[k] >= 0 &&
                                std::size_t(s->end2[k]) < (s->with_wall ? walls.facets.size() : bodies.size());
                if (!ok) in.fail("a contact of model '" + model + "' names a body or facet that does not exist");
                if (row_key(bodies, walls, *s, k) != std::make_pair(key1[k], key2[k]))
                    in.fail("a contact of model '" + model + "' names bodies by index and by id that differ");
            }
        }
    }
}

} // namespace plab
