#include "physics/portable_math.h"

#include <cmath>  // sqrt (exact), frexp and ldexp (exact), isfinite, fabs, nearbyint (exact)
#include <cstdint>
#include <limits>

namespace softbody::portable {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// pi/2 in three parts for the reduction x - n pi/2 (Cody and Waite): the first two have 33
// significant bits, so n times either is exact for |n| < 2^20; the third is the rest, rounded.
constexpr double kHalfPi1 = 1.5707963267341256;
constexpr double kHalfPi2 = 6.077100506303966e-11;
constexpr double kHalfPi3 = 2.0222662487959506e-21;
constexpr double kTwoOverPi = 0.6366197723675814;
constexpr double kQuarterPi = 0.7853981633974483;  // the double nearest pi/4: below it, x * kTwoOverPi < 0.5
// pi/2 and pi as the double nearest each, and what that leaves out.
constexpr double kHalfPi = 1.5707963267948966;
constexpr double kHalfPiLow = 6.123233995736766e-17;

// 1/n!, from n! in double (exact up to 22!, whose odd part still fits in 53 bits).
constexpr double inverse_factorial(int n) {
    double f = 1.0;
    for (int k = 2; k <= n; ++k) f *= k;
    return 1.0 / f;
}

// sin(r + c) and cos(r + c) for |r| <= pi/4 (a little more far out) and c below half a unit
// in r's last place: Taylor series to r^21 and r^22, whose next terms are below 2^-80 there,
// in Horner's form in r^2, and c through the first term of sin(r + c) = sin r + c cos r and
// cos(r + c) = cos r - c sin r. The largest term is added last, so its rounding is the result's.
// For |r| <= 1/16 (r^2 <= kSmall: a body's turn in a substep, nearly always) the series stop at
// r^11 and r^12, whose next terms are below 2^-80 there too: half the work.
constexpr double kSmall = 1.0 / 256.0;

double sin_reduced(double r, double c) {
    constexpr double s3 = -inverse_factorial(3), s5 = inverse_factorial(5), s7 = -inverse_factorial(7),
                     s9 = inverse_factorial(9), s11 = -inverse_factorial(11), s13 = inverse_factorial(13),
                     s15 = -inverse_factorial(15), s17 = inverse_factorial(17), s19 = -inverse_factorial(19),
                     s21 = inverse_factorial(21);
    const double z = r * r;
    const double tail = z <= kSmall ? s3 + z * (s5 + z * (s7 + z * (s9 + z * s11)))
                                    : s3 + z * (s5 + z * (s7 + z * (s9 + z * (s11 + z * (s13 + z * (s15 + z * (s17 + z * (s19 + z * s21))))))));
    return r + (r * z * tail + c * (1.0 - 0.5 * z));
}

double cos_reduced(double r, double c) {
    constexpr double c4 = inverse_factorial(4), c6 = -inverse_factorial(6), c8 = inverse_factorial(8),
                     c10 = -inverse_factorial(10), c12 = inverse_factorial(12), c14 = -inverse_factorial(14),
                     c16 = inverse_factorial(16), c18 = -inverse_factorial(18), c20 = inverse_factorial(20),
                     c22 = -inverse_factorial(22);
    const double z = r * r;
    const double tail = z <= kSmall ? c4 + z * (c6 + z * (c8 + z * (c10 + z * c12)))
                                    : c4 + z * (c6 + z * (c8 + z * (c10 + z * (c12 + z * (c14 + z * (c16 + z * (c18 + z * (c20 + z * c22))))))));
    // 1 - z/2 + z^2 tail, with 1 - z/2 split so that its rounding error is kept.
    const double half_z = 0.5 * z;
    const double head = 1.0 - half_z;
    return head + (((1.0 - head) - half_z) + (z * z * tail - r * c));
}

// x = n pi/2 + (r + c), r + c within pi/4 (a little more far out) and c the part of the
// reduced argument below r's last place; returns n mod 4. x - n pi/2_1 is exact (n pi/2_1 is,
// and the two are within a factor of two of each other); the next part's subtraction keeps
// its rounding error in c (Knuth's two-sum).
int reduce(double x, double& r, double& c) {
    // Within pi/4, n is 0 and the steps below give x itself and c = 0 (a small body turn in a
    // substep, nearly always): the same without them (x + 0 as they make -0 into +0).
    if (std::fabs(x) < kQuarterPi) {
        r = x + 0.0;
        c = 0.0;
        return 0;
    }
    const double n = std::nearbyint(x * kTwoOverPi);
    const double t = x - n * kHalfPi1;
    const double w = n * kHalfPi2;
    r = t - w;
    const double w_seen = t - r;  // two-sum: r + error = t - w exactly
    const double error = (t - (r + w_seen)) - (w - w_seen);
    c = error - n * kHalfPi3;
    const double sum = r + c;  // r + c as one double and what it leaves
    c = c - (sum - r);
    r = sum;
    const double quadrant = n - 4.0 * std::floor(0.25 * n);  // 0, 1, 2, 3 (n is whole: exact)
    return static_cast<int>(quadrant);
}

// asin x for |x| <= 1/2: x + x^3/6 + 3x^5/40 + ..., whose n-th coefficient is
// (2n)! / (4^n (n!)^2 (2n + 1)); 28 terms leave out less than 2^-60 of x.
double asin_small(double x) {
    constexpr int kTerms = 28;
    struct Coefficients {
        double c[kTerms];
        constexpr Coefficients() : c{} {
            double binomial = 1.0;  // (2n)! / (4^n (n!)^2), term by term
            for (int n = 1; n < kTerms; ++n) {
                binomial *= double(2 * n - 1) / double(2 * n);
                c[n] = binomial / double(2 * n + 1);
            }
        }
    };
    constexpr Coefficients k;
    const double z = x * x;
    double tail = k.c[kTerms - 1];
    for (int n = kTerms - 2; n >= 1; --n) tail = k.c[n] + z * tail;
    return x + x * z * tail;
}

}  // namespace

double sin(double x) {
    if (!std::isfinite(x)) return kNaN;
    double r = 0.0, c = 0.0;
    switch (reduce(x, r, c)) {
        case 0: return sin_reduced(r, c);
        case 1: return cos_reduced(r, c);
        case 2: return -sin_reduced(r, c);
        default: return -cos_reduced(r, c);
    }
}

double cos(double x) {
    if (!std::isfinite(x)) return kNaN;
    double r = 0.0, c = 0.0;
    switch (reduce(x, r, c)) {
        case 0: return cos_reduced(r, c);
        case 1: return -sin_reduced(r, c);
        case 2: return -cos_reduced(r, c);
        default: return sin_reduced(r, c);
    }
}

void sin_cos(double x, double& s, double& c) {
    if (!std::isfinite(x)) {
        s = c = kNaN;
        return;
    }
    double r = 0.0, e = 0.0;
    const int quadrant = reduce(x, r, e);
    const double sin_r = sin_reduced(r, e), cos_r = cos_reduced(r, e);
    switch (quadrant) {
        case 0: s = sin_r; c = cos_r; break;
        case 1: s = cos_r; c = -sin_r; break;
        case 2: s = -sin_r; c = -cos_r; break;
        default: s = -cos_r; c = sin_r; break;
    }
}

double tan(double x) {
    if (!std::isfinite(x)) return kNaN;
    double r = 0.0, c = 0.0;
    const int quadrant = reduce(x, r, c);
    const double s = sin_reduced(r, c), co = cos_reduced(r, c);
    return quadrant % 2 == 0 ? s / co : -co / s;
}

double acos(double x) {
    if (!(x >= -1.0 && x <= 1.0)) return kNaN;
    // Near 1 and -1 through the half angle: acos x = 2 asin(sqrt((1 - x) / 2)), where 1 - x is
    // exact; in between, pi/2 - asin x.
    if (x > 0.5) return 2.0 * asin_small(std::sqrt(0.5 * (1.0 - x)));
    if (x < -0.5) return 2.0 * (kHalfPi - asin_small(std::sqrt(0.5 * (1.0 + x)))) + 2.0 * kHalfPiLow;
    return kHalfPi - (asin_small(x) - kHalfPiLow);
}

double hypot(double x, double y) {
    x = std::fabs(x);
    y = std::fabs(y);
    if (std::isinf(x) || std::isinf(y)) return std::numeric_limits<double>::infinity();
    if (std::isnan(x) || std::isnan(y)) return kNaN;
    const double big = x > y ? x : y;
    if (big == 0.0) return 0.0;
    // Scaled by a power of two (exact) when the squares would overflow or lose bits below.
    int exponent = 0;
    std::frexp(big, &exponent);
    const int shift = exponent > 500 || exponent < -500 ? -exponent : 0;
    const double a = std::ldexp(x, shift), b = std::ldexp(y, shift);
    return std::ldexp(std::sqrt(a * a + b * b), -shift);
}

double cbrt(double x) {
    if (!std::isfinite(x) || x == 0.0) return x;
    const bool negative = x < 0.0;
    int exponent = 0;
    double m = std::frexp(std::fabs(x), &exponent);  // |x| = m 2^exponent, m in [1/2, 1)
    const int rest = ((exponent % 3) + 3) % 3;       // so that 3 divides exponent - rest
    m = std::ldexp(m, rest);                          // m in [1/2, 4)
    exponent -= rest;
    // Newton's method on y^3 = m from a line through (1/2, 0.79) and (4, 1.59); eight steps
    // take it from there to the double nearest (quadratic convergence; the last ones settle).
    double y = 0.68 + 0.23 * m;
    for (int i = 0; i < 8; ++i) y = y - (y * y * y - m) / (3.0 * y * y);
    y = std::ldexp(y, exponent / 3);
    return negative ? -y : y;
}

}  // namespace softbody::portable
