// The sixteen-wide nodes of a Bvh from the binary tree that SAH builds: which binary subtrees
// become wide nodes and which become leaves, so that the SAH cost of the wide tree is least. A
// dynamic programme over the binary tree (after Ylitie, Karras and Laine, "Efficient incoherent
// ray traversal on GPUs through compressed wide BVHs", HPG 2017). A wide node costs its surface
// area (the SAH's chance that a ray visits it), a leaf kLeafCost times its own. Any binary
// subtree of at most BinaryTree::kMaxLeafSize primitives may become one leaf, as its primitives
// are one run of build order; so the tree with spatial splits is built down to single
// primitives and its leaves are chosen here. A greedy collapse (open the largest child first)
// would be cheaper to build but leaves nodes half full: the programme spends build time, linear
// in the binary tree's size, on fewer nodes and fewer node visits per ray.
#pragma once

#include <vector>

#include "accel/bvh_node.h"
#include "accel/sah_builder.h"

namespace glint {

// A leaf's four-wide run test against a node's box tests: the leaves' share of the cost. Lower
// makes more, smaller leaves under fuller nodes; higher, fewer leaves and more node visits.
inline constexpr float kLeafCost = 1.5f;

// The root's children fill the first node; `binary` is not empty.
std::vector<BvhNode> collapse_to_wide(const std::vector<BinaryNode>& binary);

}  // namespace glint
