#include "physics/series.h"

#include <algorithm>
#include <charconv>
#include <cstddef>
#include <cmath>
#include <limits>

namespace softbody {

namespace {

constexpr double kMissing = std::numeric_limits<double>::quiet_NaN();

std::string shortest_text(double x) {
    if (!std::isfinite(x)) return "";
    char text[32];
    const auto result = std::to_chars(text, text + sizeof text, x);
    return std::string(text, result.ptr);
}

// RFC 4180's quoting: a field with a comma, a quote or a line end is quoted, its quotes doubled.
std::string csv_field(const std::string& field) {
    if (field.find_first_of(",\"\r\n") == std::string::npos) return field;
    std::string out = "\"";
    for (char c : field) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

// A soft body's centre of mass and mean velocity (every particle weighs the same).
void soft_motion(const SoftBody& body, Vec3d& x, Vec3d& v) {
    x = v = Vec3d{};
    const std::size_t n = body.particle_count();
    for (std::size_t i = 0; i < n; ++i) {
        x += Vec3d(body.x[i]);
        v += Vec3d(body.v[i]);
    }
    x = x / double(n);
    v = v / double(n);
}

}  // namespace

std::string tick_time_text(std::uint64_t ticks, float dt) {
    char text[32];
    const auto result = std::to_chars(text, text + sizeof text, dt);
    const std::string dt_text(text, result.ptr);
    // A decimal number of the form D.DDD (no exponent): ticks x its digits, the point put back.
    const auto point = dt_text.find('.');
    const std::string digits = point == std::string::npos ? dt_text : dt_text.substr(0, point) + dt_text.substr(point + 1);
    const std::size_t decimals = point == std::string::npos ? 0 : dt_text.size() - point - 1;
    // Exact while the product fits 64 bits (ticks up to 2^32 of a dt of at most nine digits).
    if (dt_text.find('e') != std::string::npos || ticks > (std::uint64_t(1) << 32) || digits.size() > 9) {
        return shortest_text(double(ticks) * double(dt));
    }
    std::uint64_t product = ticks * std::stoull(digits);
    std::string whole;
    do {
        whole.insert(whole.begin(), char('0' + int(product % 10)));
        product /= 10;
    } while (product > 0);
    if (whole.size() <= decimals) whole.insert(0, decimals + 1 - whole.size(), '0');
    std::string out = whole.substr(0, whole.size() - decimals);
    std::string fraction = whole.substr(whole.size() - decimals);
    while (!fraction.empty() && fraction.back() == '0') fraction.pop_back();
    return fraction.empty() ? out : out + "." + fraction;
}

Series::Series(const World& world) {
    columns_ = {{"time", "s"}, {"kinetic", "J"}, {"gravitational", "J"}, {"elastic", "J"}, {"dissipated", "J"}, {"total", "J"}};
    const auto follow = [&](Followed::Kind kind, const std::string& name) {
        followed_.push_back({kind, name});
        if (kind == Followed::Kind::Spring) {
            columns_.push_back({name + " length", "m"});
            columns_.push_back({name + " force", "N"});
            return;
        }
        for (const char* axis : {"x", "y", "z"}) columns_.push_back({name + " " + axis, "m"});
        for (const char* axis : {"vx", "vy", "vz"}) columns_.push_back({name + " " + axis, "m/s"});
    };
    std::size_t bodies = 0;
    for (std::size_t b = 0; b < world.soft_body_count() && bodies < kSeriesBodies; ++b, ++bodies) {
        follow(Followed::Kind::Soft, world.soft_body(b).name());
    }
    for (std::size_t b = 0; b < world.rigid_body_count() && bodies < kSeriesBodies; ++b) {
        if (world.rigid_body(b).fixed) continue;
        follow(Followed::Kind::Rigid, world.rigid_body(b).name);
        ++bodies;
    }
    for (std::size_t s = 0; s < world.spring_count(); ++s) {
        const SpringDef& def = world.def(world.spring_id(s));
        if (!def.name.empty()) follow(Followed::Kind::Spring, def.name);
    }
    data_.assign(columns_.size(), {});
}

void Series::clear() {
    for (auto& column : data_) column.clear();
    ticks_.clear();
    dts_.clear();
}

void Series::keep_first(std::size_t rows) {
    if (rows >= size()) return;
    for (auto& column : data_) column.resize(rows);
    ticks_.resize(rows);
    dts_.resize(rows);
}

void Series::drop_first(std::size_t rows) {
    rows = std::min(rows, size());
    for (auto& column : data_) column.erase(column.begin(), column.begin() + std::ptrdiff_t(rows));
    ticks_.erase(ticks_.begin(), ticks_.begin() + std::ptrdiff_t(rows));
    dts_.erase(dts_.begin(), dts_.begin() + std::ptrdiff_t(rows));
}

void Series::record(const World& world, const EnergyLedger& ledger) {
    std::vector<double> row;
    row.reserve(columns_.size());
    const Energy& e = ledger.energy();
    row.insert(row.end(), {world.time(), e.kinetic, e.gravity, e.elastic, ledger.dissipated(), ledger.total()});
    for (const Followed& f : followed_) {
        if (f.kind == Followed::Kind::Spring) {
            const auto id = world.find_spring(f.name);
            if (!id) {
                row.insert(row.end(), {kMissing, kMissing});
                continue;
            }
            const Link& link = world.links()[world.index(*id)];
            const double l = length(world.link_end_position(link.b) - world.link_end_position(link.a));
            row.insert(row.end(), {l, link.k * (l - link.l0)});  // Eq. 21's tension
            continue;
        }
        Vec3d x, v;
        bool found = false;
        if (f.kind == Followed::Kind::Soft) {
            if (const auto id = world.find_soft_body(f.name)) {
                soft_motion(world.soft_body(world.index(*id)), x, v);
                found = true;
            }
        } else if (const auto id = world.find_rigid_body(f.name)) {
            const RigidMotion m = world.rigid_motion(world.index(*id));
            x = m.x;
            v = m.v;
            found = true;
        }
        if (found) row.insert(row.end(), {x.x, x.y, x.z, v.x, v.y, v.z});
        else row.insert(row.end(), 6, kMissing);
    }
    for (std::size_t k = 0; k < row.size(); ++k) data_[k].push_back(row[k]);
    ticks_.push_back(world.ticks());
    dts_.push_back(world.settings().dt);
}

std::string Series::csv_header() const {
    std::string out;
    for (std::size_t k = 0; k < columns_.size(); ++k) out += (k ? "," : "") + csv_field(columns_[k].header());
    return out + "\r\n";
}

std::string Series::csv_row(std::size_t row) const {
    std::string out = tick_time_text(ticks_[row], dts_[row]);
    for (std::size_t k = 1; k < columns_.size(); ++k) out += "," + shortest_text(data_[k][row]);
    return out + "\r\n";
}

void Series::write_csv(std::ostream& out) const {
    out << csv_header();
    for (std::size_t row = 0; row < size(); ++row) out << csv_row(row);
}

}  // namespace softbody
