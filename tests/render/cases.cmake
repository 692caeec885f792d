# The screenshot cases, shared by the tests and by the bless target. Each case is one
# `softbody render` call producing one image; its reference is references/<case>.png.
# Paths are relative to this folder (the command runs here).
set(SCREENSHOT_SIZE 320x240)

set(SCREENSHOT_CASES resting falling bouncing sliding springs pointcloud hanging showcase rigid contacts reduced)

# A smooth body settled on the floor (contact shadow, smooth shading, the floor and its grid).
set(CASE_resting     --scene scenes/resting.json --at 4 --overlay none)
# A faceted body in the air: hard edges, a soft shadow away from it, the centre-of-mass marker.
set(CASE_falling     --scene scenes/falling.json --at 0.35 --overlay com)
# Squashed at the bottom of a bounce: normals recomputed from the deformed surface.
set(CASE_bouncing    --scene scenes/bouncing.json --at 0.6 --camera follow)
# Sliding with friction, seen side-on, with velocity arrows.
set(CASE_sliding     --scene scenes/sliding.json --at 0.2 --overlay velocity --camera yaw=-20,pitch=16,zoom=1.1)
# The springs overlay through a see-through body: compressed springs blue, stretched red.
set(CASE_springs     --scene scenes/springs.json --at 0.6 --overlay springs --body ghost --camera follow)
# A mesh with no faces: the particles are the body, with their shadows.
set(CASE_pointcloud  --scene scenes/pointcloud.json --at 0.6 --overlay particles)
# A body hanging from two pinned particles, the pins marked.
set(CASE_hanging     --scene scenes/hanging.json --at 1 --overlay pins)
# Rigid bodies: a box tumbling in the air with its omega and L arrows, a cylinder lying on the
# ground, a ball at rest (static vertex buffers drawn with model matrices, shadows, palette).
set(CASE_rigid       --scene scenes/rigid.json --at 0.3 --overlay angular,com)
# Bodies that meet: a soft cube landed on a seesaw's end, the plank on its fulcrum, a block
# thrown off the other end; the contacts overlay (points, normals, impulses) on rigid-rigid and
# soft-rigid contacts.
set(CASE_contacts    --scene scenes/seesaw.json --at 0.8 --overlay contacts --camera yaw=-30,pitch=14,zoom=0.8)
# A body above its particle budget: the knot's 5,760 vertices simulated on 600 particles (k 100
# N/m: a body of 600 holds its shape), its full-resolution surface drawn by skinning.
set(CASE_reduced     --scene scenes/reduced.json --at 1.0 --camera follow)
# The README's picture, larger: a soft ball squashed on landing.
set(CASE_showcase    --scene scenes/bouncing.json --at 0.6 --camera follow,yaw=-40,pitch=12 --size 640x360)

# Faults that must make a case fail: each one is that case rendered with a deliberate change.
set(NEGATIVE_CASES shift_x_1cm shift_z_1cm recolour no_ground flipped_normals no_shadow no_springs rigid_shift_1cm no_contacts particle_mesh)
set(NEGATIVE_shift_x_1cm     resting  --debug-offset 0.01,0,0)
set(NEGATIVE_shift_z_1cm     falling  --debug-offset 0,0,0.01)
set(NEGATIVE_recolour        resting  --body-color E8703A)
set(NEGATIVE_no_ground       resting  --no-ground)
set(NEGATIVE_flipped_normals bouncing --debug-flip-normals)
set(NEGATIVE_no_shadow       falling  --no-shadows)
set(NEGATIVE_no_springs      springs  --overlay none)
set(NEGATIVE_rigid_shift_1cm rigid    --debug-offset 0.01,0,0)
set(NEGATIVE_no_contacts     contacts --overlay none)
set(NEGATIVE_particle_mesh   reduced  --debug-particle-mesh)
