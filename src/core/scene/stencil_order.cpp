#include "core/scene/stencil_order.h"

#include <algorithm>
#include <tuple>

namespace neurocloth {
namespace {

// A shorter stretch fills no vector of doubles twice over and pays a chunk's
// set-up; left in node order, its springs read nodes near their neighbours'.
constexpr std::size_t kMinStencilRun = 8;

std::tuple<SpringFamily, std::int32_t, std::int32_t> stencil_key(const SpringSpec& s) {
  return {s.family, s.b - s.a, s.a};
}

bool continues(const SpringSpec& previous, const SpringSpec& s) {
  return s.family == previous.family && s.a == previous.a + 1 && s.b == previous.b + 1;
}

// Where the stretch of springs[first] ends.
std::size_t stretch_end(const std::vector<SpringSpec>& springs, std::size_t first) {
  std::size_t end = first + 1;
  while (end < springs.size() && continues(springs[end - 1], springs[end]))
    ++end;
  return end;
}

}  // namespace

void sort_into_stencil_runs(std::vector<SpringSpec>& springs) {
  std::sort(springs.begin(), springs.end(), [](const SpringSpec& x, const SpringSpec& y) {
    return stencil_key(x) < stencil_key(y);
  });
  std::vector<SpringSpec> ordered, scattered;
  ordered.reserve(springs.size());
  for (std::size_t first = 0; first < springs.size();) {
    const std::size_t end = stretch_end(springs, first);
    auto& into = end - first >= kMinStencilRun ? ordered : scattered;
    into.insert(into.end(), springs.begin() + static_cast<std::ptrdiff_t>(first),
                springs.begin() + static_cast<std::ptrdiff_t>(end));
    first = end;
  }
  std::sort(scattered.begin(), scattered.end(), [](const SpringSpec& x, const SpringSpec& y) {
    return std::tie(x.a, x.b, x.family) < std::tie(y.a, y.b, y.family);
  });
  ordered.insert(ordered.end(), scattered.begin(), scattered.end());
  springs = std::move(ordered);
}

std::size_t springs_in_stencil_runs(const std::vector<SpringSpec>& springs) {
  std::size_t in_runs = 0;
  for (std::size_t first = 0; first < springs.size();) {
    const std::size_t end = stretch_end(springs, first);
    if (end - first >= kMinStencilRun) in_runs += end - first;
    first = end;
  }
  return in_runs;
}

}  // namespace neurocloth
