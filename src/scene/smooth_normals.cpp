// Smooth shading normals (compute_smooth_normals in scene.h): corners grouped by welded position, each group's
// distinct face normals blended within the crease angle, and the results interned so that equal normals share one
// entry. The groups are shared out among threads in ranges; each interns its own results in order and the ranges
// are then joined in order, which gives every normal the index a one-thread pass would.
// Depends on core and scene.h only.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>

#include "core/memory_budget.h"
#include "core/thread_pool.h"
#include "scene/scene.h"

namespace lueur {
namespace {

bool less_xyz(const Vec3& a, const Vec3& b) {
  if (a.x != b.x) return a.x < b.x;
  if (a.y != b.y) return a.y < b.y;
  return a.z < b.z;
}

/// `count` items cut into consecutive ranges, one per thread of `pool` where there are enough items for it.
struct Ranges {
  Ranges(size_t items, const ThreadPool& pool)
      : count(items), parts(static_cast<unsigned>(std::clamp<size_t>(items / 4096 + 1, 1, pool.thread_count()))) {}
  size_t begin(unsigned part) const { return count * part / parts; }
  size_t end(unsigned part) const { return count * (part + 1) / parts; }
  /// Runs work(begin, end, part, on_calling_thread) for every range on `pool`.
  template <typename Work>
  void run(ThreadPool& pool, Work&& work) const {
    pool.parallel_for(static_cast<int>(parts), [&](int part, int worker) {
      const auto p = static_cast<unsigned>(part);
      work(begin(p), end(p), p, worker == 0);
    });
  }

  size_t count;
  unsigned parts;
};

/// Gives every position the id of its group of exactly equal positions, so that triangle soups (each triangle with
/// its own copies of the corners) smooth like indexed meshes. Ids follow the positions' order (x, then y, then z).
std::vector<uint32_t> weld_positions(const std::vector<Vec3>& positions, ThreadPool& pool) {
  std::vector<uint32_t> weld(positions.size());
  std::vector<uint32_t> order;
  order.reserve(positions.size());
  uint32_t next_id = 0;
  for (uint32_t i = 0; i < positions.size(); ++i) {
    // NaN would break the strict weak ordering of the sort; such points simply stay alone.
    if (is_finite(positions[i])) {
      order.push_back(i);
    } else {
      weld[i] = next_id++;
    }
  }
  const auto less = [&](uint32_t a, uint32_t b) { return less_xyz(positions[a], positions[b]); };
  // Sorted in ranges on every thread, then merged: the ids only depend on the positions' order.
  const Ranges ranges(order.size(), pool);
  ranges.run(pool, [&](size_t begin, size_t end, unsigned, bool) {
    std::sort(order.begin() + static_cast<ptrdiff_t>(begin), order.begin() + static_cast<ptrdiff_t>(end), less);
  });
  for (unsigned p = 1; p < ranges.parts; ++p)
    std::inplace_merge(order.begin(), order.begin() + static_cast<ptrdiff_t>(ranges.begin(p)),
                       order.begin() + static_cast<ptrdiff_t>(ranges.end(p)), less);
  for (size_t k = 0; k < order.size(); ++k) {
    if (k == 0 || less_xyz(positions[order[k - 1]], positions[order[k]])) ++next_id;
    weld[order[k]] = next_id - 1;
  }
  return weld;
}

float corner_angle(const Vec3& at, const Vec3& a, const Vec3& b) {
  const Vec3 e1 = a - at;
  const Vec3 e2 = b - at;
  // atan2 of |cross| and dot stays accurate for the very small and very flat angles where acos does not.
  return std::atan2(glm::length(glm::cross(e1, e2)), glm::dot(e1, e2));
}

/// Equal normals (bit for bit, -0 folded into +0) share one index, given in the order they were first seen: an open
/// addressing table of indices into `normals`.
class NormalInterner {
 public:
  uint32_t intern(const Vec3& n) {
    if (2 * (normals.size() + 1) > slots_.size()) grow();
    const Key key = key_of(n);
    for (size_t slot = hash(key) & mask_;; slot = (slot + 1) & mask_) {
      const uint32_t index = slots_[slot];
      if (index == kEmpty) {
        slots_[slot] = static_cast<uint32_t>(normals.size());
        normals.push_back(n);
        keys_.push_back(key);
        return slots_[slot];
      }
      if (keys_[index] == key) return index;
    }
  }

  std::vector<Vec3> normals;

 private:
  struct Key {
    uint32_t bits[3];
    bool operator==(const Key& other) const {
      return bits[0] == other.bits[0] && bits[1] == other.bits[1] && bits[2] == other.bits[2];
    }
  };
  static constexpr uint32_t kEmpty = 0xffffffffu;

  static Key key_of(const Vec3& v) {
    Key key{};
    for (int i = 0; i < 3; ++i) {
      const float value = v[i] + 0.0f;
      std::memcpy(&key.bits[i], &value, sizeof value);
    }
    return key;
  }
  static size_t hash(const Key& key) {
    // Every bit of the three floats moves every bit of the slot (a 64-bit finaliser): smooth normals differ in few
    // bits, and linear probing punishes clusters.
    uint64_t h = (uint64_t{key.bits[0]} << 32 | key.bits[1]) ^ (uint64_t{key.bits[2]} * 0x9e3779b97f4a7c15ull);
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdull;
    h ^= h >> 33;
    h *= 0xc4ceb9fe1a85ec53ull;
    h ^= h >> 33;
    return static_cast<size_t>(h);
  }
  void grow() {
    const size_t size = std::max<size_t>(1024, 2 * slots_.size());
    slots_.assign(size, kEmpty);
    mask_ = size - 1;
    for (uint32_t index = 0; index < keys_.size(); ++index) {
      size_t slot = hash(keys_[index]) & mask_;
      while (slots_[slot] != kEmpty) slot = (slot + 1) & mask_;
      slots_[slot] = index;
    }
  }

  std::vector<uint32_t> slots_;
  std::vector<Key> keys_;
  size_t mask_ = 0;
};

/// One group's distinct face normal, the angles of its corners there, and its blend within the crease (as an index
/// into the range's interner).
struct Distinct {
  Vec3 normal;
  float weight;
  uint32_t index;
};

}  // namespace

void compute_smooth_normals(Scene& scene, float crease_degrees, unsigned threads,
                            const std::function<void(double done)>& progress) {
  ThreadPool pool(static_cast<int>(threads));
  // Reported at the end of each step by the rough share of the time up to there; the groups, group by group.
  const auto report = [&](double done) {
    if (progress) progress(done);
  };
  const size_t triangle_count = scene.triangles.size();
  const float crease = std::clamp(std::isfinite(crease_degrees) ? crease_degrees : 60.0f, 0.0f, 180.0f);
  // The small slack lets faces with the same normal (dot rounding to just under 1) join even at crease 0.
  const float cos_crease = std::cos(crease * kPi / 180.0f) - 1e-6f;

  // Unit face normals; zero-area (or overflowing) triangles have none (zero) and take no part.
  // And each corner's angle, weighing its face's normal: computed here in triangle order, where the positions they
  // read are at hand, rather than corner by corner in the scattered order of the groups below.
  std::vector<Vec3> face_normal(triangle_count, Vec3(0.0f));
  std::vector<float> corner_weight(3 * triangle_count);
  Ranges(triangle_count, pool).run(pool, [&](size_t begin, size_t end, unsigned, bool) {
    for (size_t t = begin; t < end; ++t) {
      const Vec3 raw = scene.geometric_normal_raw(static_cast<uint32_t>(t));
      const float length = glm::length(raw);
      if (length > 0.0f && std::isfinite(length)) face_normal[t] = raw / length;
      const Triangle& tri = scene.triangles[t];
      for (uint32_t c = 0; c < 3; ++c) {
        const float angle = corner_angle(scene.positions[tri.v[c]], scene.positions[tri.v[(c + 1) % 3]],
                                         scene.positions[tri.v[(c + 2) % 3]]);
        corner_weight[3 * t + c] = std::isfinite(angle) ? angle : 0.0f;
      }
    }
  });
  const auto usable = [&](uint32_t t) { return face_normal[t] != Vec3(0.0f); };

  report(0.15);
  // Corners grouped by welded position (compressed rows: corners of group g lie in [start[g], start[g+1])).
  const std::vector<uint32_t> weld = weld_positions(scene.positions, pool);
  const uint32_t group_count = weld.empty() ? 0u : *std::max_element(weld.begin(), weld.end()) + 1u;
  std::vector<uint32_t> start(group_count + 1, 0);
  for (uint32_t t = 0; t < triangle_count; ++t) {
    if (!usable(t)) continue;
    for (uint32_t c = 0; c < 3; ++c) ++start[weld[scene.triangles[t].v[c]] + 1];
  }
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<uint32_t> corners(start.back());
  {
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (uint32_t t = 0; t < triangle_count; ++t) {
      if (!usable(t)) continue;
      for (uint32_t c = 0; c < 3; ++c) corners[fill[weld[scene.triangles[t].v[c]]]++] = 3 * t + c;
    }
  }

  report(0.4);
  std::vector<Triangle>& triangles = scene.triangles;
  for (Triangle& tri : triangles) tri.n[0] = tri.n[1] = tri.n[2] = kNoNormal;

  // Per range of groups, each corner gets its normal's index in the range's own interner; the ranges' interners are
  // then joined in order and the corners renumbered.
  const Ranges groups(group_count, pool);
  std::vector<NormalInterner> interners(groups.parts);
  groups.run(pool, [&](size_t group_begin, size_t group_end, unsigned part, bool calling_thread) {
    NormalInterner& interner = interners[part];
    // Per group, corners whose faces share one normal get one result: a flat fan around a vertex of a 5000-gon
    // costs one sum, not 5000 x 5000.
    std::vector<Distinct> distinct;
    std::vector<uint32_t> order;
    for (size_t g = group_begin; g < group_end; ++g) {
      if (calling_thread && (g - group_begin) % 65536 == 65535)  // the calling thread's range stands for all
        report(0.4 + 0.45 * static_cast<double>(g - group_begin) / static_cast<double>(group_end - group_begin));
      const uint32_t begin = start[g];
      const uint32_t end = start[g + 1];
      if (begin == end) continue;
      order.assign(corners.begin() + begin, corners.begin() + end);
      std::sort(order.begin(), order.end(),
                [&](uint32_t a, uint32_t b) { return less_xyz(face_normal[a / 3], face_normal[b / 3]); });
      distinct.clear();
      for (uint32_t corner : order) {
        const Vec3& n = face_normal[corner / 3];
        if (distinct.empty() || less_xyz(distinct.back().normal, n)) distinct.push_back({n, 0.0f, 0u});
        distinct.back().weight += corner_weight[corner];
      }
      for (Distinct& d : distinct) {
        Vec3 sum(0.0f);
        for (const Distinct& other : distinct)
          if (glm::dot(d.normal, other.normal) >= cos_crease) sum += other.weight * other.normal;
        const float length = glm::length(sum);
        d.index = interner.intern((length > 1e-12f && std::isfinite(length)) ? sum / length : d.normal);
      }
      size_t k = 0;
      for (uint32_t corner : order) {
        const Vec3& n = face_normal[corner / 3];
        while (less_xyz(distinct[k].normal, n)) ++k;
        triangles[corner / 3].n[corner % 3] = distinct[k].index;
      }
    }
  });
  report(0.85);
  // The first range's indices are already the file's; the others' are renumbered into it.
  NormalInterner all = std::move(interners[0]);
  std::vector<std::vector<uint32_t>> renumber(groups.parts);
  for (unsigned part = 1; part < groups.parts; ++part)
    for (const Vec3& n : interners[part].normals) renumber[part].push_back(all.intern(n));
  interners.clear();
  groups.run(pool, [&](size_t group_begin, size_t group_end, unsigned part, bool) {
    if (part == 0) return;
    for (uint32_t i = start[group_begin]; i < start[group_end]; ++i) {
      uint32_t& index = triangles[corners[i] / 3].n[corners[i] % 3];
      index = renumber[part][index];
    }
  });
  scene.normals = std::move(all.normals);
  release_free_memory();
}

}  // namespace lueur
