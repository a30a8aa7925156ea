// The SAH builder of sah_builder.h as a template over a policy, so that a caller can compose a
// variant without the renderer's build paying for it. The renderer's policy (sah_builder_impl.cpp)
// splits nodes between primitive centres alone; a policy that SplitsByPlanes may also cut a node
// by an axis plane (the benchmarks' spatial splits, bench/spatial_splits.h). Only such a
// policy's builder compiles the code for planes and their free slots.
#pragma once

#include <immintrin.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <concepts>
#include <cstring>
#include <limits>
#include <numeric>
#include <span>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

#include "accel/sah_builder.h"

namespace glint {

// An axis plane: the axis and the coordinate there.
struct SplitPlane {
    int axis = -1;
    double position = 0;
};

// Every policy gives kTraversalCost: one step down, relative to one primitive test, in the trees
// it builds. A policy that splits by planes also cuts a node by an axis plane through the
// references it crosses, each cut one becoming a reference on both sides with the box of its
// part there; the tree's order may then name a primitive several times. The builder leaves
// free slots for the references this adds (at most budget() more per primitive), asks for a
// plane only where the children of the best split by centres overlap by more than
// overlap_share() of the root's half area, and takes the plane where it costs less.
// best_plane(boxes, prims, node, plane): the cheapest plane through a node of box `node`
// holding the references `boxes` (of the primitives `prims`), and its unnormalised SAH cost
// (infinite if there is none). part(prim, box): a box around the part of primitive `prim`
// inside `box` (empty if none).
template <typename P>
concept SplitsByPlanes = requires(const P& policy, std::span<const Bounds3> boxes, std::span<const uint32_t> prims,
                                  const Bounds3& box, SplitPlane& plane, uint32_t prim) {
    { policy.budget() } -> std::convertible_to<double>;
    { policy.overlap_share() } -> std::convertible_to<float>;
    { policy.best_plane(boxes, prims, box, plane) } -> std::convertible_to<float>;
    { policy.part(prim, box) } -> std::convertible_to<Bounds3>;
};

// The builder's parts, for SahBuilder alone.
namespace sah {

// Bins: 32 for nodes of kManyPrimitives or more, where the split decides the most rays, so a
// finer choice of plane pays for the longer sweep; at most 16 below, and one bin per primitive
// for nodes of fewer, as more bins could not tell more splits apart and sweeping them would
// dominate the build.
constexpr int kBins = 32;
constexpr int kFewBins = 16;
constexpr uint32_t kManyPrimitives = 1024;
// Primitives binned per block (see best_sah_split).
constexpr uint32_t kBinningBlock = 32;
// Below this depth SAH decides; deeper, splits fall back to the median so the tree's depth
// (and so the traversal stack) stays bounded whatever the input.
constexpr int kSahDepth = 64;
// A parallel build (SahBuildConfig) leaves subtrees of at most a kSubtreeShare-th of the
// primitives to the threads. The top, built by one thread first, bins every primitive at each of
// its levels: a share of 8 leaves it three or four levels, and a dozen or more subtrees to share
// out between a few cores.
constexpr uint32_t kSubtreeShare = 8;

// A box in one SSE register per corner (x, y, z, unused): growing it is two instructions, which
// is what binning does most. Float boxes rounded outward lose nothing the tree needs.
struct SseBox {
    __m128 lo = _mm_set1_ps(std::numeric_limits<float>::infinity());
    __m128 hi = _mm_set1_ps(-std::numeric_limits<float>::infinity());

    void extend(const SseBox& b) {
        lo = _mm_min_ps(lo, b.lo);
        hi = _mm_max_ps(hi, b.hi);
    }
    void extend(__m128 p) {
        lo = _mm_min_ps(lo, p);
        hi = _mm_max_ps(hi, p);
    }
    // lo + hi: the centre, doubled, which orders and bins primitives as the centre does (halving
    // is exact) for one instruction less.
    __m128 twice_centre() const { return _mm_add_ps(lo, hi); }
    float half_area() const {
        // x·y + y·z + z·x in the register: the extent times its rotation, then the lanes summed.
        const __m128 e = _mm_sub_ps(hi, lo);
        const __m128 products = _mm_mul_ps(e, _mm_shuffle_ps(e, e, _MM_SHUFFLE(3, 0, 2, 1)));
        const __m128 sum = _mm_add_ss(_mm_add_ss(products, _mm_shuffle_ps(products, products, 1)), _mm_movehl_ps(products, products));
        return _mm_cvtss_f32(e) < 0 ? 0 : _mm_cvtss_f32(sum);
    }
    FloatBox to_float_box() const {
        alignas(16) float l[4], h[4];
        _mm_store_ps(l, lo);
        _mm_store_ps(h, hi);
        return {{l[0], l[1], l[2]}, {h[0], h[1], h[2]}};
    }
    Bounds3 to_bounds() const {
        const FloatBox f = to_float_box();
        return {{f.lo[0], f.lo[1], f.lo[2]}, {f.hi[0], f.hi[1], f.hi[2]}};
    }
    // The float box around a double one.
    static SseBox enclosing(const Bounds3& b) {
        const FloatBox f = FloatBox::enclosing(b);
        return {_mm_setr_ps(f.lo[0], f.lo[1], f.lo[2], 0), _mm_setr_ps(f.hi[0], f.hi[1], f.hi[2], 0)};
    }
};

// A bin's box, left uninitialised until the node's binning sets it up.
union LazyBox {
    SseBox box;
    LazyBox() {}
};

// A primitive's box and its bin along each axis in the node being split, which the binning
// pass leaves for the partition (the fourth byte is unused; the four are stored as one word).
// 48 bytes: the centre is recomputed rather than stored, as the build streams these through the
// cache once per level.
struct BuildPrim {
    SseBox box;
    uint32_t index;
    std::array<uint8_t, 4> bin;
    __m128 twice_centre() const { return box.twice_centre(); }
};
static_assert(sizeof(BuildPrim) == 48);

// Maps doubled centres to bins along all three axes at once.
class Binning {
public:
    Binning(const SseBox& twice_centres, uint32_t count)
        : lo_(twice_centres.lo), count_(count >= kManyPrimitives ? kBins : std::min(kFewBins, int(count))) {
        alignas(16) float extent[4], scale[4] = {};
        _mm_store_ps(extent, _mm_sub_ps(twice_centres.hi, twice_centres.lo));
        for (int a = 0; a < 3; ++a) {
            splittable_[a] = extent[a] > 0;
            scale[a] = splittable_[a] ? float(count_) / extent[a] : 0;
        }
        scale_ = _mm_load_ps(scale);
    }
    int count() const { return count_; }
    bool splittable(int axis) const { return splittable_[axis]; }
    // The bin along each axis in lanes 0..2, clamped at both ends: a box reaching infinity has
    // an infinite or NaN centre (which the minima and maxima of the centre box may pass over),
    // and its product converts to INT_MIN; such a primitive lands in an end bin.
    __m128i bins(const SseBox& box) const {
        const __m128i bin = _mm_cvttps_epi32(_mm_mul_ps(_mm_sub_ps(box.twice_centre(), lo_), scale_));
        return _mm_max_epi32(_mm_min_epi32(bin, _mm_set1_epi32(count_ - 1)), _mm_setzero_si128());
    }

private:
    __m128 lo_, scale_;
    int count_;
    bool splittable_[3];
};

struct Split {
    int axis = -1;
    int bin = 0;  // the first bin on the right
    float cost = std::numeric_limits<float>::infinity();
};

}  // namespace sah

// Builds over prims_[0, n). A node owns a range of prims_ and the free slots after it up to its
// capacity's end, which splits by a plane fill with the references they add; each split shares
// the free slots out between the children in proportion to their sizes (a policy that does not
// split by planes leaves none, and its builder has no code for them).
//
// A parallel build leaves the subtrees of at most a kSubtreeShare-th of the primitives as tasks;
// threads then build each into a node array of its own, over its own range of prims_, and the
// arrays are appended in the order of the tasks. The tree is the one a single thread builds (each
// node's split depends on its primitives alone), only numbered otherwise, and collapse_to_wide()
// numbers the wide tree from the structure alone.
template <typename Policy>
class SahBuilder {
    static constexpr bool kPlanes = SplitsByPlanes<Policy>;
    static constexpr float kTraversalCost = Policy::kTraversalCost;
    // build() makes a node of no more primitives than the step cost a leaf before any other check.
    static_assert(kTraversalCost < BinaryTree::kMaxLeafSize + 1, "a leaf made for its step cost must fit kMaxLeafSize");
    using SseBox = sah::SseBox;
    using BuildPrim = sah::BuildPrim;
    using Binning = sah::Binning;
    using Split = sah::Split;
    using LazyBox = sah::LazyBox;

public:
    SahBuilder(std::vector<BuildPrim>& prims, const Policy& policy, std::vector<BinaryNode>& nodes)
        : prims_(prims), policy_(policy), nodes_(&nodes) {}

    // Splits by planes are built on one thread: their free slots are shared out as they go.
    BinaryTree run(const SahBuildConfig& config) {
        const auto n = static_cast<uint32_t>(prims_.size());
        uint32_t capacity = n;
        if constexpr (kPlanes)
            capacity += static_cast<uint32_t>(policy_.budget() * n);
        else if (n >= config.parallel_from)
            largest_task_ = n / sah::kSubtreeShare;
        nodes_->reserve(2 * capacity);
        nodes_->push_back({});
        prims_.resize(capacity);
        const Extent root = extent_of(0, n);
        if constexpr (kPlanes) planes_.root_area = root.bounds.half_area();
        build(0, {0, n, capacity, root}, 0);
        build_tasks(config.threads ? config.threads : std::max(1u, std::thread::hardware_concurrency()));
        BinaryTree tree;
        tree.order = compact(*nodes_);
        tree.nodes = std::move(*nodes_);
        return tree;
    }

private:
    // The box around some primitives and the box around their doubled centres.
    struct Extent {
        SseBox bounds, centres;
        void add(const BuildPrim& p) {
            bounds.extend(p.box);
            centres.extend(p.twice_centre());
        }
        void extend(const Extent& e) {
            bounds.extend(e.bounds);
            centres.extend(e.centres);
        }
    };

    // The extent of prims_[begin, end), in two chains, for even and odd positions: one chain of
    // minima and maxima would make each primitive wait for the previous one's.
    Extent extent_of(uint32_t begin, uint32_t end) const {
        std::array<Extent, 2> chains;
        uint32_t i = begin;
        for (; i + 1 < end; i += 2) {
            chains[0].add(prims_[i]);
            chains[1].add(prims_[i + 1]);
        }
        if (i < end) chains[0].add(prims_[i]);
        chains[0].extend(chains[1]);
        return chains[0];
    }

    // The references of the leaves, in order, without the free slots left between them.
    std::vector<uint32_t> compact(std::vector<BinaryNode>& nodes) const {
        std::vector<BinaryNode*> leaves;
        for (BinaryNode& node : nodes)
            if (node.is_leaf()) leaves.push_back(&node);
        std::sort(leaves.begin(), leaves.end(), [](const BinaryNode* a, const BinaryNode* b) { return a->first < b->first; });
        std::vector<uint32_t> order;
        order.reserve(prims_.size());
        for (BinaryNode* leaf : leaves) {
            const uint32_t first = leaf->first;
            leaf->first = static_cast<uint32_t>(order.size());
            for (uint32_t i = first; i < first + leaf->count; ++i) order.push_back(prims_[i].index);
        }
        return order;
    }

    // A node to build: its range of prims_, the free slots after it up to capacity_end, and the
    // extent of its primitives, which its parent found on the way.
    struct Child {
        uint32_t begin, end, capacity_end;
        Extent extent;
    };
    // A subtree left for the workers: the node it fills and what to build there.
    struct Task {
        uint32_t node;
        Child child;
        int depth;
    };

    // Builds the tasks on `threads` threads, largest first, then appends their nodes to the tree.
    void build_tasks(unsigned threads) {
        if (tasks_.empty()) return;
        std::vector<std::vector<BinaryNode>> subtrees(tasks_.size());
        std::vector<uint32_t> by_size(tasks_.size());
        std::iota(by_size.begin(), by_size.end(), 0u);
        std::stable_sort(by_size.begin(), by_size.end(), [&](uint32_t a, uint32_t b) { return size_of(a) > size_of(b); });
        std::atomic<size_t> next{0};
        const auto work = [&] {
            for (size_t i; (i = next.fetch_add(1)) < by_size.size();) {
                const Task& task = tasks_[by_size[i]];
                std::vector<BinaryNode>& nodes = subtrees[by_size[i]];
                nodes.reserve(2 * size_t{task.child.end - task.child.begin});
                nodes.push_back({});
                SahBuilder(prims_, policy_, nodes).build(0, task.child, task.depth);
            }
        };
        {
            std::vector<std::jthread> workers(std::min<size_t>(tasks_.size(), threads) - 1);
            for (std::jthread& worker : workers) worker = std::jthread(work);
            work();
        }
        for (size_t t = 0; t < tasks_.size(); ++t) append(tasks_[t].node, subtrees[t]);
    }

    uint32_t size_of(uint32_t task) const { return tasks_[task].child.end - tasks_[task].child.begin; }

    // Puts a subtree's root in `node` and its other nodes at the end of the tree, renumbered.
    void append(uint32_t node, const std::vector<BinaryNode>& subtree) {
        const auto base = static_cast<uint32_t>(nodes_->size()) - 1;  // where subtree node 1 goes
        for (size_t i = 0; i < subtree.size(); ++i) {
            BinaryNode copy = subtree[i];
            if (!copy.is_leaf()) copy.first += base;  // children are never the subtree's root
            if (i == 0)
                (*nodes_)[node] = copy;
            else
                nodes_->push_back(copy);
        }
    }

    void build(uint32_t node, const Child& child, int depth) {
        const auto [begin, end, capacity_end, extent] = child;
        const uint32_t count = end - begin;
        if (count <= largest_task_) return tasks_.push_back({node, child, depth});
        (*nodes_)[node].box = extent.bounds.to_float_box();
        const float leaf_cost = float(count);
        // A split costs at least the traversal step: a node of no more primitives than that is a
        // leaf without a look at its bins.
        if (leaf_cost <= kTraversalCost) return make_leaf(node, begin, count);
        const Binning binning(extent.centres, count);
        const Split split = depth < sah::kSahDepth ? best_sah_split(begin, end, binning) : Split{};
        const float split_cost = kTraversalCost + split.cost / extent.bounds.half_area();
        if (count <= BinaryTree::kMaxLeafSize && leaf_cost <= split_cost) return make_leaf(node, begin, count);
        Extent left, right;
        uint32_t mid = split.axis >= 0 ? partition(begin, end, split, left, right) : begin;
        if (mid == begin || mid == end) {
            mid = median_split(begin, end, extent.centres);
            left = extent_of(begin, mid);
            right = extent_of(mid, end);
        }
        if constexpr (kPlanes) {
            if (capacity_end > end && depth < sah::kSahDepth && overlap_enough(left.bounds, right.bounds) &&
                split_by_plane(node, child, depth, split.cost))
                return;
        }
        const uint32_t to_left = share_free_slots(child, mid);
        split_node(node, {begin, mid, mid + to_left, left}, {mid + to_left, end + to_left, capacity_end, right}, depth);
    }

    // The left child's share of the node's free slots, which the right-hand references move up by.
    uint32_t share_free_slots(const Child& child, uint32_t mid) {
        if constexpr (!kPlanes) {
            return 0;
        } else {
            const auto [begin, end, capacity_end, extent] = child;
            const auto to_left = static_cast<uint32_t>((capacity_end - end) * uint64_t{mid - begin} / (end - begin));
            if (to_left > 0) std::move_backward(prims_.begin() + mid, prims_.begin() + end, prims_.begin() + end + to_left);
            return to_left;
        }
    }

    // Moves the primitives left of the split to the front (in std::partition's order), and
    // gathers each side's extent on the way, so that the children need no pass of their own over
    // their primitives. Returns where the right side begins.
    uint32_t partition(uint32_t begin, uint32_t end, const Split& split, Extent& left, Extent& right) {
        const auto on_left = [&](const BuildPrim& p) { return p.bin[split.axis] < split.bin; };
        uint32_t lo = begin, hi = end;
        for (;;) {
            for (; lo < hi && on_left(prims_[lo]); ++lo) left.add(prims_[lo]);
            for (; lo < hi && !on_left(prims_[hi - 1]); --hi) right.add(prims_[hi - 1]);
            if (lo == hi) return lo;
            std::swap(prims_[lo], prims_[--hi]);  // prims_[lo] belonged right and prims_[hi] left
            left.add(prims_[lo++]);
            right.add(prims_[hi]);
        }
    }

    void split_node(uint32_t node, const Child& left, const Child& right, int depth) {
        const auto first = static_cast<uint32_t>(nodes_->size());
        (*nodes_)[node].first = first;
        (*nodes_)[node].count = 0;
        nodes_->push_back({});
        nodes_->push_back({});
        build(first, left, depth + 1);
        build(first + 1, right, depth + 1);
    }

    // Whether the boxes of an object split's children overlap enough to look for a plane.
    bool overlap_enough(SseBox overlap, const SseBox& right) const {
        overlap.lo = _mm_max_ps(overlap.lo, right.lo);
        overlap.hi = _mm_min_ps(overlap.hi, right.hi);
        return _mm_movemask_ps(_mm_cmpgt_ps(overlap.lo, overlap.hi)) == 0 &&
               overlap.half_area() > policy_.overlap_share() * planes_.root_area;
    }

    // Splits the node by the policy's best plane if that costs less than `object_cost` and
    // the free slots hold the references it adds; returns whether it did.
    bool split_by_plane(uint32_t node, const Child& child, int depth, float object_cost) {
        const auto [begin, end, capacity_end, extent] = child;
        std::vector<Bounds3>& boxes = planes_.boxes;
        boxes.clear();
        planes_.prims.clear();
        for (uint32_t i = begin; i < end; ++i) {
            boxes.push_back(prims_[i].box.to_bounds());
            planes_.prims.push_back(prims_[i].index);
        }
        SplitPlane plane;
        if (!(policy_.best_plane(boxes, planes_.prims, extent.bounds.to_bounds(), plane) < object_cost)) return false;
        std::vector<BuildPrim>& left = planes_.left;
        std::vector<BuildPrim>& right = planes_.right;
        left.clear();
        right.clear();
        for (uint32_t i = begin; i < end; ++i) {
            const BuildPrim& p = prims_[i];
            const Bounds3& box = boxes[i - begin];
            if (box.hi[plane.axis] <= plane.position) {
                left.push_back(p);
            } else if (box.lo[plane.axis] >= plane.position) {
                right.push_back(p);
            } else {
                Bounds3 below = box, above = box;
                below.hi[plane.axis] = above.lo[plane.axis] = plane.position;
                add_part(left, p.index, below);
                add_part(right, p.index, above);
            }
        }
        return place_sides(node, child, depth);
    }

    // Stores the plane's sides as the node's children, sharing its free slots out between them;
    // false if they do not fit or one is empty.
    bool place_sides(uint32_t node, const Child& child, int depth) {
        const uint32_t begin = child.begin, capacity_end = child.capacity_end;
        const std::vector<BuildPrim>& left = planes_.left;
        const std::vector<BuildPrim>& right = planes_.right;
        const auto n_left = static_cast<uint32_t>(left.size()), n_right = static_cast<uint32_t>(right.size());
        if (n_left == 0 || n_right == 0 || n_left + n_right > capacity_end - begin) return false;
        const auto to_left = static_cast<uint32_t>((capacity_end - begin - n_left - n_right) * uint64_t{n_left} / (n_left + n_right));
        const uint32_t right_begin = begin + n_left + to_left;
        std::copy(left.begin(), left.end(), prims_.begin() + begin);
        std::copy(right.begin(), right.end(), prims_.begin() + right_begin);
        split_node(node, {begin, begin + n_left, right_begin, extent_of(begin, begin + n_left)},
                   {right_begin, right_begin + n_right, capacity_end, extent_of(right_begin, right_begin + n_right)}, depth);
        return true;
    }

    // Adds a reference to the part of primitive `prim` inside `box`, if there is one.
    void add_part(std::vector<BuildPrim>& side, uint32_t prim, const Bounds3& box) const {
        const Bounds3 part = policy_.part(prim, box);
        if (!part.empty()) side.push_back({SseBox::enclosing(part), prim, {}});
    }

    void make_leaf(uint32_t node, uint32_t begin, uint32_t count) {
        (*nodes_)[node].first = begin;
        (*nodes_)[node].count = count;
    }

    // One bin along all three axes: a box and a count for each. 128 bytes, so a bin's offset is
    // its index shifted, and the axes' boxes and counts lie at fixed offsets from there.
    struct alignas(128) Bin {
        std::array<LazyBox, 3> boxes;
        std::array<uint32_t, 4> counts;  // lane 3 is 0
        __m128i count() const { return _mm_load_si128(reinterpret_cast<const __m128i*>(counts.data())); }
    };
    using Bins = std::array<Bin, sah::kBins>;

    // The primitives fill the bins of all three axes and note their bins; the cost is the
    // unnormalised SAH sum. Block by block, the bins are found first and filled after: neighbours
    // often share a bin, and filling a bin whose address came out of the long chain of the
    // binning arithmetic keeps the processor from running ahead to the next primitive's update.
    // kBinningBlock primitives a block: enough to run ahead on, few enough that the second loop
    // finds them still in the cache.
    Split best_sah_split(uint32_t begin, uint32_t end, const Binning& binning) {
        // Only the bins in use are set up: clearing all of them cost more than binning small nodes.
        Bins bins;
        for (int b = 0; b < binning.count(); ++b) {
            for (LazyBox& box : bins[b].boxes) box.box = SseBox{};
            bins[b].counts = {};
        }
        // The low byte of each lane, packed into one word.
        const __m128i low_bytes = _mm_setr_epi8(0, 4, 8, 12, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1);
        for (uint32_t block = begin; block < end; block += sah::kBinningBlock) {
            const uint32_t block_end = std::min(end, block + sah::kBinningBlock);
            for (uint32_t i = block; i < block_end; ++i) {
                BuildPrim& p = prims_[i];
                const auto word = static_cast<uint32_t>(_mm_cvtsi128_si32(_mm_shuffle_epi8(binning.bins(p.box), low_bytes)));
                std::memcpy(p.bin.data(), &word, sizeof word);
            }
            for (uint32_t i = block; i < block_end; ++i) {
                const BuildPrim& p = prims_[i];
                for (int a = 0; a < 3; ++a) {
                    Bin& bin = bins[p.bin[a]];
                    bin.boxes[a].box.extend(p.box);
                    ++bin.counts[a];
                }
            }
        }
        return best_split(bins, binning, end - begin);
    }

    // The half areas of three boxes, one per lane (0 for an empty box).
    static __m128 half_areas(const std::array<SseBox, 3>& boxes) {
        __m128 x = _mm_sub_ps(boxes[0].hi, boxes[0].lo), y = _mm_sub_ps(boxes[1].hi, boxes[1].lo);
        __m128 z = _mm_sub_ps(boxes[2].hi, boxes[2].lo), w = _mm_setzero_ps();
        _MM_TRANSPOSE4_PS(x, y, z, w);  // now x, y, z hold the extents along x, y, z of boxes 0..2
        const __m128 area = _mm_add_ps(_mm_add_ps(_mm_mul_ps(x, y), _mm_mul_ps(y, z)), _mm_mul_ps(z, x));
        return _mm_andnot_ps(_mm_cmplt_ps(x, _mm_setzero_ps()), area);
    }

    // Sweeps from the right to get each split's right-hand cost, then from the left, the three
    // axes in the lanes of one register. Ties go to the lower axis, then to the lower bin.
    static Split best_split(const Bins& bins, const Binning& binning, uint32_t total) {
        const int bin_count = binning.count();
        alignas(16) std::array<std::array<float, 4>, sah::kBins> right_cost;
        std::array<SseBox, 3> acc;
        __m128i n = _mm_setzero_si128();
        for (int b = bin_count - 1; b > 0; --b) {
            for (int a = 0; a < 3; ++a) acc[a].extend(bins[b].boxes[a].box);
            n = _mm_add_epi32(n, bins[b].count());
            _mm_store_ps(right_cost[b].data(), _mm_mul_ps(half_areas(acc), _mm_cvtepi32_ps(n)));
        }
        acc = {};
        n = _mm_setzero_si128();
        const __m128i all = _mm_set1_epi32(static_cast<int>(total));
        __m128 best_cost = _mm_set1_ps(std::numeric_limits<float>::infinity());
        __m128i best_bin = _mm_setzero_si128();
        for (int b = 0; b < bin_count - 1; ++b) {
            for (int a = 0; a < 3; ++a) acc[a].extend(bins[b].boxes[a].box);
            n = _mm_add_epi32(n, bins[b].count());
            const __m128 cost =
                _mm_add_ps(_mm_mul_ps(half_areas(acc), _mm_cvtepi32_ps(n)), _mm_load_ps(right_cost[b + 1].data()));
            // Both sides hold primitives (0 < n < total) and the cost is lower than the best so far.
            const __m128 both_sides = _mm_castsi128_ps(
                _mm_and_si128(_mm_cmpgt_epi32(n, _mm_setzero_si128()), _mm_cmplt_epi32(n, all)));
            const __m128 better = _mm_and_ps(both_sides, _mm_cmplt_ps(cost, best_cost));
            best_cost = _mm_blendv_ps(best_cost, cost, better);
            best_bin = _mm_blendv_epi8(best_bin, _mm_set1_epi32(b + 1), _mm_castps_si128(better));
        }
        alignas(16) float costs[4];
        alignas(16) int32_t first_right[4];
        _mm_store_ps(costs, best_cost);
        _mm_store_si128(reinterpret_cast<__m128i*>(first_right), best_bin);
        Split best;
        for (int a = 0; a < 3; ++a)
            if (binning.splittable(a) && costs[a] < best.cost) best = {a, first_right[a], costs[a]};
        return best;
    }

    // A NaN centre (a box from -inf to +inf) counts as 0, so the order stays a strict weak one.
    static float median_key(const BuildPrim& p, int axis) {
        alignas(16) float c[4];
        _mm_store_ps(c, p.twice_centre());
        return std::isnan(c[axis]) ? 0.0f : c[axis];
    }

    uint32_t median_split(uint32_t begin, uint32_t end, const SseBox& centres) {
        alignas(16) float extent[4];
        _mm_store_ps(extent, _mm_sub_ps(centres.hi, centres.lo));
        const int axis = max_axis(Vec3{extent[0], extent[1], extent[2]});
        const uint32_t mid = begin + (end - begin) / 2;
        std::nth_element(prims_.begin() + begin, prims_.begin() + mid, prims_.begin() + end,
                         [axis](const BuildPrim& a, const BuildPrim& b) { return median_key(a, axis) < median_key(b, axis); });
        return mid;
    }

    // What splits by planes keep: the root's area for the overlap test, and a node's
    // references and a plane's sides, before they are stored. Nothing for a policy without them.
    struct PlaneState {
        float root_area = 0;
        std::vector<Bounds3> boxes;
        std::vector<uint32_t> prims;
        std::vector<BuildPrim> left, right;
    };
    struct NoPlanes {};

    std::vector<BuildPrim>& prims_;
    const Policy& policy_;
    [[no_unique_address]] std::conditional_t<kPlanes, PlaneState, NoPlanes> planes_;
    std::vector<BinaryNode>* nodes_;
    uint32_t largest_task_ = 0;  // subtrees of at most this many primitives are left as tasks
    std::vector<Task> tasks_;
};


// build_sah_tree with `policy`: primitives with empty boxes are left out.
template <typename Policy>
BinaryTree build_sah_tree(std::span<const Bounds3> prim_bounds, const Policy& policy, const SahBuildConfig& config = {}) {
    std::vector<sah::BuildPrim> prims;
    prims.reserve(prim_bounds.size());
    for (uint32_t i = 0; i < prim_bounds.size(); ++i) {
        if (prim_bounds[i].empty()) continue;
        // Field by field: built whole, the primitive goes through the stack, where loading its
        // index and bins as one 16-byte word waits for their narrower stores (a failed store
        // forwarding, in the loop over every primitive).
        sah::BuildPrim& p = prims.emplace_back();
        p.box = sah::SseBox::enclosing(prim_bounds[i]);
        p.index = i;
    }
    if (prims.empty()) return {};
    std::vector<BinaryNode> nodes;
    return SahBuilder<Policy>(prims, policy, nodes).run(config);
}

}  // namespace glint
