#pragma once
// The elimination order of the large steps' factor (spring_laplacian.cpp).
// Internal to the core.
#include <Eigen/SparseCore>
#include <cstdint>
#include <vector>

namespace neurocloth {

using LaplacianPattern = Eigen::SparseMatrix<double, Eigen::ColMajor, std::int32_t>;

// A nested-dissection order of the symmetric matrix whose lower triangle is
// `lower`: place[i] is node i's place in it. The nodes of one half come
// first, then the other half's, then a separator that no edge crosses, so
// that the factor's two halves are solved independently; each half is cut
// again the same way down to parts of a few thousand nodes, which are in
// approximate minimum degree order. half and separator are where the second
// half and the separator begin; both 0 when the graph does not split (then
// place is one minimum-degree order).
void laplacian_order(const LaplacianPattern& lower, std::vector<std::int32_t>& place,
                     std::int32_t& half, std::int32_t& separator);

}  // namespace neurocloth
