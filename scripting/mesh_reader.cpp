// Binary STL, ASCII STL and Wavefront OBJ into triangles. Every refusal says
// where: the JSON path, the file, and the line (text) or the triangle
// (binary). The file is read whole, after a check that it is a regular file
// of bounded size, so a device, a pipe or a huge file cannot hang the load.
#include "mesh_reader.hpp"

#include <plab_host/errors.hpp>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace plab {

namespace fs = std::filesystem;

namespace {

// Where a refusal is: the JSON path, and the file as the scene names it.
struct Source {
    std::string where, shown;
    [[noreturn]] void fail(const std::string& at, const std::string& message) const {
        throw InputError(where, "\"" + shown + "\"" + (at.empty() ? "" : " " + at) + ": " + message);
    }
};

// "1 triangle", "2 triangles"
std::string count_of(std::uint64_t n, const std::string& noun) {
    return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

std::string lower(std::string s) {
    for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

std::string read_whole_file(const std::string& path, const Source& src) {
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (ec || !fs::exists(st)) src.fail("", "cannot open the mesh file (looked for " + path + ")");
    if (fs::is_directory(st)) src.fail("", "is a directory, not a mesh file: give its .stl or .obj file");
    if (!fs::is_regular_file(st)) src.fail("", "is not a regular file (a device, pipe or socket): give an .stl or .obj file");
    const std::uintmax_t bytes = fs::file_size(path, ec);
    if (ec) src.fail("", "cannot read its size: " + ec.message());
    if (bytes > kMaxMeshBytes)
        src.fail("", "the file has " + std::to_string(bytes) + " bytes, above the mesh limit of " +
                         std::to_string(kMaxMeshBytes) + " (about 5 million binary STL triangles)");
    std::ifstream f(path, std::ios::binary);
    if (!f) src.fail("", "cannot open the mesh file (" + path + ")");
    std::string data(std::size_t(bytes), '\0');
    f.read(data.data(), std::streamsize(bytes));
    if (std::size_t(f.gcount()) != data.size()) src.fail("", "the file could not be read whole");
    return data;
}

// A zero-area triangle: its doubled area against its longest edge squared
// (the sine of its smallest angle, roughly) below round-off of doubles.
bool degenerate(const Triangle& t) {
    const Vec ab = t[1] - t[0], ac = t[2] - t[0], bc = t[2] - t[1];
    const double longest = std::max({ab.squaredNorm(), ac.squaredNorm(), bc.squaredNorm()});
    return !(ab.cross(ac).norm() > 1e-12 * longest);
}

void keep(MeshFile& mesh, const Triangle& t, const std::string& at) {
    if (!degenerate(t)) {
        mesh.triangles.push_back(t);
        return;
    }
    if (++mesh.degenerate <= 3) mesh.degenerate_where += (mesh.degenerate_where.empty() ? "" : ", ") + at;
    else if (mesh.degenerate == 4) mesh.degenerate_where += ", ...";
}

// ---------------------------------------------------------------- binary STL

std::uint32_t u32_le(const std::string& d, std::size_t at) {
    const auto b = [&](std::size_t k) { return std::uint32_t(static_cast<unsigned char>(d[at + k])); };
    return b(0) | b(1) << 8 | b(2) << 16 | b(3) << 24;
}

double f32_le(const std::string& d, std::size_t at) {
    const std::uint32_t bits = u32_le(d, at);
    float v;
    std::memcpy(&v, &bits, sizeof v);
    return double(v);
}

// 80-byte header, a little-endian count n, then per triangle a normal (not
// used: walls have two faces), three vertices (float32) and 2 attribute bytes.
void read_binary_stl(const std::string& d, const Source& src, MeshFile& mesh) {
    mesh.format = "binary STL";
    const std::size_t n = u32_le(d, 80);
    for (std::size_t k = 0; k < n; ++k) {
        const std::size_t at = 84 + 50 * k + 12;
        Triangle t;
        for (int v = 0; v < 3; ++v)
            for (int c = 0; c < 3; ++c) t[v][c] = f32_le(d, at + 12 * std::size_t(v) + 4 * std::size_t(c));
        const std::string which = "triangle " + std::to_string(k + 1) + " of " + std::to_string(n);
        for (int v = 0; v < 3; ++v)
            if (!t[v].allFinite())
                src.fail("(binary STL) " + which, "vertex " + std::to_string(v + 1) + " is not finite (" +
                                                     short_number(t[v].x()) + ", " + short_number(t[v].y()) + ", " +
                                                     short_number(t[v].z()) + ")");
        keep(mesh, t, which);
    }
}

// ---------------------------------------------------------------- ASCII STL

// The words of one line of a text file, with its number for messages.
struct Line {
    std::size_t number = 0;
    std::vector<std::string> words;
    std::string text;  // as written, for messages (cut short)
};

std::vector<Line> split_lines(const std::string& d, char comment) {
    std::vector<Line> lines;
    std::size_t number = 0, start = 0;
    while (start < d.size()) {
        std::size_t end = d.find('\n', start);
        if (end == std::string::npos) end = d.size();
        ++number;
        std::string text = d.substr(start, end - start);
        start = end + 1;
        if (!text.empty() && text.back() == '\r') text.pop_back();  // (a Windows file)
        if (comment) text = text.substr(0, text.find(comment));
        Line l{number, {}, text.size() > 60 ? text.substr(0, 57) + "..." : text};
        std::istringstream s(text);
        for (std::string w; s >> w;) l.words.push_back(w);
        if (!l.words.empty()) lines.push_back(std::move(l));
    }
    return lines;
}

// A number written in full ("1e-3", not "1e-3x"); false otherwise.
bool parse_number(const std::string& word, double& out) {
    errno = 0;
    char* end = nullptr;
    out = std::strtod(word.c_str(), &end);
    return end != word.c_str() && *end == '\0';
}

Vec read_point(const Line& l, std::size_t first, const Source& src, const std::string& format) {
    const std::string at = "(" + format + ") line " + std::to_string(l.number);
    if (l.words.size() < first + 3) src.fail(at, "expected three coordinates, got \"" + l.text + "\"");
    Vec p;
    for (int c = 0; c < 3; ++c) {
        const std::string& w = l.words[first + std::size_t(c)];
        if (!parse_number(w, p[c])) src.fail(at, "\"" + w + "\" is not a number (in \"" + l.text + "\")");
        if (!std::isfinite(p[c])) src.fail(at, "the vertex is not finite: \"" + l.text + "\"");
    }
    return p;
}

// solid NAME / facet normal n n n / outer loop / vertex x y z (3) / endloop
// / endfacet ... / endsolid NAME, keywords in any case; several solids may
// follow one another. The stated normals are not used.
void read_ascii_stl(const std::string& d, const Source& src, MeshFile& mesh) {
    mesh.format = "ASCII STL";
    const std::vector<Line> lines = split_lines(d, '\0');
    enum { outside, in_solid, in_facet, in_loop, after_loop } state = outside;
    Triangle t;
    int vertices = 0;
    std::size_t facet_line = 0, facets = 0;
    const auto expect = [&](const Line& l, const std::string& what) {
        src.fail("(ASCII STL) line " + std::to_string(l.number), "expected " + what + ", got \"" + l.text + "\"");
    };
    for (const Line& l : lines) {
        const std::string kw = lower(l.words[0]);
        if (state == outside) {
            if (kw != "solid") expect(l, "\"solid\"");
            state = in_solid;
        } else if (state == in_solid) {
            if (kw == "endsolid") state = outside;
            else if (kw == "facet") { state = in_facet; facet_line = l.number; ++facets; }
            else expect(l, "\"facet\" or \"endsolid\"");
        } else if (state == in_facet) {
            if (kw != "outer" || l.words.size() < 2 || lower(l.words[1]) != "loop") expect(l, "\"outer loop\"");
            state = in_loop;
            vertices = 0;
        } else if (state == in_loop) {
            if (kw == "vertex" && vertices < 3) { t[std::size_t(vertices++)] = read_point(l, 1, src, "ASCII STL"); continue; }
            if (kw != "endloop" || vertices != 3)
                expect(l, vertices < 3 ? "\"vertex x y z\" (a facet has 3 vertices)" : "\"endloop\" after 3 vertices");
            state = after_loop;
        } else {
            if (kw != "endfacet") expect(l, "\"endfacet\"");
            keep(mesh, t, "the facet at line " + std::to_string(facet_line));
            state = in_solid;
        }
    }
    if (state != outside)
        src.fail("(ASCII STL)", "the file ends inside " + std::string(state == in_solid ? "a solid, without \"endsolid\"" : "a facet") +
                                    " after " + count_of(facets, "facet") + " (line " +
                                    std::to_string(lines.empty() ? 0 : lines.back().number) + "): truncated?");
}

bool starts_with_solid(const std::string& d) {
    std::size_t k = 0;
    while (k < d.size() && std::isspace(static_cast<unsigned char>(d[k]))) ++k;
    return lower(d.substr(k, 5)) == "solid";
}

// Binary when the size is the one its header's count gives; else ASCII when
// it starts with "solid" and holds no NUL byte (text never does, binary
// floats and attribute bytes nearly always); else a binary file of the
// wrong size (truncated, when shorter).
void read_stl(const std::string& d, const Source& src, MeshFile& mesh) {
    const std::uint64_t n = d.size() >= 84 ? u32_le(d, 80) : 0, expected = 84 + 50 * n;
    if (d.size() >= 84 && d.size() == expected) return read_binary_stl(d, src, mesh);
    if (starts_with_solid(d) && d.find('\0') == std::string::npos) return read_ascii_stl(d, src, mesh);
    if (d.size() < 84)
        src.fail("", "has " + std::to_string(d.size()) + " bytes: too short for a binary STL (an 84-byte header) and "
                     "not an ASCII STL (which starts with \"solid\")");
    if (d.size() < expected)
        src.fail("(binary STL)", "truncated: its header counts " + count_of(n, "triangle") + " (84 + 50 x " + std::to_string(n) +
                                     " = " + std::to_string(expected) + " bytes), the file has " + std::to_string(d.size()) +
                                     " bytes; triangle " + std::to_string((d.size() - 84) / 50 + 1) + " is incomplete");
    src.fail("(binary STL)", "its header counts " + count_of(n, "triangle") + " (84 + 50 x " + std::to_string(n) + " = " +
                                 std::to_string(expected) + " bytes), but the file has " + std::to_string(d.size()) +
                                 " bytes: a wrong count, or not an STL file");
}

// ---------------------------------------------------------------- OBJ

struct ObjFace {
    std::vector<long long> index;  // 0-based; positive ones checked once every vertex is read
    std::size_t line;
};

// One vertex of an `f` line: "v", "v/vt", "v//vn" or "v/vt/vn"; 1-based, or
// negative: counted back from the last vertex read so far.
long long face_vertex(const std::string& word, std::size_t read_so_far, const Line& l, const Source& src) {
    const std::string at = "(OBJ) line " + std::to_string(l.number);
    const std::string first = word.substr(0, word.find('/'));
    errno = 0;
    char* end = nullptr;
    const long long k = std::strtoll(first.c_str(), &end, 10);
    if (first.empty() || *end != '\0') src.fail(at, "\"" + word + "\" is not a vertex index (in \"" + l.text + "\")");
    if (k == 0 || errno == ERANGE) src.fail(at, "vertex index " + first + " is outside 1.." + std::to_string(read_so_far) +
                                                " (OBJ counts from 1, or back from -1)");
    if (k > 0) return k - 1;
    if (-k > (long long)read_so_far)
        src.fail(at, "vertex index " + first + " reaches before the first vertex (" + std::to_string(read_so_far) +
                         " vertices read so far)");
    return (long long)read_so_far + k;
}

// v x y z [w] and f a b c ... (polygons fan-triangulated from their first
// vertex: right for the convex polygons exporters write); texture, normal,
// grouping and material statements are not needed for a wall's shape.
void read_obj(const std::string& d, const Source& src, MeshFile& mesh) {
    mesh.format = "OBJ";
    std::vector<Vec> vertices;
    std::vector<ObjFace> faces;
    static const char* const not_shape[] = {"vt", "vn", "vp", "o", "g", "s", "usemtl", "mtllib", "l", "p"};
    for (const Line& l : split_lines(d, '#')) {
        const std::string& kw = l.words[0];
        if (kw == "v") {
            vertices.push_back(read_point(l, 1, src, "OBJ"));
        } else if (kw == "f") {
            if (l.words.size() < 4)
                src.fail("(OBJ) line " + std::to_string(l.number), "a face needs at least 3 vertices, got \"" + l.text + "\"");
            ObjFace f{{}, l.number};
            for (std::size_t k = 1; k < l.words.size(); ++k) f.index.push_back(face_vertex(l.words[k], vertices.size(), l, src));
            faces.push_back(std::move(f));
        } else if (std::find(std::begin(not_shape), std::end(not_shape), kw) == std::end(not_shape) && mesh.ignored.empty()) {
            mesh.ignored = "\"" + kw + "\" (line " + std::to_string(l.number) + ")";
        }
    }
    for (const ObjFace& f : faces) {
        for (const long long k : f.index)
            if (k >= (long long)vertices.size())
                src.fail("(OBJ) line " + std::to_string(f.line), "vertex index " + std::to_string(k + 1) + " is outside 1.." +
                                                                 std::to_string(vertices.size()) + " (the file has " +
                                                                 std::to_string(vertices.size()) + " vertices)");
        for (std::size_t k = 1; k + 1 < f.index.size(); ++k)
            keep(mesh, {vertices[std::size_t(f.index[0])], vertices[std::size_t(f.index[k])], vertices[std::size_t(f.index[k + 1])]},
                 "line " + std::to_string(f.line));
    }
}

} // namespace

MeshFile read_mesh(const std::string& path, const std::string& shown, const std::string& where) {
    const Source src{where, shown};
    const std::string ext = lower(fs::path(shown).extension().string());
    if (ext != ".stl" && ext != ".obj")
        src.fail("", "unknown mesh format \"" + ext + "\": give an .stl (binary or ASCII) or an .obj file");
    const std::string data = read_whole_file(path, src);
    MeshFile mesh;
    if (ext == ".stl") read_stl(data, src, mesh);
    else read_obj(data, src, mesh);
    if (mesh.triangles.empty())
        src.fail("(" + mesh.format + ")", "holds no triangle" + (mesh.degenerate ? " of non-zero area (" + std::to_string(mesh.degenerate) +
                                                                            " zero-area ones left out)" : std::string()));
    return mesh;
}

} // namespace plab
