// Mass properties of rigid bodies: volume, centre of mass (Eq. 20) and inertia tensor
// (Eq. 29-31), for the primitives of Table 1 and for any closed triangle mesh.
//
// Everything here is for a uniform density of 1 kg/m^3, so the mass equals the volume. For a
// real body multiply `inertia` by its density (or by mass / volume); the centre does not change.
// The tensor is J_ij = integral of (|r|^2 delta_ij - r_i r_j) dm with r measured from the centre
// of mass: moments of inertia on the diagonal, products of inertia with a minus sign off it.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "physics/mat3.h"
#include "physics/vec3.h"

namespace softbody {

struct MassProperties {
    double volume = 0.0;  // m^3 (and kg, at unit density)
    Vec3d center;         // centre of mass (Eq. 20), in the input's frame
    Mat3 inertia;         // J about `center`, in the input's axes (Eq. 29-31), for unit density
};

// Table 1. Each refuses (InputError, one line) a size that is not a positive finite number.
MassProperties box_mass_properties(const Vec3d& size);                  // full side lengths, centred
MassProperties sphere_mass_properties(double radius);                   // centred
MassProperties cylinder_mass_properties(double radius, double height);  // axis along z, centred

// A closed, consistently oriented triangle mesh, by volume integrals (Mirtich 1996; Eberly 2003,
// "Polyhedral Mass Properties"): the divergence theorem turns each integral over the solid into
// a sum over its triangles. The mesh may face outward or inward (a negative volume is flipped).
// The result means nothing for a mesh with holes: check it with is_closed_oriented when in doubt.
// Throws InputError for an index past the vertices, a coordinate that is not finite, or a mesh
// that encloses no volume.
MassProperties mesh_mass_properties(std::span<const Vec3d> vertices,
                                    std::span<const std::array<std::uint32_t, 3>> triangles);

// True when every edge is used by exactly two triangles, once in each direction: the mesh is
// closed and consistently oriented. False for no triangles or a triangle with a repeated corner.
bool is_closed_oriented(std::span<const std::array<std::uint32_t, 3>> triangles);

}  // namespace softbody
