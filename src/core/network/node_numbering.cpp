#include "core/network/node_numbering.h"

#include <cstddef>
#include <utility>

namespace neurocloth {

NodeNumbering::NodeNumbering(std::vector<std::int32_t> sources)
    : source_of_(std::move(sources)), node_of_(source_of_.size()) {
  bool in_order = true;
  for (std::size_t i = 0; i < source_of_.size(); ++i) {
    node_of_[source_of_[i]] = static_cast<std::int32_t>(i);
    in_order = in_order && source_of_[i] == static_cast<std::int32_t>(i);
  }
  if (in_order) {
    source_of_.clear();
    node_of_.clear();
  }
}

}  // namespace neurocloth
