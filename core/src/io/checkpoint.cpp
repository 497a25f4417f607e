// Checkpoint file format (plab_host/checkpoint.hpp) and the world in it:
// the host's state and each subsystem's sections, in file order.
// Everything a later step reads is saved as it is, derived columns included
// (contact geometry, per-body stiffness sums, the contact list passes see,
// the Verlet reference positions): recomputing them after a restart would
// use whole-step velocities where the uninterrupted run used half-step ones,
// and the answer would drift in the last bits.
#include <plab_host/checkpoint.hpp>

#include "contacts/contact_keys.hpp"
#include "world/cycle.hpp"

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <tuple>

#include <zlib.h>

namespace fs = std::filesystem;

namespace plab {

namespace {
constexpr char kMagic[8] = {'P', 'L', 'A', 'B', 'C', 'K', 'P', 'T'};
constexpr std::uint32_t kEndianMarker = 0x01020304u;
constexpr std::size_t kHeaderBytes = sizeof kMagic + 2 * sizeof(std::uint32_t);

std::uint32_t crc32_of(std::uint32_t crc, const void* p, std::size_t n) {
    return std::uint32_t(crc32_z(crc, static_cast<const Bytef*>(p), n));
}

std::string hex(std::uint32_t v) {
    char s[16];
    std::snprintf(s, sizeof s, "0x%08x", v);
    return s;
}

// The CRC-32 of the header with `format` in its version field: a version
// field whose bit flipped still has the CRC of the true version behind it.
std::uint32_t header_crc(const unsigned char* head, std::uint32_t format) {
    unsigned char h[kHeaderBytes];
    std::memcpy(h, head, kHeaderBytes);
    std::memcpy(h + sizeof kMagic, &format, sizeof format);
    return crc32_of(0, h, kHeaderBytes);
}
} // namespace

// The file is read as it is parsed, not into memory first: a restart then
// peaks at the world it builds, not at the world plus one copy of the file
// per reader (Simulation::restart opens two).
CheckpointReader::CheckpointReader(const std::string& path) : path_(path), file_(path, std::ios::binary) {
    if (!file_) throw CheckpointError("cannot open checkpoint " + path);
    read_header();
}

namespace {

void check_byte_order(const std::string& path, const unsigned char* head) {
    std::uint32_t marker = 0;
    std::memcpy(&marker, head + sizeof kMagic + sizeof(std::uint32_t), sizeof marker);
    if (marker == __builtin_bswap32(kEndianMarker))
        throw CheckpointError(path + " was written on a machine of the other byte order (marker " +
                              std::to_string(marker) + "); checkpoints load only on the byte order that wrote them");
    if (marker != kEndianMarker)
        throw CheckpointError(path + ": the header is damaged (byte-order marker " + hex(marker) + ", not " +
                              hex(kEndianMarker) + ")");
}

// `stored_crc`: the 4 bytes after the header, where a framed file keeps the
// header's CRC (null if the file is too short to hold them).
void check_version(const std::string& path, const unsigned char* head, std::uint32_t format,
                   const std::uint32_t* stored_crc) {
    const std::string range = " (" + std::to_string(kCheckpointOldestFormat) + " to " + std::to_string(kCheckpointFormat) + ")";
    if (format != kCheckpointFormat && stored_crc && *stored_crc == header_crc(head, kCheckpointFormat))
        throw CheckpointError(path + ": the header is damaged (format version " + std::to_string(format) +
                              " where its CRC-32 says " + std::to_string(kCheckpointFormat) + ")");
    if (format > kCheckpointFormat)
        throw CheckpointError(path + " has checkpoint format version " + std::to_string(format) +
                              ", newer than this plab reads" + range + "; restart it with the plab that wrote it or a newer one");
    if (format < kCheckpointOldestFormat)
        throw CheckpointError(path + " has checkpoint format version " + std::to_string(format) +
                              ", older than this plab reads" + range);
}

} // namespace

void CheckpointReader::read_header() {
    std::error_code ec;
    size_ = fs::file_size(path_, ec);
    unsigned char head[kHeaderBytes];
    if (ec || size_ < kHeaderBytes || !file_.read(reinterpret_cast<char*>(head), kHeaderBytes) ||
        std::memcmp(head, kMagic, sizeof kMagic) != 0)
        throw CheckpointError(path_ + " is not a plab checkpoint (no PLABCKPT header)");
    pos_ = kHeaderBytes;
    std::memcpy(&format_, head + sizeof kMagic, sizeof format_);
    check_byte_order(path_, head);
    std::uint32_t stored = 0;
    const bool has_crc = size_ >= kHeaderBytes + sizeof stored && file_.read(reinterpret_cast<char*>(&stored), sizeof stored);
    check_version(path_, head, format_, has_crc ? &stored : nullptr);
    framed_ = format_ >= kCheckpointFramedFormat;
    if (!framed_) {
        file_.seekg(std::streamoff(pos_));
        return;
    }
    if (!has_crc) fail("the file ends early (truncated or damaged)");
    pos_ += sizeof stored;
    if (stored != header_crc(head, format_))
        throw CheckpointError(path_ + ": the header is damaged (CRC-32 mismatch: stored " + hex(stored) + ", computed " +
                              hex(header_crc(head, format_)) + ")");
}

void CheckpointReader::fail(const std::string& why) const {
    throw CheckpointError("checkpoint " + path_ + (section_.empty() ? "" : ", section '" + section_ + "'") + ": " + why);
}

void CheckpointReader::raw(void* p, std::size_t n) {
    if (n > limit() - pos_)
        fail(limit() < size_ ? "it ends before its contents do (written by another build of plab?)"
                             : "the file ends early (truncated or damaged)");
    if (!file_.read(static_cast<char*>(p), std::streamsize(n))) fail("reading failed at byte " + std::to_string(pos_));
    pos_ += n;
}

std::uint64_t CheckpointReader::count(std::size_t element_bytes) {
    const std::uint64_t n = u64();
    if (n > (limit() - pos_) / element_bytes)
        fail("a length of " + std::to_string(n) + " runs past the end of the " + (limit() < size_ ? "section" : "file"));
    return n;
}

std::string CheckpointReader::str() {
    const std::uint64_t n = count(1);
    std::string s(n, '\0');
    raw(s.data(), n);
    return s;
}

void CheckpointReader::close_section() {
    if (!framed_ || section_.empty()) return;
    if (pos_ != end_) fail(std::to_string(end_ - pos_) + " bytes of it were not read (written by another build of plab?)");
    pos_ = end_ + sizeof(std::uint32_t);  // its CRC, checked when it began
    file_.seekg(std::streamoff(pos_));
    section_.clear();
}

// The section's contents, read once to check them before they are parsed;
// the read position is left at their start.
void CheckpointReader::check_crc(const std::string& name, std::uint64_t header_at) {
    const std::uint64_t length = u64(), contents = pos_;
    const std::uint64_t header_bytes = contents - header_at;
    if (length > size_ - contents || size_ - contents - length < sizeof(std::uint32_t)) {
        section_ = name;
        fail("its length of " + std::to_string(length) + " bytes runs past the end of the file (truncated or damaged)");
    }
    std::vector<char> buf(std::size_t(std::min<std::uint64_t>(std::max<std::uint64_t>(length, header_bytes), 1u << 20)));
    std::uint32_t crc = crc32_of(0, nullptr, 0);
    for (std::uint64_t left = length; left > 0;) {
        const std::size_t k = std::size_t(std::min<std::uint64_t>(left, buf.size()));
        if (!file_.read(buf.data(), std::streamsize(k))) fail("reading failed");
        crc = crc32_of(crc, buf.data(), k);
        left -= k;
    }
    std::uint32_t stored = 0;
    file_.read(reinterpret_cast<char*>(&stored), sizeof stored);
    file_.seekg(std::streamoff(header_at));  // the name and length, as written, close the CRC
    file_.read(buf.data(), std::streamsize(header_bytes));
    crc = crc32_of(crc, buf.data(), std::size_t(header_bytes));
    if (!file_ || stored != crc)
        throw CheckpointError("checkpoint " + path_ + ": section '" + name + "' is damaged (CRC-32 mismatch: stored " +
                              hex(stored) + ", computed " + hex(crc) + "); the file changed after it was written: "
                              "restart from another checkpoint, or run the scene again");
    file_.seekg(std::streamoff(contents));
    end_ = contents + length;
}

void CheckpointReader::section(const std::string& name) {
    close_section();
    const std::uint64_t at = pos_;
    const std::uint64_t n = u64();
    std::string found;
    if (n <= 64 && n <= size_ - pos_) {
        found.resize(n);
        raw(found.data(), n);
    }
    if (found != name)
        fail("expected section '" + name + "' at byte " + std::to_string(at) + ", found " +
             (found.empty() ? std::string("something else") : "'" + found + "'") + " (damaged file?)");
    if (framed_) check_crc(name, at);
    section_ = name;
}

void CheckpointReader::finish() {
    close_section();
    if (framed_ && pos_ != size_) fail(std::to_string(size_ - pos_) + " bytes follow the last section (damaged file?)");
}

CheckpointWriter::~CheckpointWriter() {
    if (!file_) return;
    file_.reset();
    std::error_code ec;
    fs::remove(path_ + ".tmp", ec);
}

CheckpointWriter CheckpointWriter::to_file(const std::string& path) {
    const fs::path p(path);
    if (p.has_parent_path()) fs::create_directories(p.parent_path());
    CheckpointWriter out;
    out.path_ = path;
    out.file_ = std::make_unique<std::ofstream>(path + ".tmp", std::ios::binary);
    if (!*out.file_) throw CheckpointError("cannot write checkpoint " + path + ".tmp");
    unsigned char head[kHeaderBytes];
    std::memcpy(head, kMagic, sizeof kMagic);
    std::memcpy(head + sizeof kMagic, &kCheckpointFormat, sizeof kCheckpointFormat);
    std::memcpy(head + sizeof kMagic + sizeof kCheckpointFormat, &kEndianMarker, sizeof kEndianMarker);
    const std::uint32_t crc = crc32_of(0, head, kHeaderBytes);
    out.put(head, kHeaderBytes);
    out.put(&crc, sizeof crc);
    return out;
}

void CheckpointWriter::commit() {
    end_section();
    file_->flush();
    if (!*file_) throw CheckpointError("cannot write checkpoint " + path_ + ".tmp");
    file_.reset();
    std::error_code ec;
    fs::rename(path_ + ".tmp", path_, ec);
    if (ec) {
        fs::remove(path_ + ".tmp", ec);
        throw CheckpointError("cannot write checkpoint " + path_ + ": " + ec.message());
    }
}

void CheckpointWriter::put(const void* p, std::size_t n) {
    if (file_) file_->write(static_cast<const char*>(p), std::streamsize(n));
    else data_.append(static_cast<const char*>(p), n);
    written_ += n;
}

void CheckpointWriter::raw(const void* p, std::size_t n) {
    put(p, n);
    if (!open_) return;
    crc_ = crc32_of(crc_, p, n);
    length_ += n;
}

void CheckpointWriter::section(const std::string& name) {
    end_section();
    const std::uint64_t n = name.size(), placeholder = 0;
    header_.assign(reinterpret_cast<const char*>(&n), sizeof n);
    header_ += name;
    put(header_.data(), header_.size());
    length_at_ = written_;
    put(&placeholder, sizeof placeholder);
    open_ = true;
    length_ = 0;
    crc_ = crc32_of(0, nullptr, 0);
}

// The length goes in its place; the CRC-32 of the contents, then of the
// name and length as written, follows the contents.
void CheckpointWriter::end_section() {
    if (!open_) return;
    open_ = false;
    std::uint32_t crc = crc32_of(crc_, header_.data(), header_.size());
    crc = crc32_of(crc, &length_, sizeof length_);
    if (file_) {
        file_->seekp(std::streamoff(length_at_));
        file_->write(reinterpret_cast<const char*>(&length_), sizeof length_);
        file_->seekp(0, std::ios::end);
    } else {
        std::memcpy(&data_[length_at_], &length_, sizeof length_);
    }
    put(&crc, sizeof crc);
}

void CheckpointWriter::append(const std::string& sections) {
    end_section();
    put(sections.data(), sections.size());
}

std::string CheckpointWriter::take() {
    end_section();
    return std::move(data_);
}

namespace {

// ---- bodies and walls -----------------------------------------------------

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

void load_bodies(Bodies& b, CheckpointReader& in) {
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

void load_walls(Walls& w, const Cycle& world, CheckpointReader& in) {
    in.section("walls");
    const std::uint64_t n = in.u64();
    if (n != w.walls.size())
        in.fail("it holds " + std::to_string(n) + " walls, the scene makes " + std::to_string(w.walls.size()));
    for (Wall& x : w.walls) {
        const std::string name = in.str();
        if (name != x.name) in.fail("wall '" + name + "' where the scene has '" + x.name + "'");
        x.group = int(in.u64());
        if (x.group < 0 || std::size_t(x.group) >= world.assignment.group_names().size()) in.fail("wall '" + name + "' has an unknown group");
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

// ---- contacts -------------------------------------------------------------

// The keys are written though the world derives them from the ends
// (contacts/contact_keys.hpp): the file stays readable as before, and a restart checks
// that its rows name the same bodies.
void save_set(const Cycle& w, const ModelInstance& inst, const ContactSet& cs, CheckpointWriter& out) {
    auto& s = const_cast<ContactSet&>(cs);  // double_columns() hands out pointers; nothing is changed
    out.column(s.end1);
    out.column(s.end2);
    std::vector<BodyId> key1(s.size()), key2(s.size());
    for (std::size_t k = 0; k < s.size(); ++k) std::tie(key1[k], key2[k]) = row_key(w.world.bodies, w.world.walls, s, k);
    out.column(key1);
    out.column(key2);
    out.column(s.active);
    out.column(s.interior);
    // history by slot: one column per slot name (see save_instance)
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

// ---- the world ------------------------------------------------------------

void save_scalars(const Cycle& w, CheckpointWriter& out) {
    out.section("world");
    out.u32(std::uint32_t(w.world.dim));
    out.f64(w.world.time);
    out.u64(w.world.step_count);
    out.f64(w.world.last_dt);
    out.vec(w.world.gravity);
    out.u64(w.neighbours.rebuilds);
    const Energies& e = w.world.energies;
    for (double v : {e.kinetic, e.strain, e.body, e.boundary, e.slip, e.dashpot, e.local_damping, e.bond_break}) out.f64(v);

    out.section("assignment");
    out.u64(w.assignment.group_names().size());
    for (const auto& g : w.assignment.group_names()) out.str(g);
    out.column(w.assignment.table());
}

void save_fields(const Cycle& w, CheckpointWriter& out) {
    out.section("fields");
    out.u64(w.world.fields.size());
    for (std::size_t f = 0; f < w.world.fields.size(); ++f) {
        out.str(w.world.fields.names()[f]);
        out.column(w.world.fields.column(int(f)));
    }
}

void save_contacts(const Cycle& w, CheckpointWriter& out) {
    out.section("contacts");
    out.u64(w.instances.size());
    for (const auto& inst : w.instances) {
        out.str(inst->model);
        out.column(inst->props);
        out.u64(std::uint64_t(inst->stride));
        for (int h = 0; h < inst->stride; ++h) out.str(inst->desc->history[h].name);
        save_set(w, *inst, inst->balls, out);
        save_set(w, *inst, inst->walls, out);
    }
}

void save_detection(const Cycle& w, CheckpointWriter& out) {
    out.section("detection");
    out.u8(w.neighbours.invalidated());
    out.u8(w.prepared);
    out.vecs(w.neighbours.position_at_build());
    out.f64(w.neighbours.wall_motion());
    const StiffnessSums& k = w.monitor.summed_stiffness();
    out.column(k.translational());
    out.column(k.rotational());
    out.column(w.pass_contacts.end1_column());
    out.column(w.pass_contacts.end2_column());
    out.column(w.pass_contacts.wall_column());
}

void save_passes(const Cycle& w, CheckpointWriter& out) {
    out.section("passes");
    out.u64(w.passes.size());
    for (const PassInstance& p : w.passes) {
        out.str(p.desc->name);
        out.column(p.props);
        const plab_pass_state_hooks* hooks = w.host->pass_state(p.desc->name);
        out.u8(hooks != nullptr);
        if (!hooks) continue;
        std::vector<unsigned char> buf(64);
        std::uint64_t need = hooks->save(p.state, buf.data(), buf.size());
        if (need > buf.size()) {
            buf.resize(need);
            need = hooks->save(p.state, buf.data(), buf.size());
        }
        if (need > buf.size() || need == 0)
            throw CheckpointError(std::string("pass '") + p.desc->name + "' (" + w.host->library_of_pass(p.desc->name) +
                                  ") failed to save its private state");
        buf.resize(need);
        out.column(buf);
    }
}

void save_log(const Cycle& w, CheckpointWriter& out) {
    out.section("bond_breaks");
    out.u64(w.world.bond_breaks.size());
    for (const BondBreak& b : w.world.bond_breaks) {
        out.u64(b.step);
        out.f64(b.time);
        out.u64(b.id1);
        out.u64(b.id2);
        out.vec(b.point);
        out.u32(std::uint32_t(b.mode));
        out.str(b.model);
    }

    // The kernel draws no random numbers while it runs (generators draw
    // theirs, seeded, when the scene loads): no generator state to carry.
    out.section("rng");
    out.u64(0);

    // the detector compares the energy balance with the one at the last
    // change of the scene: without it a restart would see a jump (issue 7)
    out.section("stability");
    const auto& b = w.monitor.detector.baseline;
    for (double v : {b.balance, b.body, b.boundary, b.dissipated, b.stored, b.potential, b.max_work}) out.f64(v);
    out.vec(b.lo);
    out.vec(b.hi);
}

void load_scalars(Cycle& w, CheckpointReader& in) {
    in.section("world");
    const std::uint32_t dim = in.u32();
    if (int(dim) != w.world.dim) in.fail("a " + std::to_string(dim) + "D state for a " + std::to_string(w.world.dim) + "D scene");
    w.world.time = in.f64();
    w.world.step_count = in.u64();
    w.world.last_dt = in.f64();
    w.world.gravity = in.vec();
    w.neighbours.rebuilds = in.u64();
    Energies& e = w.world.energies;
    for (double* v : {&e.kinetic, &e.strain, &e.body, &e.boundary, &e.slip, &e.dashpot, &e.local_damping, &e.bond_break})
        *v = in.f64();

    in.section("assignment");
    const std::uint64_t n_groups = in.u64();
    std::vector<std::string> groups;
    for (std::uint64_t g = 0; g < n_groups; ++g) groups.push_back(in.str());
    if (groups != w.assignment.group_names()) in.fail("its groups differ from the scene's (the scene is not the one that wrote it)");
    std::vector<int> cmat = in.column<int>();
    if (cmat.size() != w.assignment.table().size()) in.fail("the assignment table has the wrong size");
    for (int inst : cmat)
        if (inst < -1 || inst >= int(w.instances.size())) in.fail("the assignment table names model instance " + std::to_string(inst));
    w.assignment.set_table(std::move(cmat));
}

void load_fields(Cycle& w, CheckpointReader& in) {
    in.section("fields");
    const std::uint64_t n_fields = in.u64();
    std::vector<bool> seen(w.world.fields.size(), false);
    for (std::uint64_t f = 0; f < n_fields; ++f) {
        const std::string name = in.str();
        std::vector<double> values = in.column<double>();
        const int idx = w.world.fields.index(name);
        if (idx < 0) in.fail("body field '" + name + "' is registered by no plug-in this scene loads");
        if (values.size() != w.world.bodies.size()) in.fail("body field '" + name + "' has the wrong length");
        w.world.fields.column(idx) = std::move(values);
        seen[idx] = true;
    }
    for (std::size_t f = 0; f < seen.size(); ++f)  // a field new since the file was written starts at its default
        if (!seen[f]) w.world.fields.column(int(f)).assign(w.world.bodies.size(), w.world.fields.default_value(int(f)));
}

void load_contacts(Cycle& w, CheckpointReader& in) {
    in.section("contacts");
    const std::uint64_t n_inst = in.u64();
    if (n_inst != w.instances.size())
        in.fail("it holds " + std::to_string(n_inst) + " contact-model instances, the scene makes " +
                std::to_string(w.instances.size()));
    for (auto& inst : w.instances) {
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
                        w.host->library_of_model(model) + " (its slots: " + slot_list(*inst->desc) +
                        "); the contact history it holds would be lost — restart with the plug-in that wrote it");
            slot_of_file.push_back(found);
        }
        inst->balls.packed = w.forces.packs_balls(*inst);
        std::vector<BodyId> key1, key2;
        for (ContactSet* s : {&inst->balls, &inst->walls}) {
            load_set(*inst, *s, slot_of_file, in, key1, key2);
            for (std::size_t k = 0; k < s->size(); ++k) {
                const bool ok = s->end1[k] >= 0 && std::size_t(s->end1[k]) < w.world.bodies.size() && s->end2[k] >= 0 &&
                                std::size_t(s->end2[k]) < (s->with_wall ? w.world.walls.facets.size() : w.world.bodies.size());
                if (!ok) in.fail("a contact of model '" + model + "' names a body or facet that does not exist");
                if (row_key(w.world.bodies, w.world.walls, *s, k) != std::make_pair(key1[k], key2[k]))
                    in.fail("a contact of model '" + model + "' names bodies by index and by id that differ");
            }
        }
    }
}

void load_detection(Cycle& w, CheckpointReader& in) {
    in.section("detection");
    NeighbourLists::Saved lists;
    lists.invalidated = in.u8() != 0;
    w.prepared = in.u8() != 0;
    lists.position_at_build = in.vecs();
    lists.wall_motion = in.f64();
    const bool reference_missing = !lists.invalidated && lists.position_at_build.size() != w.world.bodies.size();
    w.neighbours.restore(std::move(lists));
    std::vector<double> k_trans = in.column<double>();
    std::vector<double> k_rot = in.column<double>();
    w.monitor.stiffness.restore(std::move(k_trans), std::move(k_rot));
    w.pass_contacts.end1_column() = in.column<std::int32_t>();
    w.pass_contacts.end2_column() = in.column<std::int32_t>();
    w.pass_contacts.wall_column() = in.column<std::uint8_t>();
    if (reference_missing)
        in.fail("the neighbour-list reference positions do not match the bodies");
    if (w.prepared && (w.monitor.stiffness.translational().size() != w.world.bodies.size() || w.monitor.stiffness.rotational().size() != w.world.bodies.size()))
        in.fail("the stiffness sums do not match the bodies");
}

void load_passes(Cycle& w, CheckpointReader& in) {
    in.section("passes");
    const std::uint64_t n_passes = in.u64();
    if (n_passes != w.passes.size())
        in.fail("it holds " + std::to_string(n_passes) + " passes, the scene runs " + std::to_string(w.passes.size()));
    for (PassInstance& p : w.passes) {
        const std::string name = in.str();
        if (name != p.desc->name) in.fail("pass '" + name + "' where the scene has '" + p.desc->name + "'");
        in.column<double>();  // properties it ran with
        const bool has_state = in.u8() != 0;
        const plab_pass_state_hooks* hooks = w.host->pass_state(name);
        if (!has_state) {
            if (hooks)
                in.fail("pass '" + name + "' now keeps private state (" + w.host->library_of_pass(name) +
                        ") but the file has none for it; it was written by an older build of that plug-in");
            continue;
        }
        const std::vector<unsigned char> bytes = in.column<unsigned char>();
        if (!hooks)
            in.fail("the file holds private state of pass '" + name + "' but the loaded library " +
                    w.host->library_of_pass(name) + " registers no state hooks for it (plab_pass_state_hooks)");
        if (hooks->load(p.state, bytes.data(), bytes.size()) != 0)
            in.fail("pass '" + name + "' (" + w.host->library_of_pass(name) + ") refused its saved state of " +
                    std::to_string(bytes.size()) + " bytes (written by another version of the plug-in?)");
    }
}

void load_log(Cycle& w, CheckpointReader& in) {
    in.section("bond_breaks");
    w.world.bond_breaks.resize(in.u64());
    for (BondBreak& b : w.world.bond_breaks) {
        b.step = in.u64();
        b.time = in.f64();
        b.id1 = in.u64();
        b.id2 = in.u64();
        b.point = in.vec();
        b.mode = int(in.u32());
        b.model = in.str();
    }

    in.section("rng");
    if (in.u64() != 0) in.fail("it holds random-number generator states this build has no use for");

    if (in.format() < 2) {  // no detector baseline saved: measure it at this state
        w.monitor.detector.measure_baseline(w.world.energies, w.world.bodies, w.world.walls, w.world.gravity);
        return;
    }
    in.section("stability");
    auto& b = w.monitor.detector.baseline;
    for (double* v : {&b.balance, &b.body, &b.boundary, &b.dissipated, &b.stored, &b.potential, &b.max_work})
        *v = in.f64();
    b.lo = in.vec();
    b.hi = in.vec();
}

// Sections in file order; bodies and walls come between the assignment
// table and the fields.
void save_cycle(const Cycle& w, CheckpointWriter& out) {
    save_scalars(w, out);
    save_bodies(w.world.bodies, out);
    save_walls(w.world.walls, out);
    save_fields(w, out);
    save_contacts(w, out);
    save_detection(w, out);
    save_passes(w, out);
    save_log(w, out);
}

void load_cycle(Cycle& w, CheckpointReader& in) {
    load_scalars(w, in);
    load_bodies(w.world.bodies, in);
    for (int g : w.world.bodies.group)
        if (g < 0 || g >= w.assignment.group_count()) in.fail("a body has group index " + std::to_string(g));
    load_walls(w.world.walls, w, in);
    load_fields(w, in);
    load_contacts(w, in);
    load_detection(w, in);
    load_passes(w, in);
    load_log(w, in);

    w.restored();
}

} // namespace

void save_world(const World& w, CheckpointWriter& out) { save_cycle(*w.cycle, out); }
void load_world(World& w, CheckpointReader& in) { load_cycle(*w.cycle, in); }

} // namespace plab
