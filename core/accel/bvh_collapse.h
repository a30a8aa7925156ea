// The sixteen-wide nodes of a Bvh from the binary tree that SAH builds: which binary subtrees
// become wide nodes and which become leaves, so that the SAH cost of the wide tree is least. A
// dynamic programme over the binary tree (after Ylitie, Karras and Laine, "Efficient incoherent
// ray traversal on GPUs through compressed wide BVHs", HPG 2017). A wide node costs its surface
// area (the SAH's chance that a ray visits it), a leaf kLeafCost times its own. Any binary
// subtree of at most BinaryTree::kMaxLeafSize primitives may become one leaf, as its primitives
// are one run of build order; so the tree with spatial splits is built down to single
// primitives and its leaves are chosen here. Against the greedy collapse that opened the largest
// child first, the trees of Sponza and the bunny take 26-40% fewer nodes, and their diffuse rays
// find closest hits 5-9% and any hit 6-13% faster (bench/BENCHMARKS.md, eleventh round).
#pragma once

#include <vector>

#include "accel/bvh.h"

namespace glint {

// A leaf's four-wide run test against a node's box tests: the leaves' share of the cost. 1.5
// against 1 and 2, timed on the eight-wide tree (bench/BENCHMARKS.md, eleventh round).
inline constexpr float kLeafCost = 1.5f;

// The root's children fill the first node; `binary` is not empty.
std::vector<BvhNode> collapse_to_wide(const std::vector<BinaryNode>& binary);

}  // namespace glint
