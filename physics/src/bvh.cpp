#include "bvh.h"

#include <algorithm>

namespace softbody {

void Box3f::grow(const Box3f& o) {
    lo = {std::min(lo.x, o.lo.x), std::min(lo.y, o.lo.y), std::min(lo.z, o.lo.z)};
    hi = {std::max(hi.x, o.hi.x), std::max(hi.y, o.hi.y), std::max(hi.z, o.hi.z)};
}

void Bvh::build(std::span<const Box3f> boxes) {
    nodes_.clear();
    items_.resize(boxes.size());
    for (std::uint32_t i = 0; i < items_.size(); ++i) items_[i] = i;
    leaf_boxes_.assign(boxes.size(), {});
    if (boxes.empty()) return;
    nodes_.reserve(2 * boxes.size() / kLeafSize + 2);
    nodes_.emplace_back();
    split(boxes, 0, 0, std::uint32_t(boxes.size()), 0);
    refit(boxes);
}

// Makes node `at` over items_[begin, end): a leaf, or two children allocated side by side
// (left, left + 1) after every node made so far, each then split in turn.
void Bvh::split(std::span<const Box3f> boxes, std::uint32_t at, std::uint32_t begin, std::uint32_t end, int depth) {
    // A leaf when small enough, or deep enough that the query's stack (64) could not hold more.
    if (end - begin <= kLeafSize || depth >= 30) {
        nodes_[at].first = begin;
        nodes_[at].count = end - begin;
        return;
    }
    const Vec3 c0 = (boxes[items_[begin]].lo + boxes[items_[begin]].hi) * 0.5f;
    Box3f centres{c0, c0};
    for (std::uint32_t k = begin; k < end; ++k) {
        const Box3f& b = boxes[items_[k]];
        const Vec3 c = (b.lo + b.hi) * 0.5f;
        centres.grow({c, c});
    }
    const Vec3 side = centres.hi - centres.lo;
    const int axis = side.x >= side.y && side.x >= side.z ? 0 : side.y >= side.z ? 1 : 2;
    const auto key = [&](std::uint32_t item) {
        const Box3f& b = boxes[item];
        return axis == 0 ? b.lo.x + b.hi.x : axis == 1 ? b.lo.y + b.hi.y : b.lo.z + b.hi.z;
    };
    const std::uint32_t middle = begin + (end - begin) / 2;
    // Ties broken by item number: the same boxes make the same tree on every machine.
    std::nth_element(items_.begin() + begin, items_.begin() + middle, items_.begin() + end,
                     [&](std::uint32_t a, std::uint32_t b) { return key(a) < key(b) || (key(a) == key(b) && a < b); });
    const std::uint32_t left = std::uint32_t(nodes_.size());
    nodes_[at].first = left;
    nodes_[at].count = 0;
    nodes_.emplace_back();
    nodes_.emplace_back();
    split(boxes, left, begin, middle, depth + 1);
    split(boxes, left + 1, middle, end, depth + 1);
}

void Bvh::refit(std::span<const Box3f> boxes) {
    for (std::uint32_t k = 0; k < items_.size(); ++k) leaf_boxes_[k] = boxes[items_[k]];
    for (std::size_t i = nodes_.size(); i-- > 0;) {
        Node& node = nodes_[i];
        if (node.count > 0) {
            node.box = leaf_boxes_[node.first];
            for (std::uint32_t k = node.first + 1; k < node.first + node.count; ++k) node.box.grow(leaf_boxes_[k]);
        } else {
            node.box = nodes_[node.first].box;
            node.box.grow(nodes_[node.first + 1].box);
        }
    }
}

}  // namespace softbody
