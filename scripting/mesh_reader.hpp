// Triangle meshes from files: binary STL, ASCII STL and Wavefront OBJ, for
// mesh walls (wall_generators.cpp) and, later, meshed rigid bodies. The
// reader returns the triangles in the file's own coordinates and units;
// placing them in the scene (scale, rotate, translate) is the caller's.
#pragma once

#include <plab_host/mass_properties.hpp>  // Triangle

#include <cstdint>
#include <string>
#include <vector>

namespace plab {

struct MeshFile {
    std::vector<Triangle> triangles;  // in the file's order (an OBJ polygon fan-triangulated in place)
    std::string format;               // "binary STL", "ASCII STL" or "OBJ"
    // Zero-area triangles are left out (a CAD export often holds slivers of
    // collinear vertices; they have no face a ball could touch): how many,
    // and where the first few were (a triangle number or a line).
    std::size_t degenerate = 0;
    std::string degenerate_where;
    std::string ignored;  // OBJ statements left out that are not v/f/vt/vn/... (e.g. "curv"), for a warning
};

// The largest mesh file read (a binary STL of ~5 million triangles).
constexpr std::uintmax_t kMaxMeshBytes = std::uintmax_t(256) << 20;

// Reads `path` (found by the caller) as STL or OBJ by its extension
// (.stl/.obj, any case); a binary STL is told from an ASCII one by its size,
// 84 + 50 n bytes for the n triangles its header counts, not by a leading
// "solid", which some binary files have too. Every refusal is an
// InputError at `where` (the JSON path of the file's name) naming `shown`
// (the file as the scene wrote it) and the line or triangle: a file that
// is not a regular file or is too big, a truncated file, a non-finite
// vertex, a face index out of range, a file with no triangle left.
MeshFile read_mesh(const std::string& path, const std::string& shown, const std::string& where);

} // namespace plab
