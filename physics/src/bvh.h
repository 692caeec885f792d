// Internal to the physics library: a bounding-volume tree over a fixed set of items (a soft
// body's triangles, or a point cloud's particles), built once from where they are and refit
// every tick to where they went: the topology never changes, only the boxes. A soft body bends
// but its neighbours stay its neighbours, so a tree split by where things were at the start
// stays a good tree (its boxes only loosen a little as the body deforms), and refitting costs
// one pass over the nodes, against the rebuild a hash grid needs every tick.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "physics/vec3.h"

namespace softbody {

struct Box3f {
    Vec3 lo, hi;
    bool overlaps(const Box3f& o) const {
        return lo.x <= o.hi.x && o.lo.x <= hi.x && lo.y <= o.hi.y && o.lo.y <= hi.y && lo.z <= o.hi.z && o.lo.z <= hi.z;
    }
    void grow(const Box3f& o);
};

class Bvh {
public:
    // The tree over boxes[0..n): each node split at the median of its items' centres along its
    // longest side, down to kLeafSize items a leaf. The same boxes give the same tree.
    void build(std::span<const Box3f> boxes);
    // The same items in new boxes (as many as built with).
    void refit(std::span<const Box3f> boxes);
    bool empty() const { return nodes_.empty(); }
    const Box3f& bounds() const { return nodes_.front().box; }

    // Calls visit(item) for every item whose box overlaps `box`, in a fixed order (the tree's).
    template <class Visit>
    void query(const Box3f& box, Visit&& visit) const {
        if (nodes_.empty()) return;
        std::uint32_t stack[64];
        int top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const Node& node = nodes_[stack[--top]];
            if (!node.box.overlaps(box)) continue;
            if (node.count > 0) {
                for (std::uint32_t k = node.first; k < node.first + node.count; ++k) {
                    if (leaf_boxes_[k].overlaps(box)) visit(items_[k]);
                }
                continue;
            }
            stack[top++] = node.first + 1;  // right child
            stack[top++] = node.first;      // left child, visited first
        }
    }

    static constexpr std::uint32_t kLeafSize = 4;

private:
    struct Node {
        Box3f box;
        std::uint32_t first = 0;  // leaf: its first item in items_; inner: its left child (the right one follows)
        std::uint32_t count = 0;  // items in a leaf; 0 for an inner node
    };
    void split(std::span<const Box3f> boxes, std::uint32_t at, std::uint32_t begin, std::uint32_t end, int depth);

    std::vector<Node> nodes_;        // children always after their parent (refit runs backwards)
    std::vector<std::uint32_t> items_;  // item numbers, leaf by leaf
    std::vector<Box3f> leaf_boxes_;   // the box of items_[k], beside it
};

}  // namespace softbody
