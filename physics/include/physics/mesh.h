// A mesh as the simulation and the renderer need it: one particle per distinct vertex
// position (Listing 8: "a particle at the location of each vertex"), plus the render vertices
// and triangles that map back onto those particles.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "physics/vec3.h"

namespace softbody {

// All pairs cost N(N-1)/2 springs a force evaluation; beyond this it cannot run usefully. A
// mesh with more vertices is simulated on a reduced set of them (mesh_reduce.h).
inline constexpr std::size_t kMaxParticles = 20000;
// Distinct vertex positions a mesh file may have: a bound on the time and memory of welding
// and reducing it (about a second per 100,000 vertices), and ten times the largest
// widely used test scans (35,947 vertices for the scanned bunny).
inline constexpr std::size_t kMaxMeshParticles = 400'000;
// Triangles a file may hold (after splitting its polygons): fifty times what a closed mesh on
// kMaxParticles vertices has, and a bound on the memory a hostile file can ask for.
inline constexpr std::size_t kMaxTriangles = 1'000'000;

// A face corner as written in the file: indices into the file's positions, normals and
// texture coordinates (-1 where the file gives none).
struct Corner {
    std::int32_t position = -1;
    std::int32_t normal = -1;
    std::int32_t uv = -1;
    bool operator==(const Corner&) const = default;
};

// What a file holds, before welding. Faces are already triangulated (3 corners each).
struct RawMesh {
    std::vector<Vec3> positions;
    std::vector<Vec3> normals;  // a file normal that is not a finite number is kept as (0, 0, 0)
    std::vector<std::array<float, 2>> uvs;
    std::vector<Corner> triangle_corners;
    // What the file got wrong that does not touch the positions and was set aside (one line
    // each, naming the file and line): for whoever shows them. The library never prints.
    std::vector<std::string> warnings;
};

// One vertex the GPU draws. Several render vertices may share a particle (UV seams, hard
// edges); they move together. Corners with the same normal_slot share one smooth normal.
struct RenderVertex {
    std::uint32_t particle = 0;
    std::uint32_t normal_slot = 0;
    std::array<float, 2> uv{0.0f, 0.0f};
};

struct Mesh {
    std::string source;                               // where it came from (for messages)
    std::vector<Vec3> positions;                      // one per particle, file units
    std::vector<std::uint32_t> vertex_to_particle;    // file vertex index -> particle
    std::vector<RenderVertex> render_vertices;
    std::vector<std::uint32_t> triangles;             // 3 render-vertex indices each
    std::uint32_t normal_slot_count = 0;
    bool has_uvs = false;
    std::vector<std::string> warnings;                // the RawMesh's, passed on

    std::size_t particle_count() const { return positions.size(); }
    std::size_t triangle_count() const { return triangles.size() / 3; }
};

// Loads an OBJ (read by tinyobjloader) or an OFF file, chosen by the extension, and welds it.
// Files only: a generated name (cloud:N, ...) is open_mesh's to tell apart (generated.h).
// Throws InputError with the file (and line) for a missing, unreadable, non-regular (a folder,
// a pipe, a device) or malformed file, or for a mesh without usable vertices, with more than
// kMaxMeshParticles particles or more than kMaxTriangles triangles.
//
// What would put a particle in the wrong place is refused: a vertex coordinate that is not a
// finite number, a face vertex index that names no vertex, a 4-D or binary OFF file, UTF-16
// text. What only the drawing uses is forgiven, with one warning line per kind of fault in
// `warnings`: a face's normal or texture-coordinate index that names none the file defines
// (that corner goes without; normals are recomputed anyway), a normal or texture coordinate
// that is not a finite number. Forgiven silently, as other readers do: a comment after a
// face's indices, a face corner that ends with '/' ("1/", "1//"), a UTF-8 byte-order mark,
// material files that are named but absent (never opened), OFF's colour, normal and texture
// columns (COFF, NOFF, STOFF...), and an OFF file without its optional "OFF" keyword.
Mesh load_mesh(const std::string& path);

// The parsers on their own (used by load_mesh, the tests and the fuzzers). Polygons are split
// into triangles in time linear in their corners: a quad along its shorter diagonal, a larger
// polygon as a fan from its first corner (exact for the convex polygons exporters write; a
// concave one's fan overlaps itself, which only the rendering shows: particles and springs
// come from the vertices alone).
RawMesh parse_obj_text(const std::string& text, const std::string& origin);
RawMesh parse_off_text(const std::string& text, const std::string& origin);

// Welds coincident positions (within 1e-6 of the bounding-box diagonal) into one particle,
// keeping first-seen order, and builds render vertices and normal slots. Triangles that
// collapse onto fewer than three particles are dropped. The RawMesh's warnings are passed on.
Mesh build_mesh(const RawMesh& raw, const std::string& source);

// The triangles on particles rather than render vertices, three particle indices each: the
// solid the mesh encloses, for its mass properties (Eq. 29-31) and hull.
std::vector<std::array<std::uint32_t, 3>> particle_triangles(const Mesh& mesh);

}  // namespace softbody
