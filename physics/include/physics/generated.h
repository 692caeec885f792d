// Bodies and scenes made from a short name instead of a file, one place for all of them, so
// that what the bench measures, what the tests build and what the app opens can be the same:
//
//   cloud:N     N particles spread uniformly through a ball 1 m across (fixed seed), no faces:
//               a mesh (--mesh cloud:2500) or a scene of that one soft body (--scene cloud:2500,
//               with auto_substeps on)
//   ball:S      an icosphere 1 m across: the icosahedron with each triangle split in four S
//               times (S = 0 to 5; 10 * 4^S + 2 particles), a mesh or a scene as cloud:N is
//               (so are torus and lattice); a scene of one of these simulates every particle
//               (max_particles all), so the body the bench times is the body the app opens
//   torus:RxS   a closed torus 1.4 m across (centre line radius 0.5 m, tube radius 0.2 m), R
//               vertices around the centre line times S around the tube (R, S >= 3), smooth
//   lattice:A   A^3 particles on a cubic grid filling a 1 m cube (A = 2 to 73), no faces
//   cube:S      a closed cube 1 m a side, each face an S x S grid (S = 1 to 64; 6 S^2 + 2
//               particles, all on its surface)
//   sheet:N     a flat square sheet 1 m a side, N x N particles (N = 2 to 400), facing up; its
//               corners are vertices 0, N - 1, N (N - 1) and N^2 - 1
//   pile:N      a scene of N rigid bodies (boxes, spheres, cylinders and icosahedra, ball:0,
//               by turns, in layers) dropped into a fixed bin that grows with N
//   boxes:N     a scene of N boxes and balls by turns dropped into a bin as pile:N is
//   pyramid:L   a scene of a square pyramid of unit boxes, L layers (L x L at the bottom; 10
//               layers are 385 boxes, 20 are 2,870), standing on the ground
//   bin:N       N boxes 0.2 to 0.4 m a side and balls 0.1 to 0.2 m in radius by turns, 1,000
//               kg/m^3, no rolling resistance, friction 0.5 and restitution 0.2, into a bin of
//               four fixed walls: a scene built as another engine's comparison built it
//   stack:L     a pyramid of 1 m cubes of 1 kg, each exactly on four below and touching its
//               neighbours in the layer (no gap), friction 0.5
//   random:SEED a scene nobody tuned, from its seed (1 and up): two to eight boxes, balls and
//               cylinders of any size, density, speed, spin, restitution and friction, and a few
//               fixed obstacles in the air (what the contact fuzz test runs by the hundred)
//   A+B         the scenes A and B together: pile:100+cloud:1000 is the bench's mixed scene
//
// A name is generated when it has this form; any other text is a file path.
#pragma once

#include <string>
#include <string_view>

#include "physics/mesh.h"
#include "physics/scene_io.h"

namespace softbody {

// True for "cloud:N", "ball:S", "torus:RxS", "lattice:A", "cube:S", "sheet:N", "pile:N", "boxes:N", "pyramid:L",
// "bin:N", "stack:L", "random:SEED" and sums of them: a name,
// not a file.
bool is_generated(std::string_view name);

// The mesh a name makes ("cloud:N", "ball:S", "torus:RxS", "lattice:A", "cube:S", "sheet:N"); InputError for a count out of range or a scene-only name.
Mesh generated_mesh(std::string_view name);

// A mesh by the name a scene or --mesh gives: a generated one when the name has that form
// (generated_mesh), else the file at that path (load_mesh). The one place that tells the two
// apart, so the file reader reads files and knows no names.
Mesh open_mesh(const std::string& name);

// The scene a name makes; InputError as above. A soft body it holds is named "body".
Scene generated_scene(std::string_view name);

}  // namespace softbody
