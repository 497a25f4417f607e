// VTK XML PolyData writer. Binary frames use the appended-data layout of
// the VTK file-format documentation ("VTK XML formats", AppendedData): every
// array is a UInt64 byte count followed by its raw little-endian bytes, or,
// compressed, the zlib block header [blocks, block size, last block size,
// compressed sizes...] followed by the blocks (vtkZLibDataCompressor).
// zlib is Debian's libz: the compressor ParaView's reader expects.
#include "vtk_output.hpp"

#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <iomanip>
#include <sstream>
#include <type_traits>

namespace plab {

namespace {

static_assert(sizeof(double) == 8 && sizeof(float) == 4, "VTK Float64/Float32");

class VtpWriter {
public:
    explicit VtpWriter(const VtkOptions& opt) : opt_(opt) {}

    void points(const std::vector<double>& xyz) { points_ = real_array("", 3, xyz); }
    enum class Cells { verts, lines, polys };
    void cell_kind(Cells k) { kind_ = k; }
    void lines(bool l) { kind_ = l ? Cells::lines : Cells::verts; }
    void cells(const std::vector<std::int64_t>& connectivity, const std::vector<std::int64_t>& offsets) {
        n_cells_ = offsets.size();
        cells_ = array_xml("connectivity", 1, connectivity) + array_xml("offsets", 1, offsets);
    }
    void add_real(const std::string& name, int comps, const std::vector<double>& v) { data_ += real_array(name, comps, v); }
    template <class Int> void add_int(const std::string& name, const std::vector<Int>& v) { data_ += array_xml(name, 1, v); }
    // A table of names (ParaView shows it under Field Data): group names by index.
    void add_names(const std::string& name, const std::vector<std::string>& names);
    std::string finish(std::size_t n_points) const;

private:
    const VtkOptions& opt_;
    std::string points_, cells_, data_, field_data_, appended_;
    std::size_t n_cells_ = 0;
    Cells kind_ = Cells::verts;

    std::string real_array(const std::string& name, int comps, const std::vector<double>& v) {
        if (!opt_.float32) return array_xml(name, comps, v);
        return array_xml(name, comps, std::vector<float>(v.begin(), v.end()));
    }
    template <class T> std::string array_xml(const std::string& name, int comps, const std::vector<T>& v);
    void append_bytes(const void* data, std::size_t bytes);
};

template <class T> const char* vtk_type() {
    if constexpr (std::is_same_v<T, double>) return "Float64";
    else if constexpr (std::is_same_v<T, float>) return "Float32";
    else if constexpr (std::is_same_v<T, std::int32_t>) return "Int32";
    else return "Int64";
}

template <class T> std::string VtpWriter::array_xml(const std::string& name, int comps, const std::vector<T>& v) {
    std::ostringstream s;
    s << "<DataArray type=\"" << vtk_type<T>() << "\"" << (name.empty() ? "" : " Name=\"" + name + "\"")
      << " NumberOfComponents=\"" << comps << "\"";
    if (opt_.encoding == VtkOptions::Encoding::ascii) {
        s << " format=\"ascii\">\n" << std::setprecision(std::is_same_v<T, float> ? 8 : 15);
        for (const T& x : v) s << x << ' ';
        s << "\n</DataArray>\n";
        return s.str();
    }
    s << " format=\"appended\" offset=\"" << appended_.size() << "\"/>\n";
    append_bytes(v.data(), v.size() * sizeof(T));
    return s.str();
}

void VtpWriter::append_bytes(const void* data, std::size_t bytes) {
    const auto put = [&](std::uint64_t x) { appended_.append(reinterpret_cast<const char*>(&x), 8); };
    if (opt_.encoding == VtkOptions::Encoding::binary) {
        put(bytes);
        appended_.append(static_cast<const char*>(data), bytes);
        return;
    }
    constexpr std::size_t block = 1 << 16;
    const std::size_t blocks = bytes == 0 ? 0 : (bytes + block - 1) / block;
    const std::size_t header_at = appended_.size();
    put(blocks);
    put(block);
    put(blocks == 0 ? 0 : bytes - (blocks - 1) * block);
    appended_.append(8 * blocks, '\0');  // compressed sizes, filled below
    std::vector<Bytef> out(compressBound(block));
    for (std::size_t b = 0; b < blocks; ++b) {
        const std::size_t n = std::min(block, bytes - b * block);
        uLongf size = uLongf(out.size());
        if (compress2(out.data(), &size, static_cast<const Bytef*>(data) + b * block, uLong(n), Z_BEST_SPEED) != Z_OK)
            throw std::runtime_error("zlib could not compress a VTK array");
        const std::uint64_t s64 = size;
        std::memcpy(&appended_[header_at + 24 + 8 * b], &s64, 8);
        appended_.append(reinterpret_cast<const char*>(out.data()), size);
    }
}

// Field data strings as the VTK XML reader reads a vtkStringArray in ASCII:
// the characters' codes, each name ended by a 0.
void VtpWriter::add_names(const std::string& name, const std::vector<std::string>& names) {
    std::ostringstream s;
    s << "<DataArray type=\"String\" Name=\"" << name << "\" NumberOfTuples=\"" << names.size() << "\" format=\"ascii\">\n";
    for (const std::string& n : names) {
        for (unsigned char c : n) s << int(c) << ' ';
        s << "0 ";
    }
    s << "\n</DataArray>\n";
    field_data_ += s.str();
}

std::string VtpWriter::finish(std::size_t n_points) const {
    const bool appended = opt_.encoding != VtkOptions::Encoding::ascii;
    std::ostringstream s;
    s << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\""
      << " header_type=\"UInt64\""
      << (opt_.encoding == VtkOptions::Encoding::zlib ? " compressor=\"vtkZLibDataCompressor\"" : "") << ">\n<PolyData>\n";
    if (!field_data_.empty()) s << "<FieldData>\n" << field_data_ << "</FieldData>\n";
    // points carry the data of vertex cells, cells that of lines and polygons
    const bool on_cells = kind_ != Cells::verts;
    const char* cells = kind_ == Cells::verts ? "Verts" : kind_ == Cells::lines ? "Lines" : "Polys";
    const auto count = [&](Cells k) { return kind_ == k ? n_cells_ : 0; };
    s << "<Piece NumberOfPoints=\"" << n_points << "\" NumberOfVerts=\"" << count(Cells::verts)
      << "\" NumberOfLines=\"" << count(Cells::lines) << "\" NumberOfStrips=\"0\" NumberOfPolys=\"" << count(Cells::polys)
      << "\">\n<Points>\n" << points_ << "</Points>\n"
      << (on_cells ? "<CellData>\n" : "<PointData>\n") << data_ << (on_cells ? "</CellData>\n" : "</PointData>\n")
      << "<" << cells << ">\n" << cells_ << "</" << cells << ">\n"
      << "</Piece>\n</PolyData>\n";
    if (appended) s << "<AppendedData encoding=\"raw\">\n_" << appended_ << "\n</AppendedData>\n";
    s << "</VTKFile>\n";
    return s.str();
}

std::vector<double> flatten(const std::vector<Vec>& v) {
    std::vector<double> out;
    out.reserve(3 * v.size());
    for (const Vec& x : v) out.insert(out.end(), {x.x(), x.y(), x.z()});
    return out;
}

std::vector<std::int64_t> iota(std::size_t n, std::int64_t from, std::int64_t stride) {
    std::vector<std::int64_t> v(n);
    for (std::size_t i = 0; i < n; ++i) v[i] = from + std::int64_t(i) * stride;
    return v;
}

} // namespace

VtkOptions read_vtk_options(const Node& n) {
    n.allow_keys({"interval", "encoding", "precision", "contacts", "bonds", "pair_contacts", "walls", "bodies", "pebbles"});
    VtkOptions o;
    o.interval = n.at("interval").positive();
    if (n.has("encoding")) {
        const std::string e = n.at("encoding").choice({"binary", "zlib", "ascii"});
        o.encoding = e == "ascii" ? VtkOptions::Encoding::ascii : e == "zlib" ? VtkOptions::Encoding::zlib
                                                                              : VtkOptions::Encoding::binary;
    }
    if (n.has("precision")) o.float32 = n.at("precision").choice({"float64", "float32"}) == "float32";
    for (auto [key, flag] : {std::pair<const char*, bool*>{"contacts", &o.contacts}, {"bonds", &o.bonds},
                             {"pair_contacts", &o.pair_contacts}, {"walls", &o.walls}, {"bodies", &o.bodies},
                             {"pebbles", &o.pebbles}})
        if (n.has(key)) *flag = n.at(key).boolean();
    return o;
}

// The balls (all, or without the clumps' pebbles), column by column.
std::string balls_vtp(const World& w, const VtkOptions& opt) {
    VtpWriter v(opt);
    const Bodies& b = w.bodies;
    std::vector<std::size_t> shown;
    for (std::size_t i = 0; i < b.size(); ++i)
        if (opt.pebbles || b.clump.empty() || b.clump[i] < 0) shown.push_back(i);
    const auto pick = [&shown](const auto& column) {
        std::vector<std::decay_t<decltype(column[0])>> out;
        out.reserve(shown.size());
        for (std::size_t i : shown) out.push_back(column[i]);
        return out;
    };
    v.points(flatten(pick(b.position)));
    v.cells(iota(shown.size(), 0, 1), iota(shown.size(), 1, 1));
    v.add_real("radius", 1, pick(b.radius));
    const auto ids = pick(b.id);
    v.add_int("id", std::vector<std::int64_t>(ids.begin(), ids.end()));
    const auto groups = pick(b.group);
    v.add_int("group", std::vector<std::int32_t>(groups.begin(), groups.end()));
    v.add_names("group_names", w.group_names());
    v.add_real("velocity", 3, flatten(pick(b.velocity)));
    v.add_real("angular_velocity", 3, flatten(pick(b.angular_velocity)));
    v.add_real("force", 3, flatten(pick(b.force)));
    for (std::size_t f = 0; f < w.fields.names().size(); ++f)
        if (field_computed(w, int(f))) v.add_real(w.fields.names()[f], 1, pick(w.fields.column(int(f))));
    std::vector<double> stress;  // per-ball average stress, tension positive (row-major 3x3)
    stress.reserve(9 * shown.size());
    const auto sigma = ball_stress(w);
    for (std::size_t i : shown)
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) stress.push_back(sigma[i](r, c));
    v.add_real("stress", 9, stress);
    return v.finish(shown.size());
}

// Ball–ball contacts as lines between centres, with the contact force;
// which kinds are written is the scene's choice (VtkOptions).
std::string contacts_vtp(const World& w, const VtkOptions& opt) {
    VtpWriter v(opt);
    v.lines(true);
    std::vector<double> points, force, normal_force;
    std::vector<std::int32_t> bonded, model;
    for (std::size_t m = 0; m < w.model_count(); ++m) {
        const ContactTable s = w.model(m).balls();
        const bool at_distance = w.model(m).desc().range_kind == PLAB_RANGE_DISTANCE;
        if (at_distance && !opt.pair_contacts) continue;
        for (std::size_t k = 0; k < s.size(); ++k) {
            if (!s.active(k)) continue;
            const bool is_bond = s.bonded(k);
            if (!at_distance && !(is_bond ? opt.bonds : opt.contacts)) continue;
            bonded.push_back(is_bond);
            model.push_back(std::int32_t(m));
            for (std::size_t e : {s.end1(k), s.end2(k)}) {
                const Vec& p = w.bodies.position[e];
                points.insert(points.end(), {p.x(), p.y(), p.z()});
            }
            const Vec f = s.force(k), n = s.normal(k);
            force.insert(force.end(), {f.x(), f.y(), f.z()});
            normal_force.push_back(f.dot(n));
        }
    }
    v.points(points);
    v.cells(iota(points.size() / 3, 0, 1), iota(bonded.size(), 2, 2));
    v.add_real("force", 3, force);
    v.add_real("normal_force", 1, normal_force);
    v.add_int("bonded", bonded);
    v.add_int("model", model);
    std::vector<std::string> models;
    for (std::size_t m = 0; m < w.model_count(); ++m) models.push_back(w.model(m).model());
    v.add_names("model_names", models);
    return v.finish(points.size() / 3);
}

// Wall facets as lines (2D segments, 3D triangle edges).
std::string walls_vtp(const World& w, const VtkOptions& opt) {
    VtpWriter v(opt);
    v.lines(true);
    std::vector<double> points;
    std::vector<std::int32_t> wall_index;
    for (const Facet& f : w.walls.facets) {
        std::vector<Vec> pts;
        if (f.kind == FacetKind::segment) pts = {f.a, f.b};
        else if (f.kind == FacetKind::triangle) pts = {f.a, f.b, f.c, f.a};
        else continue;  // infinite planes are not drawn
        for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
            for (const Vec& p : {pts[k], pts[k + 1]}) points.insert(points.end(), {p.x(), p.y(), p.z()});
            wall_index.push_back(f.wall);
        }
    }
    v.points(points);
    v.cells(iota(points.size() / 3, 0, 1), iota(wall_index.size(), 2, 2));
    v.add_int("wall", wall_index);
    std::vector<std::string> names;
    for (const auto& wall : w.walls.walls) names.push_back(wall.name);
    v.add_names("wall_names", names);
    return v.finish(points.size() / 3);
}

// Each clump's surface (3D triangles, 2D edges) where it is now, with the
// clump's id, group and velocity per face.
std::string bodies_vtp(const World& w, const VtkOptions& opt) {
    VtpWriter v(opt);
    const Clumps& C = w.clumps;
    const bool edges = w.dim == 2;
    v.cell_kind(edges ? VtpWriter::Cells::lines : VtpWriter::Cells::polys);
    std::vector<double> points, velocity;
    std::vector<std::int64_t> connectivity, offsets, id;
    std::vector<std::int32_t> group;
    for (std::size_t c = 0; c < C.size(); ++c) {
        if (C.surface[c] < 0) continue;
        const BodySurface& s = C.surfaces[std::size_t(C.surface[c])];
        const std::int64_t base = std::int64_t(points.size() / 3);
        for (const Vec& local : s.vertices) {
            const Vec p = C.position[c] + C.orientation[c] * local;
            points.insert(points.end(), {p.x(), p.y(), p.z()});
        }
        const int corners = edges ? 2 : 3;
        for (const auto& f : s.faces) {
            for (int k = 0; k < corners; ++k) connectivity.push_back(base + f[std::size_t(k)]);
            offsets.push_back(std::int64_t(connectivity.size()));
            id.push_back(std::int64_t(C.id[c]));
            group.push_back(std::int32_t(C.group[c]));
            velocity.insert(velocity.end(), {C.velocity[c].x(), C.velocity[c].y(), C.velocity[c].z()});
        }
    }
    v.points(points);
    v.cells(connectivity, offsets);
    v.add_int("id", id);
    v.add_int("group", group);
    v.add_names("group_names", w.group_names());
    v.add_real("velocity", 3, velocity);
    return v.finish(points.size() / 3);
}

} // namespace plab
