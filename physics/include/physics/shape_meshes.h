// Triangle meshes of the rigid-body primitives and of convex hulls: for drawing them, and for
// tests that need a closed mesh with a known answer. Each is built as a RawMesh and welded by
// build_mesh, so it has the same particles, render vertices and normal slots as a loaded file;
// `Mesh::source` says what it is ("box 1 x 2 x 3").
#pragma once

#include "physics/convex_hull.h"
#include "physics/mesh.h"
#include "physics/vec3.h"

namespace softbody {

// Centred, 8 corners, 12 triangles facing outward. Sides are full lengths.
Mesh box_mesh(const Vec3d& size);

// An icosphere: the regular icosahedron with each triangle split in four `subdivisions` times
// (0 to 5; 10 * 4^s + 2 vertices), every vertex on the sphere. Centred, facing outward.
inline constexpr int kMostSphereSubdivisions = 5;
Mesh sphere_mesh(double radius, int subdivisions = 3);
// The same icosphere before welding: sphere_mesh gives what build_mesh makes of it.
RawMesh sphere_raw_mesh(double radius, int subdivisions = 3);

// A prism on a regular polygon of `segments` corners (3 or more) inscribed in the circle of
// `radius`, capped by fans from the centres of its ends; axis z, centred, facing outward.
Mesh cylinder_mesh(double radius, double height, int segments = 32);

// A hull's faces as triangle fans, each face flat shaded (its own normal: hard edges).
Mesh hull_mesh(const ConvexHull& hull);

}  // namespace softbody
