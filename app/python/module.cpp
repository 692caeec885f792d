// softbody, the Python module: the World of physics/world.h for Python and numpy (README.md
// here has the whole API with an example).
//
//   w = softbody.World("spring.json", threads=2, dt=0.01)   # a scene as --scene finds it, keys as --set
//   w.set("bob.mass", 0.25); w.step(100); w.state_hash     # the hash `softbody simulate` prints
//   x, y, z = w.positions("jelly")                           # views of the world's own arrays
//
// The module adds no physics and no parsing of its own: a scene is opened as --scene opens it
// (app/scene_source.h), a key goes in as the text --set would give it (so a refusal is the
// command line's line, word for word), a picture is drawn as `softbody render` draws it.
//
// Errors: InputError is ValueError, FileError (a file that cannot be read) OSError, a world that
// diverged softbody.Diverged, anything else RuntimeError; each with the line the command line prints.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <charconv>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "physics/energy_ledger.h"
#include "physics/error.h"
#include "physics/keys.h"
#include "physics/scene_io.h"
#include "physics/series.h"
#include "physics/thread_pool.h"
#include "physics/world.h"
#include "scene_source.h"

#if defined(SOFTBODY_PYTHON_RENDER)
#include "body_view.h"
#include "offscreen_context.h"
#include "render/renderer.h"
#endif

namespace py = pybind11;

namespace softbody::python {

namespace {

// The limits the command line puts on the same numbers (--threads, --ticks).
constexpr long long kMaxThreads = 256;
constexpr long long kMaxTicks = 1'000'000'000;

// Raised by step() for a world that has diverged: its message is why, and what to change.
struct Diverged : std::runtime_error {
    using std::runtime_error::runtime_error;
};
// A call the world refuses in its present state (views alive, stepping in another thread).
struct Busy : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// --- Python values as the command line's text, and keys' values back as Python values -------

std::string number_text(double value) {
    // Python's repr: the shortest text that reads back as the same double ("0.25", "1e+300",
    // "nan", "inf"); the key's own parser then checks it as it checks --set's text.
    return py::repr(py::float_(value)).cast<std::string>();
}

// None as text: the word the key takes for unset ("none", "auto": keys.h, unset_word).
std::string unset_text(const std::string& key) {
    const std::string_view name = split_key_name(key).key;
    for (KeyOwner owner : {KeyOwner::World, KeyOwner::SoftBody, KeyOwner::RigidBody, KeyOwner::Spring}) {
        if (const KeyInfo* info = find_key(owner, name); info && !info->unset_word.empty()) return std::string(info->unset_word);
    }
    return "none";
}

std::string scalar_text(const std::string& key, const py::handle& value) {
    if (value.is_none()) return unset_text(key);
    if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
    if (py::isinstance<py::str>(value)) return value.cast<std::string>();
    if (py::hasattr(value, "__index__")) return py::repr(py::module_::import("operator").attr("index")(value)).cast<std::string>();
    if (py::hasattr(value, "__float__")) return number_text(value.cast<double>());
    throw InputError("key '" + key + "': expected a number, true or false, text, None or a sequence of numbers, got " +
                     py::str(py::type::of(value).attr("__name__")).cast<std::string>());
}

// Text from Python for a name or a path: a NUL inside would cut it short on its way to the system.
std::string checked_text(const std::string& what, std::string text) {
    if (text.find('\0') != std::string::npos) throw InputError(what + ": text with a NUL character in it");
    return text;
}

// The text `--set KEY=TEXT` would carry for a Python value: 0.25 -> "0.25", True -> "true",
// (0, 0, -9.81) -> "0,0,-9.81", [0, 5] -> "0,5", None -> "none".
std::string key_text_of(const std::string& key, const py::handle& value) {
    if (py::isinstance<py::str>(value) || py::isinstance<py::bytes>(value) || !py::isinstance<py::sequence>(value)) {
        if (py::isinstance<py::bytes>(value)) throw InputError("key '" + key + "': expected text, not bytes");
        return checked_text("key '" + key + "'", scalar_text(key, value));
    }
    std::string text;
    const py::sequence items = py::reinterpret_borrow<py::sequence>(value);
    for (std::size_t i = 0; i < items.size(); ++i) {
        const py::object item = items[i];
        if (py::isinstance<py::sequence>(item) && !py::isinstance<py::str>(item)) {
            throw InputError("key '" + key + "': expected a flat sequence of numbers");
        }
        text += (i > 0 ? "," : "") + scalar_text(key, item);
    }
    return checked_text("key '" + key + "'", text);
}

// A key held as float (keys.h: single) as the decimal it is written as: dt 0.02, not 0.0199999996.
double as_written(const KeyInfo& info, double value) {
    if (!info.single || !std::isfinite(value)) return value;
    char text[32];
    const auto end = std::to_chars(text, text + sizeof text, static_cast<float>(value)).ptr;
    double written = value;
    std::from_chars(text, end, written);
    return written;
}

py::object python_value(const KeyInfo& info, const KeyValue& value) {
    return std::visit(
        [&](const auto& v) -> py::object {
            using T = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<T, std::monostate>) return py::none();
            else if constexpr (std::is_same_v<T, double>) {
                if (info.type == KeyType::Whole) return py::int_(static_cast<long long>(v));
                return py::float_(as_written(info, v));
            } else if constexpr (std::is_same_v<T, bool>) return py::bool_(v);
            else if constexpr (std::is_same_v<T, Vec3d>) {
                return py::make_tuple(as_written(info, v.x), as_written(info, v.y), as_written(info, v.z));
            }
            else if constexpr (std::is_same_v<T, Quat>) return py::make_tuple(v.w, v.x, v.y, v.z);
            else if constexpr (std::is_same_v<T, std::string>) return py::str(v);
            else return py::cast(v);  // vertex indices: a list
        },
        value);
}

std::string_view type_text(KeyType type) {
    switch (type) {
        case KeyType::Number: return "number";
        case KeyType::Whole: return "whole number";
        case KeyType::Bool: return "true/false";
        case KeyType::Vec3: return "x,y,z";
        case KeyType::Quat: return "w,x,y,z";
        case KeyType::Word: return "word";
        case KeyType::Path: return "file";
        case KeyType::IndexList: return "indices";
    }
    return "";
}

std::string hex16(std::uint64_t value) {
    char text[17];
    std::snprintf(text, sizeof text, "%016" PRIx64, value);
    return text;
}

// A whole number from `low` to `high`, refused as the command line refuses its options.
long long whole_argument(const char* name, const py::handle& value, long long low, long long high) {
    const std::string problem = std::string(name) + ": expected a whole number from " + std::to_string(low) + " to " +
                                std::to_string(high) + ", got ";
    if (py::isinstance<py::bool_>(value) || !py::hasattr(value, "__index__")) {
        throw InputError(problem + "'" + py::repr(value).cast<std::string>() + "'");
    }
    const py::int_ number = py::module_::import("operator").attr("index")(value);
    if (number < py::int_(low) || number > py::int_(high)) throw InputError(problem + "'" + py::repr(number).cast<std::string>() + "'");
    return number.cast<long long>();
}

// --- Views: numpy arrays over a soft body's own x and v ----------------------------------------

// The base object of every numpy view of one soft body's array: it keeps the Python World (and
// so the memory) alive, and says which body the memory is, so that what would free or move that
// memory (destroying the body, a reset that rebuilds it, a restore without it) is refused while
// a view of it, or a slice of one, lives.
struct ViewOwner {
    py::object world;
    SoftBodyId body;
};

}  // namespace

// A snapshot of a world (World.snapshot), to restore later into the same world.
struct Snapshot {
    const void* world = nullptr;  // the World it was taken from
    WorldSnapshot state;
    EnergyLedger ledger;
};

// The World as Python sees it: the physics' World, the energy ledger and the series it keeps
// while it steps, and the views it has handed out.
class PyWorld {
public:
    PyWorld(const std::string& scene, const py::object& threads, long long series_every, const py::kwargs& keys) {
        const int count = int(whole_argument("threads", threads, 1, kMaxThreads));
        series_every_ = whole_argument("series_every", py::int_(series_every), 0, kMaxTicks);
        Scene resolved = app::open_scene(checked_text("scene", scene));
        for (const auto& [name, value] : keys) {
            const std::string key = py::str(name).cast<std::string>();
            set_scene_key(resolved, key, key_text_of(key, value));
        }
        app::require_bodies(resolved);
        world_ = std::make_unique<World>(resolved, WorldOptions{count, false});
        for (const std::string& note : world_->notes()) notes_.push_back(note);
        restart_series();
    }

    // --- Time ---------------------------------------------------------------------------------
    void step(const py::object& ticks_object) {
        const auto ticks = whole_argument("ticks", ticks_object, 0, kMaxTicks);
        {
            Guard guard(*this);
            py::gil_scoped_release release;
            // Ctrl+C stops a long run between two ticks (the ticks done so far stay done).
            using Clock = std::chrono::steady_clock;
            auto checked = Clock::now();
            for (long long t = 0; t < ticks && world_->status() == Status::Ok; ++t) {
                world_->tick();
                if (world_->status() == Status::Ok && series_ && world_->ticks() % std::uint64_t(series_every_) == 0) record();
                if (Clock::now() - checked > std::chrono::milliseconds(100)) {
                    checked = Clock::now();
                    py::gil_scoped_acquire acquire;
                    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
                }
            }
            if (world_->status() == Status::Ok) ledger_.observe(*world_);
        }
        if (world_->status() != Status::Ok) throw Diverged(world_->divergence());
    }
    void reset() {
        Guard guard(*this);
        if (world_->reset_pending()) {
            for (std::size_t b = 0; b < world_->soft_body_count(); ++b) refuse_if_viewed(world_->soft_body_id(b), "reset (it is rebuilt)");
        }
        world_->reset();
    }

    // --- Keys ---------------------------------------------------------------------------------
    void set(const std::string& name, const py::handle& value) {
        Guard guard(*this);
        world_->set_key_text(name, key_text_of(name, value));
    }
    void set_many(const py::kwargs& keys) {
        for (const auto& [name, value] : keys) set(py::str(name).cast<std::string>(), value);
    }
    py::object get(const std::string& name) const {
        Guard guard(*this);
        const WorldDef def = world_->def();
        const std::vector<KeyTarget> targets = resolve_key(name, thing_names(def));
        if (targets.empty()) throw InputError("key '" + name + "': nothing in the world has it");
        return python_value(*targets.front().info, world_->key(name));
    }
    // Every key of this world by the name set() takes: the world's, then each body's and each
    // named spring's, with its value now, unit, range, default and meaning (keys.h).
    py::list keys() const {
        Guard guard(*this);
        const WorldDef def = world_->def();
        py::list out;
        const auto add = [&](const KeyInfo& info, const std::string& thing, const KeyValue& value) {
            py::dict entry;
            entry["name"] = thing.empty() ? std::string(info.name) : thing + "." + std::string(info.name);
            entry["owner"] = std::string(to_string(info.owner));
            entry["thing"] = thing.empty() ? py::object(py::none()) : py::object(py::str(thing));
            entry["value"] = python_value(info, value);
            entry["default"] = python_value(info, default_value(info));
            entry["type"] = std::string(type_text(info.type));
            entry["unit"] = std::string(info.unit);
            entry["range"] = key_range_text(info);
            entry["min"] = info.min;
            entry["max"] = info.max;
            entry["on_reset"] = info.on_reset;
            entry["equation"] = std::string(info.equation);
            entry["meaning"] = std::string(info.meaning);
            out.append(entry);
        };
        for (const KeyInfo* info : keys_of(KeyOwner::World)) {
            if (!info->alias) add(*info, "", get_key(def.settings, *info));
        }
        for (const SoftBodyDef& body : def.soft_bodies) {
            for (const KeyInfo* info : keys_of(KeyOwner::SoftBody)) {
                if (!info->alias) add(*info, body.name, get_key(body, *info));
            }
        }
        for (const RigidBodyDef& body : def.rigid_bodies) {
            for (const KeyInfo* info : keys_of(KeyOwner::RigidBody)) {
                if (!info->alias) add(*info, body.name, get_key(body, *info));
            }
        }
        for (const SpringDef& spring : def.springs) {
            if (spring.name.empty()) continue;  // a spring without a name has no keys to set
            for (const KeyInfo* info : keys_of(KeyOwner::Spring)) {
                if (!info->alias) add(*info, spring.name, get_key(spring, *info));
            }
        }
        return out;
    }

    // --- What the world is now ----------------------------------------------------------------
    double time() const {
        Guard guard(*this);
        // The decimal the tick is (tick x dt's shortest text), as softbody simulate's sim_time: 2, not 1.99999996.
        return std::stod(tick_time_text(world_->ticks(), world_->settings().dt));
    }
    std::uint64_t ticks() const {
        Guard guard(*this);
        return world_->ticks();
    }
    std::string state_hash() const {
        Guard guard(*this);
        return hex16(world_->state_hash());
    }
    std::string status() const {
        Guard guard(*this);
        return world_->status() == Status::Ok ? "ok" : "diverged";
    }
    py::object divergence() const {
        Guard guard(*this);
        if (world_->status() == Status::Ok) return py::none();
        return py::str(world_->divergence());
    }
    int threads() const { return world_->threads(); }
    void set_threads(const py::object& threads) {
        Guard guard(*this);
        world_->set_threads(int(whole_argument("threads", threads, 1, kMaxThreads)));
    }
    py::dict energy() {
        Guard guard(*this);
        const Energy e = world_->energy();
        ledger_.observe(*world_);
        py::dict out;
        out["kinetic"] = e.kinetic;
        out["rotational"] = e.rotational;
        out["gravity"] = e.gravity;
        out["elastic"] = e.elastic;
        out["total"] = e.total();
        out["dissipated"] = ledger_.dissipated();
        return out;
    }
    std::vector<std::string> soft_bodies() const {
        std::vector<std::string> names;
        for (std::size_t b = 0; b < world_->soft_body_count(); ++b) names.push_back(world_->soft_body(b).name());
        return names;
    }
    std::vector<std::string> rigid_bodies() const {
        std::vector<std::string> names;
        for (std::size_t b = 0; b < world_->rigid_body_count(); ++b) names.push_back(world_->rigid_body(b).name);
        return names;
    }
    std::vector<std::string> springs() const {
        std::vector<std::string> names;
        for (std::size_t s = 0; s < world_->spring_count(); ++s) names.push_back(world_->def(world_->spring_id(s)).name);
        return names;
    }
    std::vector<std::string> notes() const { return notes_; }

    // --- Soft bodies: views of x and v --------------------------------------------------------
    py::object positions(const py::object& self, const py::object& body) { return views(self, body, false); }
    py::object velocities(const py::object& self, const py::object& body) { return views(self, body, true); }

    // --- Rigid bodies: Listing 10's state, copied ---------------------------------------------
    py::dict rigid_body(const py::object& body) const {
        Guard guard(*this);
        const std::size_t b = rigid_index(body);
        const RigidBody& r = world_->rigid_body(b);
        const RigidMotion m = world_->rigid_motion(b);
        const auto vec = [](const Vec3d& v) {
            py::array_t<double> a(3);
            a.mutable_at(0) = v.x;
            a.mutable_at(1) = v.y;
            a.mutable_at(2) = v.z;
            return a;
        };
        py::array_t<double> q(4);
        q.mutable_at(0) = m.q.w;
        q.mutable_at(1) = m.q.x;
        q.mutable_at(2) = m.q.y;
        q.mutable_at(3) = m.q.z;
        py::dict out;
        out["name"] = r.name;
        out["shape"] = std::string(to_string(r.shape));
        out["mass"] = r.fixed ? py::float_(INFINITY) : py::float_(r.mass);
        out["fixed"] = r.fixed;
        out["position"] = vec(m.x);
        out["orientation"] = q;
        out["velocity"] = vec(m.v);
        out["angular_velocity"] = vec(m.omega);
        out["momentum"] = vec(m.P);
        out["angular_momentum"] = vec(m.L);
        out["asleep"] = world_->rigid_asleep(b);
        return out;
    }

    // --- Made and unmade while it runs --------------------------------------------------------
    std::string add_soft_body(const std::string& name, const std::string& mesh, const py::kwargs& keys) {
        Guard guard(*this);
        Scene scene;
        SoftBodyDef def;
        def.name = name;
        def.mesh = checked_text("mesh", mesh);
        scene.soft_bodies.push_back(def);
        for (const auto& [key, value] : keys) {
            const std::string k = py::str(key).cast<std::string>();
            set_scene_key(scene, name + "." + k, key_text_of(k, value));
        }
        world_->create_soft_body(scene.soft_bodies.front());
        return name;
    }
    std::string add_rigid_body(const std::string& name, const std::string& shape, const py::kwargs& keys) {
        Guard guard(*this);
        Scene scene;
        RigidBodyDef def;
        def.name = name;
        scene.rigid_bodies.push_back(def);
        set_scene_key(scene, name + ".shape", shape);
        for (const auto& [key, value] : keys) {
            const std::string k = py::str(key).cast<std::string>();
            set_scene_key(scene, name + "." + k, key_text_of(k, value));
        }
        world_->create_rigid_body(scene.rigid_bodies.front());
        return name;
    }
    std::string add_spring(const py::object& a, const py::object& b, const py::object& stiffness, const py::object& damping,
                           const py::object& rest_length, const std::string& name) {
        Guard guard(*this);
        // The numbers go through the key table (its ranges and messages) as a scene's would, by
        // the spring's name (a stand-in for one without, given back after).
        const std::string key_name = name.empty() ? std::string("spring") : name;
        SpringDef def;
        def.name = key_name;
        def.a = spring_end(a, "a");
        def.b = spring_end(b, "b");
        Scene scene;
        scene.springs.push_back(def);
        set_scene_key(scene, key_name + ".stiffness", key_text_of("stiffness", stiffness));
        set_scene_key(scene, key_name + ".damping", key_text_of("damping", damping));
        set_scene_key(scene, key_name + ".rest_length", key_text_of("rest_length", rest_length));
        def = scene.springs.front();
        def.name = name;
        world_->create_spring(def);
        return name;
    }
    void destroy(const std::string& name) {
        Guard guard(*this);
        if (const auto id = world_->find_soft_body(name)) {
            refuse_if_viewed(*id, "destroyed");
            world_->destroy(*id);
        } else if (const auto rigid = world_->find_rigid_body(name)) {
            world_->destroy(*rigid);
        } else if (const auto spring = world_->find_spring(name)) {
            world_->destroy(*spring);
        } else {
            throw InputError("nothing named '" + name + "' in the world to destroy");
        }
    }

    // --- Time travel --------------------------------------------------------------------------
    Snapshot snapshot() const {
        Guard guard(*this);
        return Snapshot{world_.get(), world_->snapshot(), ledger_};
    }
    void restore(const Snapshot& snapshot) {
        Guard guard(*this);
        if (snapshot.world != world_.get()) throw InputError("a snapshot of another world: restore it into the world it was taken from");
        for (std::size_t b = 0; b < world_->soft_body_count(); ++b) {
            const SoftBodyId id = world_->soft_body_id(b);
            if (!snapshot.state.soft_ids.contains(id)) refuse_if_viewed(id, "unmade by the restore");
        }
        world_->restore(snapshot.state);
        ledger_ = snapshot.ledger;
    }

    // --- The series (physics/series.h) --------------------------------------------------------
    py::dict series() const {
        Guard guard(*this);
        py::dict out;
        if (!series_) return out;
        const std::size_t rows = series_->size();
        py::array_t<std::uint64_t> ticks(rows);
        for (std::size_t r = 0; r < rows; ++r) ticks.mutable_at(r) = series_->tick(r);
        out["tick"] = ticks;
        for (std::size_t k = 0; k < series_->columns().size(); ++k) {
            const std::vector<double>& column = series_->column(k);
            py::array_t<double> values(column.size());
            std::copy(column.begin(), column.end(), values.mutable_data());
            out[py::str(series_->columns()[k].name)] = values;
        }
        return out;
    }
    py::dict series_units() const {
        py::dict out;
        if (!series_) return out;
        out["tick"] = "";
        for (const SeriesColumn& column : series_->columns()) out[py::str(column.name)] = column.unit;
        return out;
    }
    void restart_series() {
        Guard guard(*this);
        ledger_ = EnergyLedger();
        ledger_.observe(*world_);
        series_.reset();
        if (series_every_ > 0) {
            series_ = std::make_unique<Series>(*world_);
            series_->record(*world_, ledger_);
        }
    }

    // --- A picture, as `softbody render` draws one --------------------------------------------
    py::array_t<std::uint8_t> render(const py::object& path, const py::object& size) {
        Guard guard(*this);
        if (!py::isinstance<py::sequence>(size) || py::isinstance<py::str>(size) || py::len(size) != 2) {
            throw InputError("size: expected (width, height)");
        }
        const py::sequence wh = py::reinterpret_borrow<py::sequence>(size);
        const int width = int(whole_argument("size (width)", wh[0], 16, 8192));
        const int height = int(whole_argument("size (height)", wh[1], 16, 8192));
#if defined(SOFTBODY_PYTHON_RENDER)
        app::OffscreenContext context(width, height);
        render::Renderer renderer(context.loader());
        if (width > renderer.info().max_size || height > renderer.info().max_size) {
            throw InputError("size " + std::to_string(width) + "x" + std::to_string(height) + ": this OpenGL (" +
                             renderer.info().renderer + ") draws at most " + std::to_string(renderer.info().max_size) +
                             " pixels a side");
        }
        render::Frame frame;
        app::world_view(*world_, 1.0f, frame);
        app::match_ground(world_->settings(), frame.appearance);
        app::frame_body(*world_, float(width) / float(height), frame.camera, 1.0f);
        renderer.draw(frame, width, height);
        const render::Image image = renderer.read_back();
        if (!path.is_none()) {
            const std::string file = py::str(path).cast<std::string>();
            try {
                render::write_png(file, image);
            } catch (const std::runtime_error& e) {
                throw FileError(e.what(), errno);  // a folder that is missing or not writable
            }
        }
        py::array_t<std::uint8_t> pixels({image.height, image.width, 4});
        std::copy(image.rgba.begin(), image.rgba.end(), pixels.mutable_data());
        return pixels;
#else
        (void)path;
        (void)width;
        (void)height;
        throw std::runtime_error("this build of the module has no renderer (built with SOFTBODY_BUILD_GUI=OFF)");
#endif
    }

    const World& world() const { return *world_; }

private:
    // No two calls into the world at once: step() lets go of the GIL, and another Python thread
    // must not change the world under it.
    class Guard {
    public:
        explicit Guard(const PyWorld& w) : w_(w) {
            if (w_.busy_.exchange(true)) throw Busy("the world is stepping in another thread; wait for step() to return");
        }
        ~Guard() { w_.busy_ = false; }
        Guard(const Guard&) = delete;
        Guard& operator=(const Guard&) = delete;

    private:
        const PyWorld& w_;
    };

    void record() {
        ledger_.observe(*world_);
        series_->record(*world_, ledger_);
    }

    std::size_t soft_index(const py::object& body) const {
        if (py::isinstance<py::str>(body)) {
            const std::string name = body.cast<std::string>();
            if (const auto id = world_->find_soft_body(name)) return world_->index(*id);
            throw InputError("no soft body named '" + name + "'" + listing(soft_bodies(), "soft bodies"));
        }
        const long long count = static_cast<long long>(world_->soft_body_count());
        if (count == 0) throw InputError("the world has no soft body");
        return std::size_t(whole_argument("soft body", body, 0, count - 1));
    }
    std::size_t rigid_index(const py::object& body) const {
        if (py::isinstance<py::str>(body)) {
            const std::string name = body.cast<std::string>();
            if (const auto id = world_->find_rigid_body(name)) return world_->index(*id);
            throw InputError("no rigid body named '" + name + "'" + listing(rigid_bodies(), "rigid bodies"));
        }
        const long long count = static_cast<long long>(world_->rigid_body_count());
        if (count == 0) throw InputError("the world has no rigid body");
        return std::size_t(whole_argument("rigid body", body, 0, count - 1));
    }
    static std::string listing(const std::vector<std::string>& names, const char* what) {
        if (names.empty()) return std::string(" (there are no ") + what + ")";
        std::string text = std::string(" (") + what + ": ";
        for (std::size_t i = 0; i < names.size() && i < 8; ++i) text += (i > 0 ? ", " : "") + names[i];
        return text + (names.size() > 8 ? ", ...)" : ")");
    }

    static SpringEndDef spring_end(const py::object& end, const char* which) {
        SpringEndDef out;
        const std::string where = std::string("spring end '") + which + "'";
        const auto point = [&](const py::handle& p) {
            if (!py::isinstance<py::sequence>(p) || py::isinstance<py::str>(p) || py::len(p) != 3) {
                throw InputError(where + ": a point is three numbers (x, y, z)");
            }
            const py::sequence s = py::reinterpret_borrow<py::sequence>(p);
            Vec3d v;
            double* xyz[3] = {&v.x, &v.y, &v.z};
            for (int i = 0; i < 3; ++i) {
                if (!py::hasattr(s[i], "__float__")) throw InputError(where + ": a point is three numbers (x, y, z)");
                *xyz[i] = py::float_(s[i]).cast<double>();
                if (!std::isfinite(*xyz[i])) throw InputError(where + ": a point's coordinates must be finite");
            }
            return v;
        };
        if (py::isinstance<py::dict>(end)) {
            const py::dict d = end.cast<py::dict>();
            for (const auto& [key, value] : d) {
                const std::string k = py::str(key).cast<std::string>();
                if (k == "body") out.body = py::str(value).cast<std::string>();
                else if (k == "point") out.point = point(value);
                else if (k == "vertex") out.vertex = whole_argument((where + ": vertex").c_str(), value, 0, 1LL << 32);
                else throw InputError(where + ": unknown key '" + k + "' (body, point, vertex)");
            }
            return out;
        }
        out.point = point(end);  // a point fixed in the world
        return out;
    }

    void refuse_if_viewed(SoftBodyId id, const char* what) {
        for (auto it = views_.begin(); it != views_.end();) {
            py::object owner = (*it)();
            if (owner.is_none()) {
                it = views_.erase(it);
                continue;
            }
            if (owner.cast<const ViewOwner&>().body == id) {
                throw Busy("soft body '" + world_->def(id).name + "' cannot be " + what +
                           " while numpy views of it (positions, velocities, or slices of them) are alive: del them first");
            }
            ++it;
        }
    }

    py::object views(const py::object& self, const py::object& body, bool velocity) {
        Guard guard(*this);
        const std::size_t b = soft_index(body);
        const SoftBody& soft = world_->soft_body(b);
        const Vec3Array& a = velocity ? soft.v : soft.x;
        py::object owner = py::cast(ViewOwner{self, world_->soft_body_id(b)});
        views_.push_back(py::weakref(owner));
        py::list axes;
        for (const FloatArray* axis : {&a.x, &a.y, &a.z}) {
            py::array_t<float> view({py::ssize_t(axis->size())}, {py::ssize_t(sizeof(float))}, axis->data(), owner);
            view.attr("flags").attr("writeable") = false;
            axes.append(view);
        }
        return py::module_::import("softbody").attr("Axes")(*axes);
    }

    std::unique_ptr<World> world_;
    EnergyLedger ledger_;
    std::unique_ptr<Series> series_;
    long long series_every_ = 1;
    std::vector<std::string> notes_;
    std::vector<py::weakref> views_;
    mutable std::atomic<bool> busy_ = false;
};

}  // namespace softbody::python

PYBIND11_MODULE(softbody, m) {
    using namespace softbody;
    using namespace softbody::python;
    m.doc() = "softbody: the soft-body and rigid-body world of the softbody project, for Python and numpy";

    static py::exception<Diverged> diverged(m, "Diverged", PyExc_RuntimeError);
    py::register_exception_translator([](std::exception_ptr thrown) {
        try {
            if (thrown) std::rethrow_exception(thrown);
        } catch (const Diverged& e) {
            diverged(e.what());
        } catch (const FileError& e) {
            PyObject* kind = PyExc_OSError;
            if (e.error_number() == ENOENT) kind = PyExc_FileNotFoundError;
            else if (e.error_number() == EACCES || e.error_number() == EPERM) kind = PyExc_PermissionError;
            else if (e.error_number() == EISDIR) kind = PyExc_IsADirectoryError;
            py::object error = py::reinterpret_steal<py::object>(PyObject_CallFunction(kind, "s", e.what()));
            if (!error) return;  // the call raised: that error stands
            if (e.error_number() != 0) error.attr("errno") = e.error_number();
            PyErr_SetObject(kind, error.ptr());
        } catch (const InputError& e) {
            PyErr_SetString(PyExc_ValueError, e.what());
        } catch (const std::invalid_argument& e) {
            PyErr_SetString(PyExc_ValueError, e.what());
        }
    });

    // (x, y, z): one float32 view per axis, as the world stores them (a structure of arrays).
    m.attr("Axes") = py::module_::import("collections").attr("namedtuple")("Axes", "x y z");
    m.attr("Axes").attr("__module__") = "softbody";
    m.attr("DEFAULT_THREADS") = kDefaultThreads;

    py::class_<ViewOwner>(m, "_ViewOwner");
    py::class_<Snapshot>(m, "Snapshot", "A world's state at one moment (World.snapshot); restore it into the same world.")
        .def_property_readonly("ticks", [](const Snapshot& s) { return s.state.ticks; })
        .def_property_readonly("bytes", [](const Snapshot& s) { return s.state.bytes(); });

    py::class_<PyWorld>(m, "World", "A world made from a scene; see help(softbody) and app/python/README.md.")
        .def(py::init<const std::string&, const py::object&, long long, const py::kwargs&>(), py::arg("scene") = "",
             py::kw_only(), py::arg("threads") = py::int_(kDefaultThreads), py::arg("series_every") = 1,
             "World(scene='', *, threads=DEFAULT_THREADS, series_every=1, **keys): a scene file, a bundled scene's name\n"
             "('spring.json') or a generated one ('pile:12', 'cloud:300'; '' the default scene), with keys over it as\n"
             "--set gives them (World('spring.json', dt=0.01, **{'bob.mass': 0.25})). The series gets a row every\n"
             "series_every ticks (0: none).")
        .def("step", &PyWorld::step, py::arg("ticks") = 1,
             "Advances ticks fixed ticks of dt (the GIL released). Raises softbody.Diverged when the world has diverged.")
        .def("reset", &PyWorld::reset, "Back to the start: bodies rebuilt from their keys (those that apply on reset take effect).")
        .def("set", &PyWorld::set, py::arg("key"), py::arg("value"),
             "Sets one key as --set names it: 'dt', 'stiffness' (every soft body's), 'bob.mass'.")
        .def("update", &PyWorld::set_many, "update(**keys): set() for each keyword.")
        .def("get", &PyWorld::get, py::arg("key"), "The value of one key as set() names it.")
        .def("keys", &PyWorld::keys, "Every key of this world: name, value, unit, range, default, meaning.")
        .def_property_readonly("time", &PyWorld::time, "simulated time, s (ticks x dt)")
        .def_property_readonly("ticks", &PyWorld::ticks)
        .def_property_readonly("state_hash", &PyWorld::state_hash, "16 hex digits: softbody simulate's state_hash")
        .def_property_readonly("status", &PyWorld::status, "'ok' or 'diverged'")
        .def_property_readonly("divergence", &PyWorld::divergence, "why it diverged, and what to change (None while ok)")
        .def_property("threads", &PyWorld::threads, &PyWorld::set_threads)
        .def_property_readonly("energy", &PyWorld::energy, "J: kinetic, rotational, gravity, elastic, total, dissipated")
        .def_property_readonly("soft_bodies", &PyWorld::soft_bodies)
        .def_property_readonly("rigid_bodies", &PyWorld::rigid_bodies)
        .def_property_readonly("springs", &PyWorld::springs, "the springs' names ('' for one without)")
        .def_property_readonly("notes", &PyWorld::notes, "what was decided while building (softbody: note: ... on the command line)")
        .def(
            "positions", [](py::object self, const py::object& body) { return self.cast<PyWorld&>().positions(self, body); },
            py::arg("body") = 0,
            "Axes(x, y, z): read-only float32 views, shape (N,), of a soft body's particle positions (m), following the\n"
            "world as it steps; np.stack(w.positions(b), axis=1) is an (N, 3) copy.")
        .def(
            "velocities", [](py::object self, const py::object& body) { return self.cast<PyWorld&>().velocities(self, body); },
            py::arg("body") = 0, "As positions(), the particles' velocities (m/s).")
        .def("rigid_body", &PyWorld::rigid_body, py::arg("body") = 0,
             "A rigid body's state now (copies): position, orientation (w, x, y, z), velocity, angular_velocity, ...")
        .def("add_soft_body", &PyWorld::add_soft_body, py::arg("name"), py::arg("mesh"),
             "add_soft_body(name, mesh, **keys): a soft body of a mesh file or a generated one ('cloud:50').")
        .def("add_rigid_body", &PyWorld::add_rigid_body, py::arg("name"), py::arg("shape") = "box",
             "add_rigid_body(name, shape='box', **keys): size=(1, 1, 1), radius=, mass=, position=, ...")
        .def("add_spring", &PyWorld::add_spring, py::arg("a"), py::arg("b"), py::arg("stiffness"), py::arg("damping") = 0.0,
             py::arg("rest_length") = py::none(), py::arg("name") = "",
             "A spring between two ends, each {'body': NAME, 'point': (x, y, z)}, {'body': NAME, 'vertex': K} or a point (x, y, z).")
        .def("destroy", &PyWorld::destroy, py::arg("name"), "Unmakes the body or spring of that name (a body's springs go with it).")
        .def("snapshot", &PyWorld::snapshot)
        .def("restore", &PyWorld::restore, py::arg("snapshot"))
        .def("series", &PyWorld::series,
             "The time series (softbody simulate --series): a dict of numpy arrays, one a column, a row every series_every ticks.")
        .def("series_units", &PyWorld::series_units, "Each series column's unit.")
        .def("restart_series", &PyWorld::restart_series, "Empties the series and follows what the world holds now.")
        .def("render", &PyWorld::render, py::arg("path") = py::none(), py::arg("size") = py::make_tuple(800, 600),
             "Draws the world as softbody render does (OSMesa); writes a PNG when path is given. Returns the\n"
             "picture, a uint8 array (height, width, 4).");

    m.def("key_table", []() { return py::module_::import("json").attr("loads")(keys_json()); },
          "Every key of every kind of thing, as `softbody keys --json` prints them.");
}
