// The run's time series as the app keeps it (physics/series.h): a row for the main world's start
// and one after every tick, with the energy the world has let go of (energy_ledger.h). What the
// Graph tool draws and what its Export CSV writes: the same columns and the same numbers as
// `softbody simulate --series` gives for the same scene and ticks.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "physics/energy_ledger.h"
#include "physics/series.h"

namespace softbody::app {

class SeriesRecord {
public:
    // At most this many numbers are kept (about 64 MB); past it, the oldest half of the rows go.
    static constexpr std::size_t kMaxValues = std::size_t(8) << 20;

    // A new or reset world: its columns, and its first row.
    void start(World& world);
    // After every tick. A body or a named spring made or unmade starts the record again, with
    // the columns of what the world now holds.
    void after_tick(World& world);
    // The world went back to an earlier tick (time travel): the rows after it go, and the running
    // total of what was dissipated goes on from that tick's.
    void cut_after(World& world);

    const Series* series() const { return series_ ? &*series_ : nullptr; }
    // The rows as CSV (RFC 4180) into `path`; an existing file is replaced only with `overwrite`.
    // Throws InputError with one line saying what went wrong.
    void write_csv(const std::string& path, bool overwrite) const;
    std::string csv() const;  // the same text (the page hands it to the browser as a download)

private:
    static std::size_t things(const World& world);

    std::optional<Series> series_;
    EnergyLedger ledger_;
    std::size_t things_ = 0;  // bodies and springs when the columns were made
};

}  // namespace softbody::app
