#pragma once
// Which file vertex each node is. A mesh's nodes are renumbered at load so that
// neighbours sit near each other in memory and its springs fall into runs
// (mesh_node_order.h), yet users name nodes as the file numbers its vertices:
// pins, pin_motion, RESULT.json and the window's script and report. Every such
// boundary maps through this one type.
#include <cstdint>
#include <vector>

namespace neurocloth {

class NodeNumbering {
 public:
  // Nodes in file order: what grids and meshes kept in their file's order use.
  NodeNumbering() = default;
  // Node i is the file's vertex sources[i]; `sources` is a permutation.
  explicit NodeNumbering(std::vector<std::int32_t> sources);

  bool identity() const { return source_of_.empty(); }
  // The file's index of node `node`, and the node of file index `source`;
  // both in [0, node count).
  int source(int node) const { return identity() ? node : source_of_[node]; }
  int node(int source) const { return identity() ? source : node_of_[source]; }

 private:
  // Empty when nodes are in file order, so a grid pays nothing.
  std::vector<std::int32_t> source_of_, node_of_;
};

}  // namespace neurocloth
