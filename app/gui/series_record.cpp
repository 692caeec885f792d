#include "gui/series_record.h"

#include <algorithm>
#include <sstream>

#include "physics/file_output.h"

namespace softbody::app {

std::size_t SeriesRecord::things(const World& world) {
    return world.soft_body_count() + world.rigid_body_count() + world.spring_count();
}

void SeriesRecord::start(World& world) {
    series_.emplace(world);
    things_ = things(world);
    ledger_ = EnergyLedger{};
    ledger_.observe(world);
    series_->record(world, ledger_);
}

void SeriesRecord::after_tick(World& world) {
    if (!series_ || things(world) != things_) {
        start(world);
        return;
    }
    ledger_.observe(world);
    series_->record(world, ledger_);
    if (series_->size() * series_->columns().size() > kMaxValues) series_->drop_first(series_->size() / 2);
}

void SeriesRecord::cut_after(World& world) {
    if (!series_) return;
    // The rows up to the world's tick stay; the last of them is where the ledger goes on from.
    std::size_t keep = series_->size();
    while (keep > 0 && series_->tick(keep - 1) > world.ticks()) --keep;
    if (keep == 0 || series_->tick(keep - 1) != world.ticks()) {
        start(world);  // before the record's first row: a record from here
        return;
    }
    series_->keep_first(keep);
    ledger_.resume(world, series_->column(Series::kDissipated)[keep - 1]);
}

std::string SeriesRecord::csv() const {
    std::ostringstream text;
    if (series_) series_->write_csv(text);
    return text.str();
}

void SeriesRecord::write_csv(const std::string& path, bool overwrite) const {
    write_text_file(path, csv(), overwrite ? Overwrite::Yes : Overwrite::No);
}

}  // namespace softbody::app
