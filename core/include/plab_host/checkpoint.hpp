// Checkpoints: the complete state of a World in a versioned binary file, so a
// run stopped at step k and restarted gives bit-for-bit the state the
// uninterrupted run has at every later step (docs/restart.md, which also
// lists the format versions).
//
// File layout: the magic "PLABCKPT", the format version (u32), an endianness
// marker (u32 0x01020304 as written) and the CRC-32 of those 16 bytes, then
// named sections. A section is its name (u64 length, characters), the length
// of its contents (u64), the contents and a CRC-32 (u32) of the contents
// followed by the name and length as written. The reader checks a section's
// CRC before it parses the section, so a damaged file is refused with the
// name of the damaged section, and a foreign one with the name of what was
// expected. Contact history is stored by slot name: a model that gained a
// slot since the file was written loads it with the slot's default; a model
// that lost one is refused, naming the slot.
#pragma once

#include <plab_host/types.hpp>

#include <cstdint>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace plab {

// The format version this build writes, and the oldest it reads (what each
// version changed: docs/restart.md). Versions before kCheckpointFramedFormat
// have no lengths or checksums.
constexpr std::uint32_t kCheckpointFormat = 7;
constexpr std::uint32_t kCheckpointOldestFormat = 1;
constexpr std::uint32_t kCheckpointFramedFormat = 3;

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
    CheckpointWriter(CheckpointWriter&&) = default;
    CheckpointWriter& operator=(CheckpointWriter&&) = default;
    // A writer to a file that is never committed removes its `path`.tmp.
    ~CheckpointWriter();
    // A checkpoint file: the header, then sections streamed to `path`.tmp
    // instead of held in memory (a million-ball checkpoint is hundreds of
    // MB); commit() renames it to `path`, so a run killed while writing
    // leaves the previous file.
    static CheckpointWriter to_file(const std::string& path);
    void commit();
    // Whole sections from take() of a writer in memory.
    void append(const std::string& sections);
    // Ends the section being written (its length and CRC-32), begins `name`.
    void section(const std::string& name);
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
    // The sections written, the last one ended; the writer is spent.
    std::string take();

private:
    void raw(const void* p, std::size_t n);  // a section's contents: counted and checksummed
    void put(const void* p, std::size_t n);  // as it is
    void end_section();
    std::string data_;
    std::unique_ptr<std::ofstream> file_;
    std::string path_;
    std::uint64_t written_ = 0;  // bytes put so far
    // the section being written: where its length goes, its header as
    // written (name and a placeholder length), its contents' length and CRC
    bool open_ = false;
    std::uint64_t length_at_ = 0, length_ = 0;
    std::string header_;
    std::uint32_t crc_ = 0;
};

class CheckpointReader {
public:
    // Reads and checks the header; throws CheckpointError saying why a file
    // is not a checkpoint this build can load.
    explicit CheckpointReader(const std::string& path);
    std::uint32_t format() const { return format_; }
    const std::string& path() const { return path_; }
    // Reads a section's name and checks it is the one expected here, and
    // (framed formats) that the section is read whole, and its CRC-32.
    void section(const std::string& name);
    // After the last section: nothing is left unread.
    void finish();
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
    void read_header();
    void raw(void* p, std::size_t n);
    std::uint64_t count(std::size_t element_bytes);  // a length that fits in what is left
    std::uint64_t limit() const { return framed_ && !section_.empty() ? end_ : size_; }
    void close_section();  // checks the section was read to its end, skips its CRC
    void check_crc(const std::string& name, std::uint64_t header_at);
    std::string path_;
    std::ifstream file_;
    std::string section_;
    std::uint64_t size_ = 0, pos_ = 0;  // the file's length and the read position
    std::uint64_t end_ = 0;  // framed: the end of the section's contents
    std::uint32_t format_ = 0;
    bool framed_ = false;
};

class World;
// The world's complete state. `w` of load_world() must be built from the
// same scene (groups, model instances, passes, fields registered); its state
// is replaced by the file's.
void save_world(const World& w, CheckpointWriter& out);
void load_world(World& w, CheckpointReader& in);

} // namespace plab
