#pragma once
// Data that depends on a Chebyshev grid's degree alone, computed once and shared by every user
// of that degree: the most recently used degrees are kept (a few cover an optimisation: the
// SS and DS grids and their 10× finer check).
#include <algorithm>
#include <cstddef>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

namespace gaitopt {

// The T of degree n, made by make(n) at its first use. One cache per T (and type of `make`):
// each kind of data has its own type and its one `make`.
template <class T, class Make>
std::shared_ptr<const T> sharedByDegree(int n, const Make& make) {
  constexpr std::size_t kKept = 8;
  static std::mutex mutex;
  static std::vector<std::pair<int, std::shared_ptr<const T>>> kept;  // most recent first
  const std::lock_guard<std::mutex> lock(mutex);
  auto it = std::find_if(kept.begin(), kept.end(), [n](const auto& e) { return e.first == n; });
  std::pair<int, std::shared_ptr<const T>> entry =
      it != kept.end() ? *it : std::make_pair(n, std::make_shared<const T>(make(n)));
  if (it != kept.end()) kept.erase(it);
  kept.insert(kept.begin(), entry);
  if (kept.size() > kKept) kept.pop_back();
  return entry.second;
}

}  // namespace gaitopt
