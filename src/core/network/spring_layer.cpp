#include "core/network/spring_layer.h"

#include "core/network/spring_chunks.h"

namespace neurocloth {

const char* to_string(SpringFunctionKind k) {
  return k == SpringFunctionKind::linear ? "linear" : "stiffening";
}

void SpringLayer::rebuild_runs() {
  runs.clear();
  const auto n = static_cast<std::int32_t>(node_a.size());
  for (std::int32_t s = 0; s < n; ++s) {
    if (!runs.empty()) {
      SpringRun& r = runs.back();
      if (node_a[s] == r.node_a + r.count && node_b[s] == r.node_b + r.count) {
        ++r.count;
        continue;
      }
    }
    runs.push_back({s, 1, node_a[s], node_b[s]});
  }
  chunks = spring_chunks::cut(runs);
}

}  // namespace neurocloth
