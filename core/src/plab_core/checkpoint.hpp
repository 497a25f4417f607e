// Checkpoints: the complete state of a World in a versioned binary file, so a
// run stopped at step k and restarted gives bit-for-bit the state the
// uninterrupted run has at every later step (docs/restart.md).
//
// File layout: the magic "PLABCKPT", the format version (u32), an endianness
// marker (u32 0x01020304 as written), then named sections. Every section
// starts with its name, so a damaged or foreign file is refused with the name
// of what was expected. Contact history is stored by slot name: a model that
// gained a slot since the file was written loads it with the slot's default;
// a model that lost one is refused, naming the slot.
#pragma once

#include "world.hpp"

#include <cstdint>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace plab {

// Format versions this build writes and reads.
//   1  the first
//   2  adds the section "stability": the instability detector's energy and
//      domain baseline (a version-1 file re-measures it at the restart step)
constexpr std::uint32_t kCheckpointFormat = 2;
constexpr std::uint32_t kCheckpointOldestFormat = 1;

// A checkpoint that cannot be written or loaded; the message says why.
class CheckpointError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

class CheckpointWriter {
public:
    // Sections in memory, without the file header: a part of a checkpoint
    // to append() to a file's writer later.
    CheckpointWriter() = default;
    // A checkpoint file: the header, then sections streamed to `path`.tmp
    // instead of held in memory (a million-ball checkpoint is hundreds of
    // MB); commit() renames it to `path`, so a run killed while writing
    // leaves the previous file.
    static CheckpointWriter to_file(const std::string& path);
    void commit();
    void append(const std::string& bytes) { raw(bytes.data(), bytes.size()); }
    void section(const std::string& name) { str(name); }
    void u8(std::uint8_t v) { raw(&v, 1); }
    void u32(std::uint32_t v) { raw(&v, sizeof v); }
    void u64(std::uint64_t v) { raw(&v, sizeof v); }
    void f64(double v) { raw(&v, sizeof v); }
    void str(const std::string& s) { u64(s.size()); raw(s.data(), s.size()); }
    void vec(const Vec& v) { raw(v.data(), 3 * sizeof(double)); }
    template <class T> void column(const std::vector<T>& v) {
        u64(v.size());
        if (!v.empty()) raw(v.data(), v.size() * sizeof(T));
    }
    void vecs(const std::vector<Vec>& v) {
        u64(v.size());
        for (const Vec& x : v) vec(x);
    }
    const std::string& bytes() const { return data_; }
    std::string take() { return std::move(data_); }  // the bytes, without a copy; the writer is spent

private:
    void raw(const void* p, std::size_t n) {
        if (file_) file_->write(static_cast<const char*>(p), std::streamsize(n));
        else data_.append(static_cast<const char*>(p), n);
    }
    std::string data_;
    std::unique_ptr<std::ofstream> file_;
    std::string path_;
};

class CheckpointReader {
public:
    // Reads and checks the header; throws CheckpointError saying why a file
    // is not a checkpoint this build can load.
    explicit CheckpointReader(const std::string& path);
    std::uint32_t format() const { return format_; }
    const std::string& path() const { return path_; }
    // Reads a section name and checks it is the one expected here.
    void section(const std::string& name);
    std::uint8_t u8() { std::uint8_t v; raw(&v, 1); return v; }
    std::uint32_t u32() { std::uint32_t v; raw(&v, sizeof v); return v; }
    std::uint64_t u64() { std::uint64_t v; raw(&v, sizeof v); return v; }
    double f64() { double v; raw(&v, sizeof v); return v; }
    std::string str();
    Vec vec() { Vec v; raw(v.data(), 3 * sizeof(double)); return v; }
    template <class T> std::vector<T> column() {
        const std::uint64_t n = count(sizeof(T));
        std::vector<T> v(n);
        if (n) raw(v.data(), n * sizeof(T));
        return v;
    }
    std::vector<Vec> vecs() {
        const std::uint64_t n = count(3 * sizeof(double));
        std::vector<Vec> v(n);
        for (auto& x : v) x = vec();
        return v;
    }
    [[noreturn]] void fail(const std::string& why) const;

private:
    void raw(void* p, std::size_t n);
    std::uint64_t count(std::size_t element_bytes);  // a length that fits in what is left
    std::string path_;
    std::ifstream file_;
    std::string section_;
    std::uint64_t size_ = 0, pos_ = 0;  // the file's length and the read position
    std::uint32_t format_ = 0;
};

// The World's complete state (a friend of World).
struct WorldCheckpoint {
    static void save(const World& w, CheckpointWriter& out);
    // `w` must be built from the same scene (groups, model instances, passes,
    // fields registered); its state is replaced by the file's.
    static void load(World& w, CheckpointReader& in);

private:
    // one pair per group of sections, in file order
    static void save_scalars(const World& w, CheckpointWriter& out);  // world, assignment
    static void save_fields(const World& w, CheckpointWriter& out);
    static void save_contacts(const World& w, CheckpointWriter& out);
    static void save_detection(const World& w, CheckpointWriter& out);
    static void save_passes(const World& w, CheckpointWriter& out);
    static void save_log(const World& w, CheckpointWriter& out);  // bond_breaks, rng
    static void load_scalars(World& w, CheckpointReader& in);
    static void load_fields(World& w, CheckpointReader& in);
    static void load_contacts(World& w, CheckpointReader& in);
    static void load_detection(World& w, CheckpointReader& in);
    static void load_passes(World& w, CheckpointReader& in);
    static void load_log(World& w, CheckpointReader& in);
};

} // namespace plab
