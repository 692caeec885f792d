// Internal to the physics library: islands of rigid bodies, and their sleep (World's members in
// sleep.cpp; the state, SleepState, in world.h).
//
// Islands: rigid bodies joined by the tick's touching contacts (closer than kSleepTouch as the
// tick ended, or pushing) and by springs between two of them. Fixed bodies and the ground join
// nothing: two boxes resting side by side on the floor are two islands. A contact only within
// reach joins nothing either: a body merely near a restless one (a ball rolling on for ever)
// is not kept awake by it.
//
// A body comes to rest when every point of it is slower than kSleepSpeed: |v| + |w| r <
// kSleepSpeed, r its bounding radius (the bench's measure of "moving", app/soundness.h). It stays
// at rest while it goes nowhere: no point further than kSleepDrift from where it was as its rest
// began (the centre's move plus r times the angle it turned), none faster than kTwitchSpeed. And
// it is not at rest while it is being pushed out of an overlap: its deepest contact both deeper
// than kSleepDepth and shallower than a tick before by kSleepDepthShrink. Its rest time counts up
// by dt each tick it is at rest, and falls back to 0 the tick it is not.
//
// An island falls asleep at the end of a tick when
//   - every body in it has been at rest for kTimeToSleep,
//   - it leans on something that does not move: a contact with the ground or a fixed body, or a
//     spring to a fixed point (a body drifting slowly through empty space is not at rest, it
//     is in motion that nothing will stop: it never sleeps),
//   - nothing that never sleeps holds it: no soft body's particle coming at it (into its surface
//     at kSleepSpeed or faster) or soft triangle within reach, no spring to a soft body, no grab.
//     A soft body resting on it does not hold it: its particles lie on it as on a fixed body
//     while it sleeps.
// Its bodies' P and L become exactly 0, and its contacts are set aside in the island's own list
// (SleepState::contacts).
// A sleeping body is not integrated, has no contacts found with the ground, fixed or other
// sleeping bodies, and is in no solver: it costs its box in the broad phase and nothing else
// (nothing at all when every rigid body sleeps: then the broad phase does not run).
//
// An island wakes (every body in it, rest times back to 0, its contacts back as the warm start
// of the solver, so a stack picks up the impulses that held it) when
//   - a contact is found between one of its bodies and an awake body that touches it or reaches
//     it in the tick (its gap less the approach speed times dt within kSleepTouch), or a
//     particle coming at it, or a soft body's triangle comes within reach of one (the tick it
//     happens, before its contacts are solved: those it did not have asleep are added,
//     World::add_woken_contacts).
//     An awake body within reach that does not touch leaves it asleep: the solver takes it as
//     static, as a fixed body, and stops the awake one at its surface,
//   - the app grabs one of its bodies (World::set_grab) or sets its material,
//   - any key changes (set_settings, set_def): every island wakes.
// With `sleeping` false nothing falls asleep (the rest times still count, for the inspector).
//
// Nothing here depends on the thread count, and an island whose bodies never come to rest never
// sleeps: such a scene runs bit for bit as it does with `sleeping` off.
#pragma once

namespace softbody {

// m/s: a point slower than this is at rest. 5 cm/s: a box sliding this
// slowly on friction 0.4 stops within v^2 / (2 mu g) = 0.3 mm anyway, and one lifted this fast
// rises 0.13 mm, so a body this slow for half a second is resting, not on its way anywhere; and
// a pile's bodies, held by many contacts, keep a jitter of a few cm/s that a lower threshold
// would not let sleep (measured: physics/README.md, "Choices the physics makes").
inline constexpr double kSleepSpeed = 0.05;
// m: a body with a contact deeper than this is not at rest, however slow: it is still being
// pushed out of an overlap, slowly (the push apart is overdamped, contact_solver.h), and asleep
// it would stay that deep. Resting contacts in a pile of
// boxes stand up to 1 to 2 mm deep (measured: with 1 mm here, 56 of the 100 boxes of the pile
// in tests/physics/sleep_test.cpp sleep after 10 s; with 2 mm, over 90).
inline constexpr double kSleepDepth = 2e-3;
// m a tick: an overlap coming out slower than this (5 mm/s) is not coming out: a box wedged
// 2.09 mm into another by its neighbours stood there, its depth the same to the micrometre tick
// after tick, and kept its pile awake for ever. It sleeps as deep as it stood awake. (The push
// apart takes a 2 mm overlap out at about 2 cm/s: ContactSettings.)
inline constexpr double kSleepDepthShrink = 1e-4;
// s: how long every body of an island is at rest before it sleeps. A rest time is a sum of dt,
// a float (0.02 s is 0.0199999996 s as a double), and 25 ticks of it come 11 ns short of half a
// second: a body counts as at rest that long within a millionth of it (kTimeToSleepReached),
// else it slept a tick late.
inline constexpr double kTimeToSleep = 0.5;
inline constexpr double kTimeToSleepReached = kTimeToSleep * (1.0 - 1e-6);
// m: how far a point of a resting body may go from where its rest began; m/s: how fast it may
// go meanwhile. A pile's bodies settle as it sinks into its contacts, and now and then one
// twitches for a tick as a contact beside it is found again with other points: in the 20-layer
// stack of 1 m cubes one body or another reached 5 to 10 cm/s every 10 or 20 ticks, for one tick,
// moving 1 to 2 mm, and each time every body of the stack began its half second again (asleep
// at 1.66 s; now at 0.6 s). A body going steadily slower than kSleepSpeed stays within
// kSleepDrift for the half second and sleeps, as it did when only its speed counted; one that
// keeps going faster does not; one that twitches and stays does.
inline constexpr double kSleepDrift = kSleepSpeed * kTimeToSleep;
inline constexpr double kTwitchSpeed = 4.0 * kSleepSpeed;
// m: two bodies closer than this touch: one island, and a sleeping one wakes when an awake one
// touches it. A tenth of a millimetre: resting contacts stand overlapping (up to 2 mm, above),
// and a gap of a few millimetres between neighbours in a pile is not a touch. Measured in
// bin:1000 after 10 s: 819 bodies kept awake by islands of every contact within reach, 708 by
// those closer than 2 mm, 512 by those closer than 0.1 mm (physics/README.md, "Islands and
// sleeping").
inline constexpr double kSleepTouch = 1e-4;

}  // namespace softbody
