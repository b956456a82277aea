// k_nearest.h — the candidate list of the k-nearest-neighbour queries (point_set.h: kNearest),
// shared by every structure: a fixed-size binary max-heap of (squared distance, index), so that
// a query needs no allocation and the result is the same set whatever order the candidates
// arrive in (a structure only decides which points it offers, never which ones win).
#pragma once

#include <cstdint>

#include "caustica/util/math.h"
#include "caustica/util/unfused.h"

namespace caustica {

/// The most neighbours one kNearest query returns (a larger k is clamped to it): the heap lives
/// in the query's registers or local memory, 8 bytes per entry (512 bytes).
inline constexpr uint32_t kMaxNeighbors = 64;

/// A candidate of a kNearest query: point `index` at squared distance `distanceSquared`.
struct Neighbor {
    Float distanceSquared = 0;
    uint32_t index = 0;
};

/// The order of kNearest's results: squared distance ascending, ties by index ascending. Indices
/// are distinct, so this is a strict total order on candidates: "the k first" is one set.
CA_HD_INLINE bool nearerThan(Neighbor a, Neighbor b) {
    return a.distanceSquared < b.distanceSquared ||
           (a.distanceSquared == b.distanceSquared && a.index < b.index);
}

/// The min(k, kMaxNeighbors) first candidates by nearerThan among those offered that pass
/// inBall(position, center, maxRadius). A max-heap: heap_[0] is the worst one kept.
class NearestHeap {
public:
    CA_HD NearestHeap(uint32_t k, Float maxRadius)
        : capacity_(k < kMaxNeighbors ? k : kMaxNeighbors),
          maxRadius_(maxRadius),
          maxDistanceSquared_(mulUnfused(maxRadius, maxRadius)) {}

    /// How many neighbours the query keeps (0: nothing to search).
    CA_HD uint32_t capacity() const { return capacity_; }
    CA_HD bool full() const { return size_ == capacity_; }
    /// The query's maxRadius.
    CA_HD Float maxRadius() const { return maxRadius_; }
    /// maxRadius^2 as inBall computes it: no point farther than this (in float) is kept.
    CA_HD Float maxDistanceSquared() const { return maxDistanceSquared_; }
    /// A point at computed squared distance > limit() cannot enter: maxRadius^2 until the heap
    /// is full, then the k-th candidate's (a point at exactly that distance still may, by index).
    CA_HD Float limit() const {
        return size_ == capacity_ && size_ > 0 ? heap_[0].distanceSquared : maxDistanceSquared_;
    }

    /// Offers point i at position p: kept when |p - center|^2 <= maxRadius^2 (inBall's test, the
    /// same float operations) and it is among the best k so far.
    CA_HD void consider(uint32_t i, Vec3f p, Vec3f center) {
        const Float d2 = distanceSquaredUnfused(p, center);
        if (!(d2 <= maxDistanceSquared_)) return;
        const Neighbor c{d2, i};
        if (size_ < capacity_) {
            heap_[size_] = c;
            siftUp(size_++);
        } else if (capacity_ > 0 && nearerThan(c, heap_[0])) {
            heap_[0] = c;
            siftDown(0, size_);
        }
    }

    /// Forgets every candidate (a structure that restarts with brute force).
    CA_HD void clear() { size_ = 0; }

    /// Writes the kept candidates ascending by nearerThan: indices[0, count) and, when not null,
    /// distancesSquared[0, count). Heap sort in place: the heap is empty afterwards.
    CA_HD void finish(uint32_t* indices, uint32_t& count, Float* distancesSquared) {
        count = size_;
        for (uint32_t end = size_; end > 1; --end) {
            const Neighbor top = heap_[0];
            heap_[0] = heap_[end - 1];
            heap_[end - 1] = top;
            siftDown(0, end - 1);
        }
        for (uint32_t j = 0; j < count; ++j) {
            indices[j] = heap_[j].index;
            if (distancesSquared) distancesSquared[j] = heap_[j].distanceSquared;
        }
        size_ = 0;
    }

private:
    CA_HD void siftUp(uint32_t j) {
        while (j > 0) {
            const uint32_t parent = (j - 1) / 2;
            if (!nearerThan(heap_[parent], heap_[j])) return;
            swap(parent, j);
            j = parent;
        }
    }
    CA_HD void siftDown(uint32_t j, uint32_t size) {
        for (;;) {
            const uint32_t l = 2 * j + 1, r = l + 1;
            uint32_t worst = j;
            if (l < size && nearerThan(heap_[worst], heap_[l])) worst = l;
            if (r < size && nearerThan(heap_[worst], heap_[r])) worst = r;
            if (worst == j) return;
            swap(worst, j);
            j = worst;
        }
    }
    CA_HD void swap(uint32_t a, uint32_t b) {
        const Neighbor t = heap_[a];
        heap_[a] = heap_[b];
        heap_[b] = t;
    }

    Neighbor heap_[kMaxNeighbors];
    uint32_t size_ = 0;
    uint32_t capacity_ = 0;
    Float maxRadius_ = 0;
    Float maxDistanceSquared_ = 0;
};

/// An entry of a tree's k-nearest walk: a node and a lower bound of the squared distances of
/// the points below it.
struct NearestEntry {
    uint32_t node = 0;
    Float bound = 0;
};

/// The bounded depth-first walk of the trees' k-nearest searches (kd_tree.h, multi_hash.h), from
/// node 0: expand(entry, push) offers the node's points to the heap and push(child entry)es
/// its children, the nearer last. An entry whose bound exceeds the heap's limit is dropped when
/// pushed and when popped; a bound equal to the limit is searched (a tie may still win by
/// index). A NaN bound is never pruned. The stack holds kStackSize entries: at most one pending
/// sibling per level plus the top node.
template <int kStackSize, class Expand>
CA_HD void walkNearest(NearestHeap& heap, Expand&& expand) {
    NearestEntry stack[kStackSize];
    int top = 0;
    stack[top++] = NearestEntry{0, 0};
    auto push = [&](NearestEntry e) {
        if (!(e.bound > heap.limit())) stack[top++] = e;
    };
    while (top > 0) {
        const NearestEntry e = stack[--top];
        if (e.bound > heap.limit()) continue;
        expand(e, push);
    }
}

}  // namespace caustica
