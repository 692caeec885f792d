// Lessons: the bundled scenes in the addendum's order, each about a few of its equations, and
// for a lesson with a closed form, "expected against actual": the value the closed form
// predicts from the scene's keys beside what this simulation does, measured tick by tick.
//
// A scene is a lesson by its "title" and "text" keys (scene_io.h); its "expect" key names the
// closed form and the bodies it watches. No GL here: the app's Lesson panel, `softbody
// lessons` and the tests read the same numbers.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "physics/mass_properties.h"
#include "physics/scene_io.h"
#include "physics/world.h"

namespace softbody {

// One lesson: a scene file of assets/scenes and the equations it is about.
struct LessonInfo {
    std::string_view file;      // "spring.json"
    std::string_view equation;  // "Eq. 21"
};
// Every lesson, in the order of the addendum: the soft body's forces (Eq. 21 to 25), Listing 8
// and its stability, then the rigid bodies (Eq. 26 to 38).
std::span<const LessonInfo> lessons();
// The lesson a scene file is (by its file name), numbered from 1; 0 when it is none.
std::size_t lesson_number(std::string_view path);

// A closed form a scene's "expect" can name, and what it reads.
struct ClosedFormInfo {
    std::string_view kind;      // the name in "expect": { "kind": ... }
    std::string_view equation;  // where it comes from
    std::string_view summary;   // one line: what it predicts
    std::string_view body;      // what "body" must name, for messages
    bool rigid_body = true;     // "body" names a rigid body (else a soft body)
    bool takes_slope = false;   // "slope" may name a fixed rigid body the body rests on (else the ground)
};
std::span<const ClosedFormInfo> closed_forms();
const ClosedFormInfo* find_closed_form(std::string_view kind);

// One line of "expected against actual".
struct Comparison {
    std::string name;       // "period"
    std::string formula;    // "T = 2 pi sqrt(m / k)"
    std::string equation;   // "Eq. 21"
    std::string unit;       // "s" ("" when it has none)
    double predicted = 0.0;
    std::optional<double> measured;  // empty: not yet
    std::string predicted_text;      // an outcome the closed form predicts ("holds", "diverges"), or ""
    std::string measured_text;       // the outcome seen, or how it was measured
    double tolerance = 0.0;          // relative: how close the two should be (0: the outcome decides)
    std::optional<bool> agrees;      // empty: not yet known
};

// Watches one world tick by tick for the closed form of a scene's "expect".
class LessonMeter {
public:
    // Throws InputError when the world lacks what the closed form reads (no spring on the
    // body, a body that is not where "expect" says).
    LessonMeter(LessonExpect expect, const World& world);

    // After every tick. A world that went back (a reset, a restored snapshot) or skipped ticks
    // starts the measurement again from where it is now.
    void observe(const World& world);

    // Predicted from the world's keys as they are now (sliders move them), measured so far.
    std::vector<Comparison> comparisons(const World& world) const;

    const LessonExpect& expect() const { return expect_; }

private:
    void start(const World& world);
    // spring_period, damper_decay: how far the body's end of the springs is from their fixed end.
    double spring_reach(const World& world) const;
    // The one spring that stands for them all: k of the parallel sets, combined in series.
    double effective_stiffness(const World& world) const;
    // comparisons() for each closed form: its lines appended to out, `elapsed` seconds since
    // the measurement started.
    void compare_spring(const World& world, double elapsed, std::vector<Comparison>& out) const;
    void compare_terminal_velocity(const World& world, double elapsed, std::vector<Comparison>& out) const;
    void compare_friction_slope(const World& world, double elapsed, std::vector<Comparison>& out) const;
    void compare_stability(const World& world, double elapsed, std::vector<Comparison>& out) const;
    void compare_inertia(const World& world, double elapsed, std::vector<Comparison>& out) const;
    void compare_collision(const World& world, double elapsed, std::vector<Comparison>& out) const;
    void compare_quaternion_norm(const World& world, double elapsed, std::vector<Comparison>& out) const;
    void compare_flip_period(const World& world, double elapsed, std::vector<Comparison>& out) const;

    struct Extremum {
        double t, value;
    };
    LessonExpect expect_;
    std::size_t body_ = 0;   // the rigid or soft body watched
    std::optional<std::size_t> slope_;  // friction_slope: the rigid body it rests on (none: the ground)
    // spring_period, damper_decay: the springs that hold the body. `upper_` joins a fixed point
    // (in parallel when there are several); `lower_`, when not empty, joins the body to a light
    // moving body that `upper_` holds: the two sets in series. Their keys are read each time.
    std::vector<std::size_t> upper_, lower_;
    std::uint64_t last_tick_ = 0;
    double start_time_ = 0.0;

    // spring_period, damper_decay: the spring's length at the last three ticks, and its extrema.
    std::vector<double> recent_;
    std::vector<Extremum> extrema_;
    // terminal_velocity: the speed while falling free, frozen at the first contact.
    std::optional<double> speed_;
    bool landed_ = false;
    // friction_slope: where the body started, and (time, speed down the slope) while it slides on it.
    Vec3d start_com_;
    double travelled_ = 0.0;
    std::vector<std::pair<double, double>> slide_;
    bool left_slope_ = false;
    // stability: when it diverged.
    std::optional<double> diverged_at_;
    // inertia: the body's own shape as triangles, integrated by Eq. 29-31 (unit density); none
    // for a mesh body, whose tensor comes from its triangles already.
    std::optional<MassProperties> from_triangles_;
    // collision: every rigid body's motion as the last tick ended, and the first hit on the body
    // (faster than 1 cm/s): Eq. 38's terms, and both bodies' motion before and after it.
    struct Hit {
        ImpulseTerms terms;
        double sign = 1.0;                   // the body's impulse is sign * lambda * n (+1: it is body 1)
        std::optional<std::size_t> other;    // the other rigid body; none for the ground
        RigidMotion body_before, body_after, other_before, other_after;
        double time = 0.0;
    };
    std::vector<RigidMotion> before_;
    std::optional<Hit> hit_;
    // flip_period: the intermediate axis's component of omega, and the times it changed sign.
    int axis_ = 1;
    double last_w_ = 0.0;
    std::vector<double> crossings_;
};

}  // namespace softbody
