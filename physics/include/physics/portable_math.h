// The elementary functions the physics needs beyond + - * / and sqrt, computed by the physics
// itself, so that they give the same bits on every platform the project builds for.
//
// Why: a C library's sin or acos is accurate to about one unit in the last place, but which way
// it rounds in that last place is its own. The desktop build's (glibc) and the browser build's
// (emscripten's musl) differ there: on pile.json, 8 of the 54 bodies' starting orientations
// (made from degrees by sin and cos) came out one bit apart, and the two runs parted from the
// first tick. Everything else the physics does is + - * / and sqrt, which IEEE 754 defines to
// the bit, in an order the source fixes (both builds forbid fusing a * b + c). With these
// functions in the simulation's path, a native build forced to the portable pair tile and the
// browser build reach the same state hash (SOFTBODY_KERNEL, physics/pair_forces.h).
//
// Each is a short series after an argument reduction that keeps its rounding error, written
// with + - * / and sqrt only (see portable_math.cpp): sin and cos within 0.8 units in the last
// place, acos, hypot and cbrt within 1.2, tan 2.1 (tests/physics/portable_math_test.cpp); the
// C library's are within about 0.5.
// Code outside the simulation's state (lessons' closed forms, the renderer) may use <cmath>.
#pragma once

namespace softbody::portable {

// Radians. Full accuracy for |x| < 1e6 (the argument reduction's range); beyond, still the
// same bits everywhere, with an absolute error growing as |x| ulp(x).
double sin(double x);
double cos(double x);
// sin x and cos x at once, from one argument reduction: the same bits as the two above.
void sin_cos(double x, double& s, double& c);
double tan(double x);
double acos(double x);  // [-1, 1] -> [0, pi]; NaN outside
double hypot(double x, double y);
double cbrt(double x);

// Float arguments as the physics passes them (rounded from the double result).
inline float sin(float x) { return static_cast<float>(sin(static_cast<double>(x))); }
inline float cos(float x) { return static_cast<float>(cos(static_cast<double>(x))); }

}  // namespace softbody::portable
