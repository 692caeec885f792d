// The time series of a run, one row a tick: the time, the energies (kinetic, gravitational,
// elastic, dissipated, total: energy_ledger.h), each moving body's centre and velocity, and
// each named spring's length and force (Eq. 21). What `softbody simulate --series` writes as
// CSV, what the app's graphs and its Export CSV show, and what the Python module hands to numpy.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "physics/energy_ledger.h"
#include "physics/world.h"

namespace softbody {

struct SeriesColumn {
    std::string name;  // "time", "kinetic", "jelly x", "spring force"
    std::string unit;  // "s", "J", "m", "m/s", "N"
    std::string header() const { return unit.empty() ? name : name + " (" + unit + ")"; }
};

// The most bodies a series follows: the first this many that move, in the world's order.
inline constexpr std::size_t kSeriesBodies = 64;

class Series {
public:
    // Columns for what the world holds now (bodies and springs by name); a thing made later is
    // not followed, one unmade leaves its columns empty (NaN).
    explicit Series(const World& world);

    // One row: the world as it is, its energies as the ledger last observed them.
    void record(const World& world, const EnergyLedger& ledger);
    void clear();

    const std::vector<SeriesColumn>& columns() const { return columns_; }
    std::size_t size() const { return ticks_.size(); }
    // Column k's values, one per row (column 0 is the time, s).
    const std::vector<double>& column(std::size_t k) const { return data_[k]; }
    std::uint64_t tick(std::size_t row) const { return ticks_[row]; }

    // RFC 4180: a header row of names with units, then the rows, comma separated, CRLF line
    // ends, fields quoted where they hold a comma, a quote or a line end. The time is written as
    // the decimal it is (tick x dt, 0.02 not 0.0199999996); other numbers in the fewest digits
    // that read back to the same double; a missing value (a body unmade) as an empty field.
    void write_csv(std::ostream& out) const;
    std::string csv_header() const;
    std::string csv_row(std::size_t row) const;

private:
    struct Followed {
        enum class Kind { Soft, Rigid, Spring } kind;
        std::string name;
    };
    std::vector<SeriesColumn> columns_;
    std::vector<Followed> followed_;
    std::vector<std::vector<double>> data_;  // by column
    std::vector<std::uint64_t> ticks_;
    std::vector<float> dts_;  // each row's dt (its time's decimal is its tick times it)
};

// The time of a tick as the decimal it is: ticks times dt's shortest decimal text ("0.02"), so
// tick 5 is "0.1", not float's 0.100000001.
std::string tick_time_text(std::uint64_t ticks, float dt);

}  // namespace softbody
