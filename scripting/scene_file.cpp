// Reading a scene file: only a regular file of bounded size, parsed without
// deep recursion, with errors that say where in the file (the JSON path of
// the value being read) and what.
#include "simulation.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <vector>

namespace plab {

namespace fs = std::filesystem;

namespace {

// Deeper than any scene needs; it bounds the recursion of every later
// reader of the value (messages print values, validators descend them).
constexpr int kMaxDepth = 64;

std::uintmax_t max_scene_bytes() {
    if (const char* env = std::getenv("PLAB_MAX_SCENE_BYTES")) return std::strtoull(env, nullptr, 10);
    return std::uintmax_t(256) << 20;
}

void check_scene_path(const std::string& path) {
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (ec || !fs::exists(st)) throw InputError(path, "cannot open the scene file");
    if (fs::is_directory(st)) throw InputError(path, "is a directory, not a scene file: give its .json file");
    if (!fs::is_regular_file(st))
        throw InputError(path, "is not a regular file (a device, pipe or socket): give a .json scene file");
    const std::uintmax_t bytes = fs::file_size(path, ec), limit = max_scene_bytes();
    if (!ec && bytes > limit)
        throw InputError(path, "the file has " + std::to_string(bytes) + " bytes, above the scene limit of " +
                                   std::to_string(limit) + " (raise it with PLAB_MAX_SCENE_BYTES)");
}

// The JSON path of the value the parser is reading, kept from its events.
class PathTracker {
public:
    bool on(int depth, json::parse_event_t event, const json& parsed) {
        using E = json::parse_event_t;
        switch (event) {
        case E::object_start:
        case E::array_start:
            next_element();
            if (depth >= kMaxDepth)
                throw InputError(path(false), "JSON nested deeper than " + std::to_string(kMaxDepth) + " levels");
            frames_.push_back({event == E::array_start, -1, {}});
            break;
        case E::key:
            frames_.back().key = parsed.get<std::string>();
            if (!frames_.back().keys.insert(frames_.back().key).second)  // nlohmann keeps the last silently
                throw InputError(path(false), "the key appears twice in one object; give it once");
            break;
        case E::value: next_element(); break;
        case E::object_end:
        case E::array_end: frames_.pop_back(); break;
        }
        return true;
    }
    // the path of the value read last, or (pending) of the one being read:
    // in an array, the element after the last; the first 8 levels only
    std::string path(bool pending) const {
        std::string p = "scene";
        for (std::size_t i = 0; i < frames_.size() && i < 8; ++i) {
            const Frame& f = frames_[i];
            const bool next = pending && i + 1 == frames_.size();
            p += f.array ? "[" + std::to_string(f.index + (next ? 1 : 0)) + "]" : "." + f.key;
        }
        return frames_.size() > 8 ? p + "..." : p;
    }

private:
    struct Frame {
        bool array;
        long index;  // the last element read
        std::string key;
        std::set<std::string> keys;  // of an object, so far
    };
    void next_element() {
        if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
    }
    std::vector<Frame> frames_;
};

} // namespace

json parse_scene_text(const std::string& text, const std::string& name) {
    if (const auto nul = text.find('\0'); nul != std::string::npos)
        throw InputError(name, "a NUL byte at offset " + std::to_string(nul) + ": a scene is JSON text");
    PathTracker where;
    try {
        return json::parse(text, [&where](int depth, json::parse_event_t e, json& v) { return where.on(depth, e, v); });
    } catch (const json::out_of_range& e) {  // a number beyond the range of a double
        throw InputError(name + ": " + where.path(true), std::string(e.what()).substr(std::string(e.what()).find(']') + 2) +
                                                        ": beyond the largest double, 1.8e308");
    } catch (const json::parse_error& e) {
        throw InputError(name, std::string("malformed JSON: ") + e.what());
    }
}

json read_scene_file(const std::string& path) {
    check_scene_path(path);
    std::ifstream f(path, std::ios::binary);
    if (!f) throw InputError(path, "cannot open the scene file");
    std::stringstream buf;
    buf << f.rdbuf();
    return parse_scene_text(buf.str(), path);
}

} // namespace plab
