// Handles to what a world holds: a slot and the generation of what lives in it. A thing's slot
// never changes while it lives, however many others come and go; when it is destroyed its slot
// is reused with the next generation, so an id kept from before names nothing (and the world
// says so) instead of naming whatever took its place.
#pragma once

#include <cstdint>
#include <vector>

namespace softbody {

template <class Tag>
struct Id {
    static constexpr std::uint32_t kNone = 0xFFFFFFFFu;
    std::uint32_t slot = kNone;
    std::uint32_t generation = 0;
    bool valid() const { return slot != kNone; }
    bool operator==(const Id&) const = default;
};

using SoftBodyId = Id<struct SoftBodyTag>;
using RigidBodyId = Id<struct RigidBodyTag>;
using SpringId = Id<struct SpringTag>;

// The ids of one kind of thing in a world, beside the order it keeps them in (its index: 0 to
// count - 1, the order they are stepped and hashed in). Adding appends; removing closes the gap,
// so the others keep their order.
template <class Tag>
class IdTable {
public:
    using IdType = Id<Tag>;

    IdType add() {
        IdType id;
        if (!free_.empty()) {
            id.slot = free_.back();
            free_.pop_back();
        } else {
            id.slot = std::uint32_t(generation_.size());
            generation_.push_back(0);
            index_of_slot_.push_back(IdType::kNone);
        }
        id.generation = generation_[id.slot];
        index_of_slot_[id.slot] = std::uint32_t(ids_.size());
        ids_.push_back(id);
        return id;
    }

    // The index of a living id, or kNone for one that names nothing (never made, or destroyed).
    std::uint32_t index(IdType id) const {
        if (id.slot >= generation_.size() || generation_[id.slot] != id.generation) return IdType::kNone;
        return index_of_slot_[id.slot];
    }
    bool contains(IdType id) const { return index(id) != IdType::kNone; }

    // Removes a living id; the ones after it move down by one index.
    void remove(IdType id) {
        const std::uint32_t at = index(id);
        if (at == IdType::kNone) return;
        ids_.erase(ids_.begin() + at);
        for (std::uint32_t i = at; i < ids_.size(); ++i) index_of_slot_[ids_[i].slot] = i;
        index_of_slot_[id.slot] = IdType::kNone;
        ++generation_[id.slot];
        free_.push_back(id.slot);
    }

    IdType at(std::size_t index) const { return ids_[index]; }
    std::size_t size() const { return ids_.size(); }
    const std::vector<IdType>& ids() const { return ids_; }

    bool operator==(const IdTable&) const = default;

private:
    std::vector<IdType> ids_;                  // by index
    std::vector<std::uint32_t> index_of_slot_; // kNone for a free slot
    std::vector<std::uint32_t> generation_;    // by slot: the generation living there (or next)
    std::vector<std::uint32_t> free_;          // slots to reuse, last freed first
};

}  // namespace softbody
