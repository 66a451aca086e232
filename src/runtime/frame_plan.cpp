// Largest-remainder shares and round ends.
#include "runtime/frame_plan.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace lueur {

std::vector<uint64_t> share_frames(uint64_t count, const std::vector<double>& rates) {
  const size_t n = rates.size();
  std::vector<uint64_t> shares(n, 0);
  if (n == 0) return shares;
  double known_sum = 0.0;
  size_t known = 0;
  for (const double r : rates)
    if (r > 0.0 && std::isfinite(r)) {
      known_sum += r;
      ++known;
    }
  const double fallback = known > 0 ? known_sum / static_cast<double>(known) : 1.0;
  std::vector<double> weights(n);
  for (size_t i = 0; i < n; ++i) weights[i] = rates[i] > 0.0 && std::isfinite(rates[i]) ? rates[i] : fallback;
  const double total = std::accumulate(weights.begin(), weights.end(), 0.0);
  std::vector<double> remainders(n);
  uint64_t given = 0;
  for (size_t i = 0; i < n; ++i) {
    const double exact = static_cast<double>(count) * weights[i] / total;
    shares[i] = std::min(count - given, static_cast<uint64_t>(std::floor(exact)));
    given += shares[i];
    remainders[i] = exact - std::floor(exact);
  }
  std::vector<size_t> order(n);
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return remainders[a] > remainders[b]; });
  for (size_t k = 0; given < count; k = (k + 1) % n, ++given) ++shares[order[k]];
  return shares;
}

uint64_t round_end(uint64_t done, uint64_t wanted, uint64_t total, uint64_t snapshots_from) {
  if (done >= total) return total;
  uint64_t next_power = 1;
  while (next_power <= done || next_power < snapshots_from) next_power <<= 1;
  return std::min({total, next_power, done + std::max<uint64_t>(wanted, 1)});
}

std::vector<uint64_t> plan_round(uint64_t done, uint64_t total, uint64_t snapshots_from,
                                 const std::vector<double>& rates, double seconds) {
  std::vector<uint64_t> wanted(rates.size(), 1);
  uint64_t count = 0;
  for (size_t i = 0; i < rates.size(); ++i) {
    if (rates[i] > 0.0 && std::isfinite(rates[i]))
      wanted[i] = std::max<uint64_t>(1, static_cast<uint64_t>(std::llround(std::min(rates[i] * seconds, 1e9))));
    count += wanted[i];
  }
  // A round never leaves a short one behind it before the next stop (a power of two or the end), where a fast worker
  // would wait for a slow one's last frame: within two rounds of the stop, this round goes all the way to it.
  const uint64_t stop = round_end(done, total, total, snapshots_from);
  if (stop - done <= 2 * count) return share_frames(stop - done, rates);
  return wanted;
}

}  // namespace lueur
