// Checkpoint file format (plab_host/checkpoint.hpp): the header, the framed
// sections, and a world as the sections its subsystems save and restore
// (world/cycle_checkpoint.hpp), in file order. Everything a later step reads
// is saved as it is, derived columns included (contact geometry, per-body
// stiffness sums, the contact list passes see, the Verlet reference
// positions): recomputing them after a restart would use whole-step
// velocities where the uninterrupted run used half-step ones, and the answer
// would drift in the last bits.
#include <plab_host/checkpoint.hpp>

#include "world/cycle.hpp"
#include "world/cycle_checkpoint.hpp"

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

void save_world(const World& w, CheckpointWriter& out) {
    for (const CheckpointSection& s : checkpoint_sections(*w.cycle)) s.save(out);
}

void load_world(World& w, CheckpointReader& in) {
    for (const CheckpointSection& s : checkpoint_sections(*w.cycle)) s.load(in);
    w.cycle->restored();
}

} // namespace plab
