// `softbody simulate --series`: the run as a spreadsheet opens it (RFC 4180, a header of names
// with units, times as the decimals they are), and its numbers against the spring lesson's
// closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "child_process.h"

namespace {

using softbody_test::describe;
using softbody_test::read_text;
using softbody_test::Result;
using softbody_test::run;
using softbody_test::TempDir;

std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::size_t start = 0;
    for (std::size_t end; (end = text.find("\r\n", start)) != std::string::npos; start = end + 2) lines.push_back(text.substr(start, end - start));
    return lines;
}

std::vector<std::string> fields_of(const std::string& line) {
    std::vector<std::string> fields;
    std::stringstream in(line);
    for (std::string field; std::getline(in, field, ',');) fields.push_back(field);
    return fields;
}

// The spring lesson (1 kg on 40 N/m, let go at rest length): z(t) = z0 - (m g / k)(1 - cos w t),
// w = sqrt(k / m); the series says so, with Eq. 21's force k (l - l0) beside the length.
TEST(Series, TheSpringLessonAsCsvFollowsItsClosedForm) {
    TempDir dir;
    const std::string csv = dir.file("spring.csv");
    const Result r = run({"simulate", "--lesson", "1", "--seconds", "2", "--series", csv, "--series-every", "5"});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    const std::string text = read_text(csv);
    const std::vector<std::string> lines = lines_of(text);
    ASSERT_EQ(lines.size(), 1u + 21u) << text;  // the header, then ticks 0, 5, ..., 100
    EXPECT_EQ(lines[0],
              "time (s),kinetic (J),gravitational (J),elastic (J),dissipated (J),total (J),bob x (m),bob y (m),bob z (m),"
              "bob vx (m/s),bob vy (m/s),bob vz (m/s),spring length (m),spring force (N)");
    const double k = 40.0, m = 1.0, g = 9.81, w = std::sqrt(k / m), l0 = 1.0;
    for (std::size_t row = 1; row < lines.size(); ++row) {
        const std::vector<std::string> f = fields_of(lines[row]);
        ASSERT_EQ(f.size(), 14u) << lines[row];
        // The time as it is written: 0, 0.1, 0.2, ... exactly, not 0.100000001.
        std::ostringstream expected;
        expected << double(row - 1) / 10.0;
        EXPECT_EQ(f[0], expected.str());
        const double t = std::stod(f[0]), z = std::stod(f[8]), length = std::stod(f[12]), force = std::stod(f[13]);
        // Within 5% of the swing (2 m g / k = 0.49 m) over two periods: measured at most 3%
        // (Verlet's phase error at w h = 0.13 and its first step).
        EXPECT_NEAR(z, 2.0 - (m * g / k) * (1.0 - std::cos(w * t)), 0.05 * 2.0 * m * g / k) << "t = " << t;
        EXPECT_NEAR(force, k * (length - l0), 1e-9 * k);
        EXPECT_NEAR(std::stod(f[3]), 0.5 * k * (length - l0) * (length - l0), 1e-9);
        // No damper: what it lets go of is the integrator's oscillation, within 1% of the energy.
        EXPECT_LT(std::abs(std::stod(f[4])), 0.01 * std::stod(f[5]));
    }
}

// A name with a comma is quoted in the header; a damped run dissipates, and the columns add up.
TEST(Series, QuotesWhatNeedsQuotingAndTheEnergiesAddUp) {
    TempDir dir;
    const std::string scene = dir.write("odd.json",
                                        "{\"rigid_bodies\": [{\"name\": \"ball, \\\"red\\\"\", \"shape\": \"sphere\", \"radius\": 0.2,"
                                        " \"mass\": 1, \"position\": [0, 0, 1]}], \"world\": {\"restitution\": 0.5}}");
    const std::string csv = dir.file("odd.csv");
    const Result r = run({"simulate", "--scene", scene, "--seconds", "3", "--series", csv});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    const std::vector<std::string> lines = lines_of(read_text(csv));
    ASSERT_EQ(lines.size(), 1u + 151u);
    EXPECT_NE(lines[0].find("\"ball, \"\"red\"\" x (m)\""), std::string::npos) << lines[0];
    // Bounces at e = 0.5 take energy; kinetic + gravitational + elastic + dissipated stays the start.
    const std::vector<std::string> last = fields_of(lines.back());
    const double kinetic = std::stod(last[1]), gravity = std::stod(last[2]), elastic = std::stod(last[3]);
    const double dissipated = std::stod(last[4]), total = std::stod(last[5]);
    EXPECT_GT(dissipated, 0.5 * 9.81 * 0.8 * 0.5);  // most of the 7.8 J it had above its resting height
    EXPECT_NEAR(kinetic + gravity + elastic + dissipated, total, 1e-9 * total);
    EXPECT_NEAR(total, 9.81 * 1.0, 1e-6);  // m g z at the start
}

TEST(Series, AFileThatCannotBeWrittenIsSaidInOneLine) {
    const Result r = run({"simulate", "--lesson", "1", "--ticks", "5", "--series", "/no/such/folder/s.csv"});
    EXPECT_EQ(r.exit_code, 2) << describe(r);
    EXPECT_NE(r.err.find("/no/such/folder/s.csv"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

}  // namespace
