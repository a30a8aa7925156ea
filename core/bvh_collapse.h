// The eight-wide nodes of a Bvh from the binary tree that SAH builds: which binary nodes become
// wide nodes, so that the sum of their surface areas, the SAH's count of node visits, is least.
// A dynamic programme over the binary tree (after Ylitie, Karras and Laine, "Efficient
// incoherent ray traversal on GPUs through compressed wide BVHs", HPG 2017). The leaves are the
// binary tree's, so they cost the same in every choice and drop out. Against the greedy collapse
// that opened the largest child first, the trees of Sponza and the bunny take 20-30% fewer
// nodes, and the tree with spatial splits traces diffuse rays 4-7% faster (bench/BENCHMARKS.md,
// eleventh round).
#pragma once

#include <vector>

#include "bvh.h"

namespace glint {

// The root's children fill the first node; `binary` is not empty.
std::vector<BvhNode> collapse_to_wide(const std::vector<BinaryNode>& binary);

}  // namespace glint
