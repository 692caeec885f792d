// The physics' own elementary functions (physics/portable_math.h) against the C library's long
// double ones, which carry 11 bits more than a double: an error in units of the double's last
// place (ulp) is measured to about 1/1000 of one. The bounds are what the functions reach here
// with a margin (measured on 2,000,000 arguments: sin and cos 0.77 ulp, acos and hypot 1.15,
// cbrt 0.95, tan 2.07); the C library's double functions reach about 0.52.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "physics/portable_math.h"

namespace softbody {
namespace {

double ulps(double got, long double want) {
    const double nearest = static_cast<double>(want);
    const double unit = nearest == 0.0 ? std::numeric_limits<double>::denorm_min()
                                       : std::nextafter(std::fabs(nearest), INFINITY) - std::fabs(nearest);
    return static_cast<double>(std::fabs(static_cast<long double>(got) - want) / unit);
}

template <class Function, class Reference>
double worst_error(double lo, double hi, Function f, Reference reference) {
    std::mt19937_64 random(7);
    std::uniform_real_distribution<double> argument(lo, hi);
    double worst = 0.0;
    for (int i = 0; i < 200'000; ++i) {
        const double x = argument(random);
        worst = std::max(worst, ulps(f(x), reference(static_cast<long double>(x))));
    }
    return worst;
}

TEST(PortableMath, SinAndCosWithinAUnitInTheLastPlace) {
    // Small angles (within 1/16 the series are shorter), a few turns, and far out where the
    // reduction by pi/2 must carry its error.
    for (double range : {0.0625, 0.8, 7.0, 1e5}) {
        EXPECT_LT(worst_error(-range, range, [](double x) { return portable::sin(x); }, [](long double x) { return sinl(x); }), 1.0)
            << range;
        EXPECT_LT(worst_error(-range, range, [](double x) { return portable::cos(x); }, [](long double x) { return cosl(x); }), 1.0)
            << range;
    }
}

TEST(PortableMath, TanAcosHypotCbrtWithinTheirBounds) {
    EXPECT_LT(worst_error(-1.5, 1.5, [](double x) { return portable::tan(x); }, [](long double x) { return tanl(x); }), 2.5);
    EXPECT_LT(worst_error(-1.0, 1.0, [](double x) { return portable::acos(x); }, [](long double x) { return acosl(x); }), 1.5);
    EXPECT_LT(worst_error(0.999, 1.0, [](double x) { return portable::acos(x); }, [](long double x) { return acosl(x); }), 1.5);
    EXPECT_LT(worst_error(-10.0, 10.0, [](double x) { return portable::hypot(x, 0.7 * x + 1.0); },
                          [](long double x) { return hypotl(x, static_cast<long double>(0.7 * static_cast<double>(x) + 1.0)); }),
              1.5);
    EXPECT_LT(worst_error(0.0, 1e4, [](double x) { return portable::cbrt(x); }, [](long double x) { return cbrtl(x); }), 1.0);
    EXPECT_LT(worst_error(-1e-3, 1e-3, [](double x) { return portable::cbrt(x); }, [](long double x) { return cbrtl(x); }), 1.0);
}

// sin_cos is the two from one reduction: the same bits as each alone, in every quadrant, at
// the edges of the reduction's range and beyond, and NaN where they are.
TEST(PortableMath, SinCosIsSinAndCosBitForBit) {
    const auto same_bits = [](double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; };
    std::mt19937_64 random(11);
    std::uniform_real_distribution<double> near(-10.0, 10.0), far(-2e6, 2e6), tiny(-1e-6, 1e-6);
    std::vector<double> xs = {0.0, -0.0, 0.7853981633974483, 1.5707963267948966, 3.141592653589793, -4.71238898038469,
                              1e-300, -5e-324, 1e6, 3e7, INFINITY, -INFINITY, NAN};
    for (int i = 0; i < 100'000; ++i) xs.insert(xs.end(), {near(random), far(random), tiny(random)});
    int differing = 0;
    for (const double x : xs) {
        double s = 0.0, c = 0.0;
        portable::sin_cos(x, s, c);
        const double s1 = portable::sin(x), c1 = portable::cos(x);
        if (std::isnan(x)) {
            differing += !(std::isnan(s) && std::isnan(c));
        } else if (std::isinf(x)) {
            differing += !(std::isnan(s) && std::isnan(c) && std::isnan(s1) && std::isnan(c1));
        } else {
            differing += !(same_bits(s, s1) && same_bits(c, c1));
        }
    }
    EXPECT_EQ(differing, 0) << "of " << xs.size() << " arguments";
}

TEST(PortableMath, ExactValuesAndEdges) {
    EXPECT_EQ(portable::sin(0.0), 0.0);
    EXPECT_EQ(portable::cos(0.0), 1.0);
    EXPECT_EQ(portable::acos(1.0), 0.0);
    EXPECT_EQ(portable::acos(-1.0), 3.141592653589793);  // the double nearest pi
    EXPECT_EQ(portable::hypot(3.0, -4.0), 5.0);
    EXPECT_EQ(portable::cbrt(27.0), 3.0);
    EXPECT_EQ(portable::cbrt(-8.0), -2.0);
    EXPECT_EQ(portable::hypot(std::ldexp(3.0, 1000), std::ldexp(4.0, 1000)), std::ldexp(5.0, 1000));  // no overflow
    EXPECT_EQ(portable::hypot(std::ldexp(3.0, -1000), std::ldexp(4.0, -1000)), std::ldexp(5.0, -1000));  // nor underflow
    EXPECT_TRUE(std::isnan(portable::acos(1.0000000000000002)));
    EXPECT_TRUE(std::isnan(portable::sin(INFINITY)));
    EXPECT_TRUE(std::isnan(portable::cos(NAN)));
    EXPECT_EQ(portable::sin(-0.0), 0.0);
    EXPECT_EQ(portable::cos(3.141592653589793), -1.0);
    EXPECT_FLOAT_EQ(portable::sin(0.5f), std::sin(0.5f));
}

}  // namespace
}  // namespace softbody
