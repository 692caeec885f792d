#include "physics/lesson.h"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <numbers>

#include "physics/error.h"
#include "physics/shape_meshes.h"

namespace softbody {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

constexpr LessonInfo kLessons[] = {
    {"spring.json", "Eq. 21"},
    {"damper.json", "Eq. 22"},
    {"drag.json", "Eq. 23"},
    {"slope.json", "Eq. 24, 25"},
    {"listing8.json", "Listing 8"},
    {"stability.json", "Listing 8, stability"},
    {"seesaw.json", "Eq. 26, 27"},
    {"tumbling_box.json", "Eq. 29-32, Table 1"},
    {"quaternion.json", "Eq. 35, Listing 9"},
    {"intermediate_axis.json", "Eq. 26, 28, 36"},
    {"figure7.json", "Eq. 37, 38, Figure 7"},
    {"collision_1d.json", "Eq. 37, 38: momentum"},
    {"springs_parallel.json", "Eq. 21: k1 + k2"},
    {"springs_series.json", "Eq. 21: 1/k1 + 1/k2"},
};

constexpr ClosedFormInfo kForms[] = {
    {"spring_period", "Eq. 21", "the period of a body on springs to fixed points, T = 2 pi sqrt(m / k): one spring, side by side (k1 + k2) or two sets end to end through a light body (1 / (1/k1 + 1/k2))",
     "the rigid body on the springs"},
    {"damper_decay", "Eq. 22", "the decay rate c / 2m of a body on a damped spring, and its period",
     "the rigid body on the spring"},
    {"terminal_velocity", "Eq. 23", "the speed where drag cancels the weight, v_t = sqrt(2 m g / (rho C_D S))",
     "the falling rigid body"},
    {"friction_slope", "Eq. 24, 25", "held while tan theta <= mu_s; sliding at g (sin theta - mu_d cos theta)",
     "the soft body on the slope (the ground, gravity tilted, or a fixed rigid body)", false, true},
    {"stability", "Listing 8, stability", "stable while N (k h^2 + 2 c h) < 4 m", "the soft body", false},
    {"inertia", "Table 1", "the inertia tensor of a box, sphere or cylinder", "a box, sphere or cylinder"},
    {"quaternion_norm", "Eq. 35, Listing 9", "|q| under explicit Euler: (1 + (h w / 2)^2)^(n / 2)",
     "a rigid body spinning about a principal axis"},
    {"flip_period", "Eq. 26, 28", "the intermediate-axis flip period, 2 K(k) sqrt(I1 I2 I3 / ...)",
     "a rigid body spinning near its intermediate axis"},
    {"collision", "Eq. 37, 38", "the first hit's impulse lambda and the velocities and spin it leaves",
     "the rigid body that is hit"},
};

__attribute__((format(printf, 1, 2))) std::string format(const char* pattern, ...) {
    char text[160];
    va_list args;
    va_start(args, pattern);
    std::vsnprintf(text, sizeof text, pattern, args);
    va_end(args);
    return text;
}

Comparison comparison(std::string name, std::string formula, std::string equation, std::string unit) {
    Comparison c;
    c.name = std::move(name);
    c.formula = std::move(formula);
    c.equation = std::move(equation);
    c.unit = std::move(unit);
    return c;
}

// The complete elliptic integral of the first kind, K(m) for m = k^2, by the arithmetic-
// geometric mean: K = pi / (2 AGM(1, sqrt(1 - m))).
double elliptic_k(double m) {
    double a = 1.0, b = std::sqrt(1.0 - m);
    for (int i = 0; i < 60 && std::abs(a - b) > 1e-15 * a; ++i) {
        const double mean = 0.5 * (a + b);
        b = std::sqrt(a * b);
        a = mean;
    }
    return std::numbers::pi / (2.0 * a);
}

Vec3d soft_com(const SoftBody& body, bool velocity) {
    const Vec3Array& a = velocity ? body.v : body.x;
    Vec3d sum;
    for (std::size_t i = 0; i < a.size(); ++i) sum += Vec3d(a[i]);
    return a.size() ? sum / double(a.size()) : sum;
}

// The slope's geometry: the normal of its face that looks up (against gravity), the way down
// along it, and the angle theta between that face and the level. The ground (no slope body) is
// a slope when gravity is tilted: theta is then the tilt, as the physics tests make slopes.
struct SlopeFrame {
    Vec3d n, down;
    double theta = 0.0, g = 0.0;
};
SlopeFrame slope_frame(const World& world, std::optional<std::size_t> slope) {
    const Vec3d g(world.settings().gravity);
    SlopeFrame f;
    f.g = length(g);
    f.n = slope ? world.rigid_motion(*slope).R * Vec3d{0.0, 0.0, 1.0} : Vec3d{0.0, 0.0, 1.0};  // a box's top face (its z)
    if (dot(f.n, g) > 0.0) f.n = -f.n;
    if (f.g > 0.0) {
        f.theta = std::acos(std::clamp(-dot(f.n, g) / f.g, -1.0, 1.0));
        const Vec3d along = g - f.n * dot(g, f.n);
        if (length(along) > 1e-12) f.down = normalize(along);
    }
    return f;
}

// Whether a soft body touches the slope: a rigid body's contacts, or a particle on the ground.
bool touches(const World& world, std::size_t soft, std::optional<std::size_t> slope) {
    if (!slope) {
        const SoftBody& body = world.soft_body(soft);
        const float ground = world.settings().ground_height;
        for (std::size_t i = 0; i < body.particle_count(); ++i) {
            if (body.x.z[i] <= ground + 1e-3f) return true;
        }
        return false;
    }
    const std::size_t rigid = *slope;
    return std::any_of(world.contacts().begin(), world.contacts().end(), [&](const RigidContact& c) {
        return c.soft == std::int32_t(soft) && c.b == std::int32_t(rigid);
    });
}

bool rigid_touches_anything(const World& world, std::size_t body) {
    return std::any_of(world.contacts().begin(), world.contacts().end(), [&](const RigidContact& c) {
        return (c.soft < 0 && c.a == body) || c.b == std::int32_t(body);
    });
}

// Body-axes angular velocity R^T w.
Vec3d body_omega(const RigidMotion& m) { return m.R.transposed() * m.omega; }

// Least-squares slope of y over t.
double fitted_slope(const std::vector<std::pair<double, double>>& samples) {
    double st = 0.0, sy = 0.0;
    for (const auto& [t, y] : samples) {
        st += t;
        sy += y;
    }
    const double n = double(samples.size()), mt = st / n, my = sy / n;
    double num = 0.0, den = 0.0;
    for (const auto& [t, y] : samples) {
        num += (t - mt) * (y - my);
        den += (t - mt) * (t - mt);
    }
    return den > 0.0 ? num / den : 0.0;
}

bool within(double measured, double predicted, double tolerance) {
    return std::abs(measured - predicted) <= tolerance * std::abs(predicted);
}

}  // namespace

std::span<const LessonInfo> lessons() { return kLessons; }

std::size_t lesson_number(std::string_view path) {
    const std::string name = std::filesystem::path(path).filename().string();
    for (std::size_t i = 0; i < std::size(kLessons); ++i) {
        if (kLessons[i].file == name) return i + 1;
    }
    return 0;
}

std::span<const ClosedFormInfo> closed_forms() { return kForms; }

const ClosedFormInfo* find_closed_form(std::string_view kind) {
    for (const ClosedFormInfo& form : kForms) {
        if (form.kind == kind) return &form;
    }
    return nullptr;
}

LessonMeter::LessonMeter(LessonExpect expect, const World& world) : expect_(std::move(expect)) {
    const ClosedFormInfo* form = find_closed_form(expect_.kind);
    if (!form) throw InputError("expect: unknown kind '" + expect_.kind + "'");
    const auto fail = [&](const std::string& what) { throw InputError("expect '" + expect_.kind + "': " + what); };
    bool found = false;
    if (form->rigid_body) {
        for (std::size_t i = 0; i < world.rigid_body_count() && !found; ++i) {
            if (world.rigid_body(i).name == expect_.body) body_ = i, found = true;
        }
        if (!found) fail("no rigid body named '" + expect_.body + "'");
        if (world.rigid_body(body_).fixed) fail("'" + expect_.body + "' is fixed: it cannot move");
    } else {
        for (std::size_t i = 0; i < world.soft_body_count() && !found; ++i) {
            if (world.soft_body(i).name() == expect_.body) body_ = i, found = true;
        }
        if (!found) fail("no soft body named '" + expect_.body + "'");
    }
    if (!expect_.slope.empty()) {
        for (std::size_t i = 0; i < world.rigid_body_count() && !slope_; ++i) {
            if (world.rigid_body(i).name == expect_.slope) slope_ = i;
        }
        if (!slope_) fail("no rigid body named '" + expect_.slope + "'");
    } else if (expect_.kind == "friction_slope" && !world.settings().ground) {
        fail("no slope: name a rigid body as \"slope\", or turn the ground on");
    }
    if (expect_.kind == "spring_period" || expect_.kind == "damper_decay") {
        // The body's springs to a fixed point in the world (side by side: in parallel), or to a
        // moving body that hangs on such springs and on nothing else (the two sets in series).
        const auto is_body = [](const LinkEnd& e, std::size_t b) { return e.kind == LinkEnd::Kind::Rigid && e.body == b; };
        const auto fixed = [](const LinkEnd& e) { return e.kind == LinkEnd::Kind::World; };
        const auto other_end = [&](const Link& l, std::size_t b) { return is_body(l.a, b) ? l.b : l.a; };
        const std::vector<Link>& links = world.links();
        for (std::size_t i = 0; i < links.size(); ++i) {
            if ((is_body(links[i].a, body_) || is_body(links[i].b, body_)) && fixed(other_end(links[i], body_))) upper_.push_back(i);
        }
        if (upper_.empty()) {
            std::optional<std::size_t> middle;
            for (std::size_t i = 0; i < links.size(); ++i) {
                if (!is_body(links[i].a, body_) && !is_body(links[i].b, body_)) continue;
                const LinkEnd other = other_end(links[i], body_);
                if (other.kind != LinkEnd::Kind::Rigid || (middle && *middle != other.body)) fail("'" + expect_.body + "' hangs on no spring to a fixed point");
                middle = other.body;
                lower_.push_back(i);
            }
            if (middle) {
                for (std::size_t i = 0; i < links.size(); ++i) {
                    if (!is_body(links[i].a, *middle) && !is_body(links[i].b, *middle)) continue;
                    const LinkEnd other = other_end(links[i], *middle);
                    if (fixed(other)) {
                        upper_.push_back(i);
                    } else if (!is_body(other, body_)) {
                        fail("'" + world.rigid_body(*middle).name + "' joins more than '" + expect_.body + "' and fixed points");
                    }
                }
            }
            if (upper_.empty()) fail("'" + expect_.body + "' hangs on no spring to a fixed point");
            if (expect_.kind == "damper_decay") fail("'" + expect_.body + "' hangs on springs in series: damper_decay needs one set of springs");
        }
    }
    if (expect_.kind == "inertia") {
        // The primitive's surface as triangles: a box's 12 are exact; a sphere's and a
        // cylinder's are fine enough (10,242 and 1,024 corners) to be within 1e-3 of the solid.
        const RigidBody& b = world.rigid_body(body_);
        std::optional<Mesh> surface;
        if (b.shape == ShapeKind::Box) surface = box_mesh(b.size);
        if (b.shape == ShapeKind::Sphere) surface = sphere_mesh(b.radius, 5);
        if (b.shape == ShapeKind::Cylinder) surface = cylinder_mesh(b.radius, b.height, 512);
        if (surface) {
            std::vector<Vec3d> corners;
            for (const Vec3& p : surface->positions) corners.push_back(Vec3d(p));
            from_triangles_ = mesh_mass_properties(corners, particle_triangles(*surface));
        }
    }
    if (expect_.kind == "flip_period") {
        const Mat3& J = world.rigid_body(body_).J_body;
        const double scale = J.m[0][0] + J.m[1][1] + J.m[2][2];
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 3; ++c) {
                if (r != c && std::abs(J.m[r][c]) > 1e-9 * scale) fail("'" + expect_.body + "' needs its body axes principal");
            }
        }
        // The intermediate axis: neither the largest nor the smallest moment.
        const double I[3] = {J.m[0][0], J.m[1][1], J.m[2][2]};
        for (int a = 0; a < 3; ++a) {
            const int lower = (I[(a + 1) % 3] < I[a]) + (I[(a + 2) % 3] < I[a]);
            if (lower == 1) axis_ = a;
        }
    }
    start(world);
}

void LessonMeter::start(const World& world) {
    last_tick_ = world.ticks();
    start_time_ = world.time();
    recent_.clear();
    extrema_.clear();
    speed_.reset();
    landed_ = false;
    travelled_ = 0.0;
    slide_.clear();
    left_slope_ = false;
    diverged_at_.reset();
    crossings_.clear();
    hit_.reset();
    before_.clear();
    const std::string& kind = expect_.kind;
    if (kind == "collision") {
        for (std::size_t i = 0; i < world.rigid_body_count(); ++i) before_.push_back(world.rigid_motion(i));
    }
    if (kind == "spring_period" || kind == "damper_decay") {
        recent_.push_back(spring_reach(world));
    } else if (kind == "terminal_velocity") {
        speed_ = length(world.rigid_motion(body_).v);
    } else if (kind == "friction_slope") {
        start_com_ = soft_com(world.soft_body(body_), false);
    } else if (kind == "flip_period") {
        last_w_ = body_omega(world.rigid_motion(body_))[axis_];
    }
}

void LessonMeter::observe(const World& world) {
    if (world.ticks() != last_tick_ + 1) {
        start(world);
        return;
    }
    last_tick_ = world.ticks();
    const double t = world.time(), dt = double(world.settings().dt);
    const std::string& kind = expect_.kind;
    if (kind == "spring_period" || kind == "damper_decay") {
        // The spring's length l each tick; an extremum where it turns, placed between the ticks
        // by the parabola through three samples (its vertex: offset 1/2 (l0 - l2) / (l0 - 2 l1 + l2)).
        recent_.push_back(spring_reach(world));
        if (recent_.size() > 3) recent_.erase(recent_.begin());
        if (recent_.size() == 3) {
            const double l0 = recent_[0], l1 = recent_[1], l2 = recent_[2];
            const bool turn = (l1 > l0 && l1 >= l2) || (l1 < l0 && l1 <= l2);
            const double curvature = l0 - 2.0 * l1 + l2;
            if (turn && std::abs(curvature) > 1e-12 && std::abs(l1 - l0) + std::abs(l2 - l1) > 1e-9) {
                const double offset = 0.5 * (l0 - l2) / curvature;
                extrema_.push_back({t - dt + offset * dt, l1 - 0.25 * (l0 - l2) * offset});
            }
        }
    } else if (kind == "terminal_velocity") {
        // The speed while nothing touches the body; the first contact (the ground) freezes it.
        if (!landed_ && rigid_touches_anything(world, body_)) landed_ = true;
        if (!landed_) speed_ = length(world.rigid_motion(body_).v);
    } else if (kind == "friction_slope") {
        const SlopeFrame f = slope_frame(world, slope_);
        const SoftBody& body = world.soft_body(body_);
        travelled_ = dot(soft_com(body, false) - start_com_, f.down);
        const double v = dot(soft_com(body, true), f.down);
        const bool on = touches(world, body_, slope_);
        if (!on && !slide_.empty()) left_slope_ = true;
        if (on && !left_slope_ && v > 5e-3) slide_.emplace_back(t, v);
    } else if (kind == "collision") {
        // The first contact of the body closing faster than 1 cm/s (the Last collision panel's
        // rule in a world without gravity) that took an impulse (a contact found ahead, whose gap
        // stays open this tick, takes none): its terms, and the motion on both sides of the tick.
        const auto hits_body = [&](const RigidContact& c) {
            return c.soft < 0 && c.approach_speed > 0.01 && c.normal_impulse > 0.0 &&
                   (c.a == body_ || (c.b >= 0 && std::size_t(c.b) == body_));
        };
        const auto found = hit_ ? world.contacts().end() : std::find_if(world.contacts().begin(), world.contacts().end(), hits_body);
        if (found != world.contacts().end()) {
            const RigidContact& c = *found;
            const bool is_a = c.a == body_;
            Hit h;
            h.terms = world.impulse_terms(c);
            h.sign = is_a ? 1.0 : -1.0;
            if (!is_a) h.other = std::size_t(c.a);
            else if (c.b >= 0) h.other = std::size_t(c.b);
            h.body_before = before_[body_];
            h.body_after = world.rigid_motion(body_);
            if (h.other) {
                h.other_before = before_[*h.other];
                h.other_after = world.rigid_motion(*h.other);
            }
            h.time = t;
            hit_ = h;
        }
        for (std::size_t i = 0; i < world.rigid_body_count() && i < before_.size(); ++i) before_[i] = world.rigid_motion(i);
    } else if (kind == "flip_period") {
        // The times the intermediate axis's omega changes sign, each placed between two ticks
        // by linear interpolation.
        const double w = body_omega(world.rigid_motion(body_))[axis_];
        if ((last_w_ > 0.0) != (w > 0.0) && w != last_w_) crossings_.push_back(t - dt * w / (w - last_w_));
        last_w_ = w;
    }
}

// One function per closed form, by the kind the scene's "expect" names (the constructor has
// checked it is one of kForms).
std::vector<Comparison> LessonMeter::comparisons(const World& world) const {
    using Compare = void (LessonMeter::*)(const World&, double, std::vector<Comparison>&) const;
    static constexpr struct {
        std::string_view kind;
        Compare compare;
    } kCompare[] = {
        {"spring_period", &LessonMeter::compare_spring},
        {"damper_decay", &LessonMeter::compare_spring},
        {"terminal_velocity", &LessonMeter::compare_terminal_velocity},
        {"friction_slope", &LessonMeter::compare_friction_slope},
        {"stability", &LessonMeter::compare_stability},
        {"inertia", &LessonMeter::compare_inertia},
        {"collision", &LessonMeter::compare_collision},
        {"quaternion_norm", &LessonMeter::compare_quaternion_norm},
        {"flip_period", &LessonMeter::compare_flip_period},
    };
    std::vector<Comparison> out;
    const double elapsed = world.time() - start_time_;
    for (const auto& [kind, compare] : kCompare) {
        if (kind == expect_.kind) (this->*compare)(world, elapsed, out);
    }
    return out;
}

// Eq. 21 and 22: the period of a body on a spring, and its decay rate with a damper.
double LessonMeter::spring_reach(const World& world) const {
    const Link& top = world.links()[upper_.front()];
    const Link& bottom = world.links()[lower_.empty() ? upper_.front() : lower_.front()];
    const LinkEnd& anchor = top.a.kind == LinkEnd::Kind::World ? top.a : top.b;
    const LinkEnd& end = bottom.a.kind == LinkEnd::Kind::Rigid && bottom.a.body == body_ ? bottom.a : bottom.b;
    return length(world.link_end_position(end) - world.link_end_position(anchor));
}

double LessonMeter::effective_stiffness(const World& world) const {
    // Side by side, springs add their stiffness; in series, their compliance 1/k (the light
    // body between them carries the same force through both).
    const auto sum = [&](const std::vector<std::size_t>& set) {
        double k = 0.0;
        for (const std::size_t i : set) k += world.links()[i].k;
        return k;
    };
    if (lower_.empty()) return sum(upper_);
    const double upper = sum(upper_), lower = sum(lower_);
    return upper > 0.0 && lower > 0.0 ? 1.0 / (1.0 / upper + 1.0 / lower) : 0.0;
}

void LessonMeter::compare_spring(const World& world, double, std::vector<Comparison>& out) const {
    const std::string& kind = expect_.kind;
    // Eq. 21 and 22 on one body: m x'' = -k x - c x', so x = A e^(-gamma t) cos(w_d t) with
    // gamma = c / 2m and w_d = sqrt(k / m - gamma^2); T = 2 pi / w_d (2 pi sqrt(m / k) for c = 0).
    // Several springs act as one of stiffness effective_stiffness (the light body in a series
    // chain left out: at a hundredth of the body's mass it moves T by about 0.1%).
    double c = 0.0;
    for (const std::size_t i : upper_) c += world.links()[i].c;
    const double k = effective_stiffness(world);
    const double m = world.rigid_body(body_).mass, gamma = c / (2.0 * m), w2 = k / m - gamma * gamma;
    const char* undamped = !lower_.empty() ? "T = 2 pi sqrt(m (1/k1 + 1/k2))" : upper_.size() > 1 ? "T = 2 pi sqrt(m / (k1 + k2))" : "T = 2 pi sqrt(m / k)";
    Comparison period = comparison("period", c > 0.0 ? "T = 2 pi / sqrt(k/m - (c/2m)^2)" : undamped,
                      c > 0.0 ? "Eq. 21, 22" : "Eq. 21", "s");
    period.predicted = w2 > 0.0 ? 2.0 * std::numbers::pi / std::sqrt(w2) : kNaN;
    if (!(w2 > 0.0)) period.predicted_text = "no swing: critically or over-damped";
    period.tolerance = 0.01;
    if (extrema_.size() >= 3) {
        // Extrema come every half period.
        period.measured = 2.0 * (extrema_.back().t - extrema_.front().t) / double(extrema_.size() - 1);
        period.measured_text = format("from %.0f half swings", double(extrema_.size() - 1));
        if (w2 > 0.0) period.agrees = within(*period.measured, period.predicted, period.tolerance);
    }
    if (kind == "damper_decay") {
        // Successive extrema differ by D_i proportional to e^(-gamma t_i) (the turning points of
        // e^(-gamma t) cos(w_d t) are half a period apart), so gamma = ln(D_first / D_last) / (t_last - t_first).
        Comparison decay = comparison("decay rate", "gamma = c / 2m", "Eq. 22", "1/s");
        decay.predicted = gamma;
        decay.tolerance = 0.02;
        if (extrema_.size() >= 4) {
            const double first = std::abs(extrema_[1].value - extrema_[0].value);
            const std::size_t n = extrema_.size();
            const double last = std::abs(extrema_[n - 1].value - extrema_[n - 2].value);
            if (first > 0.0 && last > 0.0) {
                decay.measured = std::log(first / last) / (extrema_[n - 2].t - extrema_[0].t);
                decay.measured_text = format("over %.1f s", extrema_[n - 2].t - extrema_[0].t);
                decay.agrees = within(*decay.measured, gamma, decay.tolerance);
            }
        }
        out.push_back(decay);
    }
    out.push_back(period);
}

// Eq. 23: the speed where drag cancels the weight.
void LessonMeter::compare_terminal_velocity(const World& world, double elapsed, std::vector<Comparison>& out) const {
    // Eq. 23 against the weight: m g = 1/2 rho C_D S v^2, so v_t = sqrt(2 m g / (rho C_D S));
    // falling from rest, v = v_t tanh(g t / v_t).
    const RigidBody& b = world.rigid_body(body_);
    const double g = length(Vec3d(world.settings().gravity));
    const double drag = 0.5 * double(world.settings().air_density) * double(b.drag_coefficient) * b.drag_area;
    Comparison v = comparison("terminal speed", "v_t = sqrt(2 m g / (rho C_D S))", "Eq. 23", "m/s");
    v.predicted = drag > 0.0 ? std::sqrt(b.mass * g / drag) : kNaN;
    if (!(drag > 0.0)) v.predicted_text = "none: no drag";
    v.tolerance = 0.01;
    v.measured = speed_;
    v.measured_text = landed_ ? "as it landed" : "speed now";
    // Judged once tanh(g t / v_t) is within 1e-3 of 1 (4 v_t / g), or when it lands.
    if (speed_ && drag > 0.0 && (landed_ || elapsed >= 4.0 * v.predicted / g)) {
        v.agrees = within(*speed_, v.predicted, v.tolerance);
    }
    out.push_back(v);
}

// Eq. 24, 25: held on the slope, or sliding down it.
void LessonMeter::compare_friction_slope(const World& world, double elapsed, std::vector<Comparison>& out) const {
    // Eq. 24: at rest, friction cancels the pull along the slope, m g sin theta, while it is
    // within mu_s m g cos theta: held while tan theta <= mu_s. Eq. 25: sliding, friction is
    // mu_d m g cos theta, so a = g (sin theta - mu_d cos theta).
    const SlopeFrame f = slope_frame(world, slope_);
    // A particle on a rigid body: the body's friction for both, if it sets one (physics/README.md#materials).
    const std::optional<float> own = slope_ ? world.rigid_body(*slope_).friction : std::nullopt;
    const double mu_s = own ? double(*own) : double(world.settings().static_friction);
    const double mu_d = own ? double(*own) : double(world.settings().dynamic_friction);
    const bool slides = std::tan(f.theta) > mu_s;
    Comparison hold = comparison("tan theta against mu_s", "held while tan theta <= mu_s", "Eq. 24", "");
    hold.predicted = std::tan(f.theta);
    hold.predicted_text = format(slides ? "slides: tan %.0f deg = %.3f > mu_s" : "holds: tan %.0f deg = %.3f <= mu_s",
                                 f.theta * 180.0 / std::numbers::pi, std::tan(f.theta)) + format(" = %.2f", mu_s);
    const bool moved = travelled_ > 0.01;  // a centimetre down the slope
    hold.measured_text = moved ? format("slides: %.2f m down", travelled_)
                               : format(elapsed >= 1.0 ? "holds: %.1f mm down" : "holds so far: %.1f mm down", travelled_ * 1e3);
    if (moved || elapsed >= 1.0) hold.agrees = moved == slides;
    out.push_back(hold);

    Comparison a = comparison("acceleration down the slope", slides ? "a = g (sin theta - mu_d cos theta)" : "a = 0 (held)",
                 slides ? "Eq. 25" : "Eq. 24", "m/s^2");
    a.predicted = slides ? f.g * (std::sin(f.theta) - mu_d * std::cos(f.theta)) : 0.0;
    a.tolerance = 0.05;
    if (slide_.size() >= 10 && slide_.back().first - slide_.front().first >= 0.2) {
        a.measured = fitted_slope(slide_);
        a.measured_text = format("fitted over %.2f s of sliding", slide_.back().first - slide_.front().first);
    } else if (!moved && elapsed >= 1.0) {
        a.measured = 0.0;
        a.measured_text = "held";
    }
    // Judged against the scale of the pull, g sin theta, when the prediction is zero.
    if (a.measured) a.agrees = std::abs(*a.measured - a.predicted) <= a.tolerance * std::max(std::abs(a.predicted), 0.1 * f.g * std::sin(f.theta));
    out.push_back(a);
}

// Listing 8's stability: stable below 1, diverging above.
void LessonMeter::compare_stability(const World& world, double elapsed, std::vector<Comparison>& out) const {
    // physics/README.md#stability: all pairs joined, equal masses; the fastest mode is the whole
    // body's swelling, omega^2 = N k / m, and Verlet is stable while N (k h^2 + 2 c h) < 4 m.
    const SoftBody& b = world.soft_body(body_);
    const double N = double(b.particle_count()), h = double(world.settings().dt) / world.substeps_in_use();
    const double ratio = N * (double(b.stiffness) * h * h + 2.0 * double(b.damping) * h) / (4.0 * double(b.mass));
    Comparison s = comparison("N (k h^2 + 2 c h) / 4 m", "stable below 1 (Verlet)", "Listing 8, stability", "");
    s.predicted = ratio;
    s.predicted_text = format(ratio < 1.0 ? "stable: %.3g < 1 at %.0f substeps" : "diverges: %.3g > 1 at %.0f substeps",
                              ratio, double(world.substeps_in_use()));
    const bool diverged = world.status() != Status::Ok;
    s.measured_text = diverged ? format("diverged at t = %.2f s", world.time()) : format("stable for %.2f s", world.time());
    if (diverged || elapsed >= 2.0) s.agrees = diverged == (ratio >= 1.0);
    out.push_back(s);
}

// Table 1: a primitive's inertia tensor, and its angular momentum.
void LessonMeter::compare_inertia(const World& world, double, std::vector<Comparison>& out) const {
    // Table 1, about the centre of mass: box a x b x c, J_xx = m (b^2 + c^2) / 12 and so on;
    // sphere 2/5 m r^2; cylinder (axis z) 1/2 m r^2 about z and m (3 r^2 + h^2) / 12 across.
    const RigidBody& b = world.rigid_body(body_);
    const double m = b.mass;
    Vec3d J{kNaN, kNaN, kNaN};
    if (b.shape == ShapeKind::Box) {
        const Vec3d s = b.size;
        J = Vec3d{s.y * s.y + s.z * s.z, s.x * s.x + s.z * s.z, s.x * s.x + s.y * s.y} * (m / 12.0);
    } else if (b.shape == ShapeKind::Sphere) {
        J = Vec3d{1.0, 1.0, 1.0} * (0.4 * m * b.radius * b.radius);
    } else if (b.shape == ShapeKind::Cylinder) {
        const double across = m * (3.0 * b.radius * b.radius + b.height * b.height) / 12.0;
        J = Vec3d{across, across, 0.5 * m * b.radius * b.radius};
    }
    const char* names[3] = {"J_xx", "J_yy", "J_zz"};
    const char* formulas[3] = {"box: m (b^2 + c^2) / 12", "box: m (a^2 + c^2) / 12", "box: m (a^2 + b^2) / 12"};
    for (int a = 0; a < 3; ++a) {
        Comparison c = comparison(names[a], b.shape == ShapeKind::Box ? formulas[a] : b.shape == ShapeKind::Sphere ? "2/5 m r^2"
                                                                       : a == 2 ? "1/2 m r^2" : "m (3 r^2 + h^2) / 12",
                     "Table 1", "kg m^2");
        c.predicted = J[a];
        if (std::isnan(J[a])) c.predicted_text = "no closed form: a mesh (Mirtich's integrals)";
        if (from_triangles_) {
            // Measured another way: the same solid as triangles, by the divergence theorem
            // (Eq. 29-31 as mesh bodies get theirs), scaled to the body's mass.
            c.measured = from_triangles_->inertia.m[a][a] * (m / from_triangles_->volume);
            c.measured_text = b.shape == ShapeKind::Box ? "Eq. 29-31 over its 12 triangles" : "Eq. 29-31 over its triangles";
            // A box's triangles are the box (float corners: 1e-7); a sphere's or cylinder's
            // are inscribed, 3.6e-4 and 2.5e-5 short at these counts (lesson_test.cpp).
            c.tolerance = b.shape == ShapeKind::Box ? 1e-6 : 1e-3;
        } else {
            c.measured = b.J_body.m[a][a];
            c.measured_text = "the body's J_body, from its triangles";
        }
        if (!std::isnan(J[a])) c.agrees = within(*c.measured, J[a], c.tolerance);
        out.push_back(c);
    }
    // And L = J w (Eq. 28) is what the body keeps between contacts: its size now.
    Comparison L = comparison("|L| about the centre of mass", "L = J_world w (Eq. 28), constant in flight (Eq. 26)", "Eq. 26, 28", "kg m^2/s");
    const RigidMotion start = rigid_motion(b, b.initial.data());
    L.predicted = length(start.L);
    L.measured = length(world.rigid_motion(body_).L);
    L.measured_text = rigid_touches_anything(world, body_) ? "now (a contact changes it)" : "now";
    L.tolerance = 1e-6;
    out.push_back(L);
}

// Eq. 37, 38 at the first hit: the impulse, and the motion it leaves.
void LessonMeter::compare_collision(const World& world, double, std::vector<Comparison>& out) const {
    // Eq. 38 at the first hit: lambda = -(1 + e) v_rel . n / (1/m_1 + 1/m_2 + n . ((J_1^-1
    // (r_1 x n)) x r_1) + n . ((J_2^-1 (r_2 x n)) x r_2)), from the velocities just before,
    // e and the masses as they are; then Eq. 37: each body's P changes by its +-lambda n and
    // its L by r x (+-lambda n). Measured from the motion itself, before and after the tick.
    const RigidBody& b = world.rigid_body(body_);
    Comparison lambda = comparison("lambda, the impulse", "-(1 + e) v_rel . n / (1/m_1 + 1/m_2 + rotation terms)", "Eq. 38", "N s");
    lambda.tolerance = 1e-6;
    if (!hit_) {
        lambda.predicted = kNaN;
        lambda.predicted_text = "at the first hit";
        out.push_back(lambda);
        return;  // nothing else to compare before the hit
    }
    const Hit& h = *hit_;
    const Vec3d n = h.terms.n;
    const double s = h.sign;
    lambda.predicted = h.terms.lambda;
    lambda.measured = s * b.mass * dot(h.body_after.v - h.body_before.v, n);
    lambda.measured_text = format("from the change of its momentum at t = %.2f s", h.time);
    lambda.agrees = within(*lambda.measured, lambda.predicted, lambda.tolerance);
    out.push_back(lambda);

    // Its spin after: w' = J_world^-1 (L + r x (+-lambda n)), with J_world as it is after the tick.
    const Vec3d r = s > 0.0 ? h.terms.r1 : h.terms.r2;
    Comparison spin = comparison("|w| after, of '" + b.name + "'", "J_world^-1 (L + r x lambda n)", "Eq. 37, 36", "rad/s");
    spin.predicted = length(h.body_after.J_inv * (h.body_before.L + cross(r, n * (s * h.terms.lambda))));
    spin.measured = length(h.body_after.omega);
    spin.tolerance = 1e-6;
    spin.agrees = within(*spin.measured, spin.predicted, spin.tolerance);
    out.push_back(spin);

    if (h.other) {  // the other body's velocity along n after: it takes the opposite impulse
        const RigidBody& o = world.rigid_body(*h.other);
        Comparison v = comparison("v . n after, of '" + o.name + "'", "v' = v + J / m, J its impulse (-lambda n)", "Eq. 37", "m/s");
        v.predicted = dot(h.other_before.v, n) - s * h.terms.lambda / o.mass;
        v.measured = dot(h.other_after.v, n);
        v.tolerance = 1e-6;
        v.agrees = within(*v.measured, v.predicted, v.tolerance);
        out.push_back(v);
    }
}

// Eq. 35, Listing 9: |q| under the integrator.
void LessonMeter::compare_quaternion_norm(const World& world, double, std::vector<Comparison>& out) const {
    // Eq. 35 by explicit Euler (Listing 9): q' = q + h/2 w q. For a spin about a principal
    // axis w stays put and w q is perpendicular to q (as 4-vectors), so each step multiplies
    // |q|^2 by 1 + (h |w| / 2)^2: after n steps |q| = (1 + (h |w| / 2)^2)^(n / 2). The other
    // integrators turn q by a rotation (symplectic Euler) or keep it to their own error (RK4).
    const RigidBody& b = world.rigid_body(body_);
    const double w = length(rigid_motion(b, b.initial.data()).omega);
    const int every = world.settings().renormalize_every;
    const double h = double(world.settings().dt) / world.substeps_in_use();
    const std::uint64_t ticks = every > 0 ? world.ticks() % std::uint64_t(every) : world.ticks();
    const double steps = double(ticks) * world.substeps_in_use();
    const bool euler = world.settings().integrator == Integrator::ExplicitEuler;
    Comparison q = comparison("|q|", euler ? "(1 + (h w / 2)^2)^(n / 2), n steps since renormalising" : "1 (a rotation keeps it)",
                 "Eq. 35, Listing 9", "");
    q.predicted = euler ? std::pow(1.0 + 0.25 * h * h * w * w, 0.5 * steps) : 1.0;
    q.measured = world.rigid_motion(body_).q.norm();
    q.measured_text = every > 0 ? format("renormalised every %.0f ticks", double(every)) : "never renormalised";
    q.tolerance = euler ? 1e-6 : 1e-4;
    q.agrees = within(*q.measured, q.predicted, q.tolerance);
    out.push_back(q);
}

// Eq. 26, 28: the time between flips about the intermediate axis.
void LessonMeter::compare_flip_period(const World& world, double, std::vector<Comparison>& out) const {
    // Euler's equations (Eq. 26, 28 in body axes, no torque), after Landau and Lifshitz
    // section 37: with I1 < I2 < I3, 2E = sum I w^2 and M^2 = sum I^2 w^2, the intermediate
    // axis's w2 goes as sn(tau, k) with tau = t sqrt((I3 - I2)(M^2 - 2E I1) / (I1 I2 I3)) and
    // k^2 = (I2 - I1)(2E I3 - M^2) / ((I3 - I2)(M^2 - 2E I1)) when M^2 > 2E I2 (indices 1 and
    // 3 swapped otherwise): it changes sign every 2 K(k) of tau, a flip every T.
    const RigidBody& b = world.rigid_body(body_);
    const Vec3d w0 = body_omega(rigid_motion(b, b.initial.data()));
    int order[3] = {0, 1, 2};
    std::sort(order, order + 3, [&](int p, int r) { return b.J_body.m[p][p] < b.J_body.m[r][r]; });
    const double I1 = b.J_body.m[order[0]][order[0]], I2 = b.J_body.m[order[1]][order[1]], I3 = b.J_body.m[order[2]][order[2]];
    const double w1 = w0[order[0]], w2 = w0[order[1]], w3 = w0[order[2]];
    const double twoE = I1 * w1 * w1 + I2 * w2 * w2 + I3 * w3 * w3;
    const double M2 = I1 * I1 * w1 * w1 + I2 * I2 * w2 * w2 + I3 * I3 * w3 * w3;
    double T = kNaN;
    if (M2 > twoE * I2) {
        const double k2 = (I2 - I1) * (twoE * I3 - M2) / ((I3 - I2) * (M2 - twoE * I1));
        T = 2.0 * elliptic_k(k2) * std::sqrt(I1 * I2 * I3 / ((I3 - I2) * (M2 - twoE * I1)));
    } else if (M2 < twoE * I2) {
        const double k2 = (I3 - I2) * (M2 - twoE * I1) / ((I2 - I1) * (twoE * I3 - M2));
        T = 2.0 * elliptic_k(k2) * std::sqrt(I1 * I2 * I3 / ((I2 - I1) * (twoE * I3 - M2)));
    }
    Comparison flip = comparison("time between flips", "T = 2 K(k) sqrt(I1 I2 I3 / ((I3 - I2)(M^2 - 2E I1)))", "Eq. 26, 28", "s");
    flip.predicted = T;
    if (std::isnan(T)) flip.predicted_text = "on the separatrix: never flips back";
    // Near the separatrix T is sensitive to E: RK4 at dt = 0.02 s drifts it by 7e-6 in 20 s
    // and the flips come 1.2% late (lesson_test.cpp); a quarter of the step, 1e-4.
    flip.tolerance = 0.02;
    if (crossings_.size() >= 2) {
        flip.measured = (crossings_.back() - crossings_.front()) / double(crossings_.size() - 1);
        flip.measured_text = format("from %.0f flips", double(crossings_.size() - 1));
        if (!std::isnan(T)) flip.agrees = within(*flip.measured, T, flip.tolerance);
    }
    out.push_back(flip);
}

}  // namespace softbody
