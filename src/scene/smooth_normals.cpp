// Smooth shading normals (compute_smooth_normals in scene.h): corners grouped by welded position, each group's
// distinct face normals blended within the crease angle, and the results interned so that equal normals share one
// entry, numbered as they are first met in the positions' sorted order (x, then y, then z).
//
// The work is split by what each step reads. The blends are computed group by group in vertex order, where a
// file's triangles keep the corners of neighbouring vertices close; only the interning walks the groups in sorted
// order, one look-up a group. Both run on every thread in ranges; the ranges' interners are then joined in order,
// which gives every normal the index a one-thread pass would.
// Depends on core and scene.h only.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/huge_pages.h"
#include "core/memory_budget.h"
#include "core/thread_pool.h"
#include "scene/normal_interner.h"
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

/// Positions welded by exact equality, so that triangle soups (each triangle with its own copies of the corners)
/// smooth like indexed meshes.
struct Weld {
  /// Per position, the smallest index of a position equal to it (a group's name, in the file's vertex order).
  HugePageVector<uint32_t> representative;
  /// One representative per distinct finite position, in the positions' sorted order (x, then y, then z).
  HugePageVector<uint32_t> sorted;
};

Weld weld_positions(const std::vector<Vec3>& positions, ThreadPool& pool) {
  Weld weld;
  weld.representative.resize(positions.size());
  // Sorted as (position, index) records rather than indices, so that the comparisons read memory in order.
  struct Keyed {
    Vec3 position;
    uint32_t index;
  };
  HugePageVector<Keyed> order;
  order.reserve(positions.size());
  for (uint32_t i = 0; i < positions.size(); ++i) {
    weld.representative[i] = i;
    // NaN would break the strict weak ordering of the sort; such points simply stay alone (and, being no part of
    // a usable face, are never smoothed).
    if (is_finite(positions[i])) order.push_back({positions[i], i});
  }
  const auto less = [](const Keyed& a, const Keyed& b) { return less_xyz(a.position, b.position); };
  // Sorted in ranges on every thread, then merged: equal positions end up next to each other in any order.
  const Ranges ranges(order.size(), pool);
  ranges.run(pool, [&](size_t begin, size_t end, unsigned, bool) {
    std::sort(order.begin() + static_cast<ptrdiff_t>(begin), order.begin() + static_cast<ptrdiff_t>(end), less);
  });
  for (unsigned p = 1; p < ranges.parts; ++p)
    std::inplace_merge(order.begin(), order.begin() + static_cast<ptrdiff_t>(ranges.begin(p)),
                       order.begin() + static_cast<ptrdiff_t>(ranges.end(p)), less);
  for (size_t run_begin = 0, run_end = 0; run_begin < order.size(); run_begin = run_end) {
    uint32_t smallest = order[run_begin].index;
    for (run_end = run_begin + 1;
         run_end < order.size() && !less_xyz(order[run_begin].position, order[run_end].position); ++run_end)
      smallest = std::min(smallest, order[run_end].index);
    for (size_t k = run_begin; k < run_end; ++k) weld.representative[order[k].index] = smallest;
    weld.sorted.push_back(smallest);
  }
  return weld;
}

float corner_angle(const Vec3& at, const Vec3& a, const Vec3& b) {
  const Vec3 e1 = a - at;
  const Vec3 e2 = b - at;
  // atan2 of |cross| and dot stays accurate for the very small and very flat angles where acos does not.
  return std::atan2(glm::length(glm::cross(e1, e2)), glm::dot(e1, e2));
}

/// Unit face normals (zero for zero-area or overflowing triangles, which take no part) and each corner's angle,
/// which weighs its face's normal.
struct Faces {
  HugePageVector<Vec3> normal;
  HugePageVector<float> corner_weight;
  bool usable(uint32_t t) const { return normal[t] != Vec3(0.0f); }
};

Faces measure_faces(const Scene& scene, ThreadPool& pool) {
  const size_t triangle_count = scene.triangles.size();
  Faces faces{HugePageVector<Vec3>(triangle_count, Vec3(0.0f)), HugePageVector<float>(3 * triangle_count)};
  Ranges(triangle_count, pool).run(pool, [&](size_t begin, size_t end, unsigned, bool) {
    for (size_t t = begin; t < end; ++t) {
      const Vec3 raw = scene.geometric_normal_raw(static_cast<uint32_t>(t));
      const float length = glm::length(raw);
      if (length > 0.0f && std::isfinite(length)) faces.normal[t] = raw / length;
      const Triangle& tri = scene.triangles[t];
      for (uint32_t c = 0; c < 3; ++c) {
        const float angle = corner_angle(scene.positions[tri.v[c]], scene.positions[tri.v[(c + 1) % 3]],
                                         scene.positions[tri.v[(c + 2) % 3]]);
        faces.corner_weight[3 * t + c] = std::isfinite(angle) ? angle : 0.0f;
      }
    }
  });
  return faces;
}

/// Compressed rows: the corners (3 t + c) of usable faces at the positions welded to representative v lie in
/// corners[start[v], start[v + 1]), in triangle order.
struct CornerGroups {
  HugePageVector<uint32_t> start;
  HugePageVector<uint32_t> corners;
};

CornerGroups group_corners(const Scene& scene, const Weld& weld, const Faces& faces) {
  CornerGroups groups;
  groups.start.assign(scene.positions.size() + 1, 0);
  const auto triangle_count = static_cast<uint32_t>(scene.triangles.size());
  for (uint32_t t = 0; t < triangle_count; ++t) {
    if (!faces.usable(t)) continue;
    for (uint32_t c = 0; c < 3; ++c) ++groups.start[weld.representative[scene.triangles[t].v[c]] + 1];
  }
  std::partial_sum(groups.start.begin(), groups.start.end(), groups.start.begin());
  groups.corners.resize(groups.start.back());
  HugePageVector<uint32_t> fill(groups.start.begin(), groups.start.end() - 1);
  for (uint32_t t = 0; t < triangle_count; ++t) {
    if (!faces.usable(t)) continue;
    for (uint32_t c = 0; c < 3; ++c) groups.corners[fill[weld.representative[scene.triangles[t].v[c]]]++] = 3 * t + c;
  }
  return groups;
}

/// Every group's results: a blended normal per distinct face normal at the position, in the face normals' sorted
/// order, those that blend all of them (the same sum) kept once; group v's lie in normals[start[v], start[v + 1]).
struct Blends {
  HugePageVector<Vec3> normals;
  HugePageVector<uint32_t> start;
};

/// Blends each group's distinct face normals within the crease, group by group in vertex order, and writes into
/// each corner's normal index its result's place within the group.
Blends blend_groups(Scene& scene, const Faces& faces, const CornerGroups& groups, float cos_crease, ThreadPool& pool,
                    const std::function<void(double)>& report) {
  const size_t vertex_count = groups.start.size() - 1;
  const Ranges ranges(vertex_count, pool);
  // Each range's results first go to its own array, placed after the earlier ranges' once all are done.
  std::vector<HugePageVector<Vec3>> range_normals(ranges.parts);
  Blends blends;
  blends.start.assign(vertex_count + 1, 0);
  ranges.run(pool, [&](size_t vertex_begin, size_t vertex_end, unsigned part, bool calling_thread) {
    HugePageVector<Vec3>& results = range_normals[part];
    // Per group, corners whose faces share one normal get one result: a flat fan around a vertex of a 5000-gon
    // costs one sum, not 5000 x 5000.
    struct Distinct {
      Vec3 normal;
      float weight;
    };
    // A corner with its face's normal and its weight at hand, so that sorting them reads no other array.
    struct CornerAt {
      Vec3 normal;
      float weight;
      uint32_t corner;
    };
    std::vector<Distinct> distinct;
    std::vector<CornerAt> at;
    std::vector<uint32_t> slot;  // per distinct normal, its result's place within the group
    for (size_t v = vertex_begin; v < vertex_end; ++v) {
      if (calling_thread && (v - vertex_begin) % 65536 == 65535)  // the calling thread's range stands for all
        report(static_cast<double>(v - vertex_begin) / static_cast<double>(vertex_end - vertex_begin));
      const auto first_result = static_cast<uint32_t>(results.size());
      blends.start[v] = first_result;
      const uint32_t begin = groups.start[v];
      const uint32_t end = groups.start[v + 1];
      if (begin == end) continue;
      at.clear();
      for (uint32_t i = begin; i < end; ++i) {
        const uint32_t corner = groups.corners[i];
        at.push_back({faces.normal[corner / 3], faces.corner_weight[corner], corner});
      }
      std::sort(at.begin(), at.end(),
                [](const CornerAt& a, const CornerAt& b) { return less_xyz(a.normal, b.normal); });
      distinct.clear();
      for (const CornerAt& a : at) {
        if (distinct.empty() || less_xyz(distinct.back().normal, a.normal)) distinct.push_back({a.normal, 0.0f});
        distinct.back().weight += a.weight;
      }
      // Each distinct normal blends those within the crease, always summed in the same order: where that is all
      // of them (a smooth vertex), its blend is the group's whole sum, kept once.
      Vec3 whole(0.0f);
      for (const Distinct& other : distinct) whole += other.weight * other.normal;
      const float whole_length = glm::length(whole);
      const bool whole_usable = whole_length > 1e-12f && std::isfinite(whole_length);
      const auto within = [&](const Distinct& a, const Distinct& b) {
        return glm::dot(a.normal, b.normal) >= cos_crease;
      };
      // Every pair within the crease, each pair tested once (the dot product is symmetric, bit for bit).
      bool all_pairs_within = true;
      for (size_t i = 0; i < distinct.size() && all_pairs_within; ++i)
        for (size_t j = i; j < distinct.size() && all_pairs_within; ++j)
          all_pairs_within = within(distinct[i], distinct[j]);
      uint32_t whole_slot = ~0u;
      slot.clear();
      for (const Distinct& d : distinct) {
        const bool all_within =
            all_pairs_within ||
            std::all_of(distinct.begin(), distinct.end(), [&](const Distinct& other) { return within(d, other); });
        if (all_within && whole_usable) {
          if (whole_slot == ~0u) {
            whole_slot = static_cast<uint32_t>(results.size()) - first_result;
            results.push_back(whole / whole_length);
          }
          slot.push_back(whole_slot);
          continue;
        }
        Vec3 sum(0.0f);
        for (const Distinct& other : distinct)
          if (within(d, other)) sum += other.weight * other.normal;
        const float length = glm::length(sum);
        slot.push_back(static_cast<uint32_t>(results.size()) - first_result);
        results.push_back((length > 1e-12f && std::isfinite(length)) ? sum / length : d.normal);
      }
      size_t k = 0;
      for (const CornerAt& a : at) {
        while (less_xyz(distinct[k].normal, a.normal)) ++k;
        scene.triangles[a.corner / 3].n[a.corner % 3] = slot[k];
      }
    }
  });
  std::vector<uint32_t> range_base(ranges.parts, 0);
  for (unsigned part = 1; part < ranges.parts; ++part)
    range_base[part] = range_base[part - 1] + static_cast<uint32_t>(range_normals[part - 1].size());
  blends.normals.resize(range_base.back() + range_normals.back().size());
  blends.start[vertex_count] = static_cast<uint32_t>(blends.normals.size());
  ranges.run(pool, [&](size_t vertex_begin, size_t vertex_end, unsigned part, bool) {
    std::copy(range_normals[part].begin(), range_normals[part].end(), blends.normals.begin() + range_base[part]);
    free_array(range_normals[part]);
    for (size_t v = vertex_begin; v < vertex_end; ++v) blends.start[v] += range_base[part];
  });
  return blends;
}

/// The ranges' interners joined in order, as one interner fed the ranges one after the other would have numbered
/// them. Returns the normals; renumber[part][i] becomes the index of the part's normal i among them. Each normal is
/// looked up in the earlier parts on every thread; only the numbering of the new ones runs in order.
std::vector<Vec3> join_interners(const std::vector<NormalInterner>& parts, std::vector<std::vector<uint32_t>>& renumber,
                                 ThreadPool& pool) {
  const size_t part_count = parts.size();
  renumber.assign(part_count, {});
  // first_part[p][i]: the first part holding part p's normal i (p itself when it is new there); renumber[p][i] its
  // index in that part until the numbering below.
  std::vector<std::vector<uint32_t>> first_part(part_count);
  constexpr size_t kSlice = 16384;
  std::vector<std::pair<uint32_t, size_t>> slices;
  for (uint32_t p = 0; p < part_count; ++p) {
    const size_t count = parts[p].normals.size();
    renumber[p].resize(count);
    first_part[p].resize(count);
    for (size_t begin = 0; begin < count; begin += kSlice) slices.emplace_back(p, begin);
  }
  const auto for_each_slice = [&](const auto& work) {
    pool.parallel_for(static_cast<int>(slices.size()), [&](int slice, int) {
      const auto [p, begin] = slices[static_cast<size_t>(slice)];
      const size_t end = std::min(begin + kSlice, parts[p].normals.size());
      for (size_t i = begin; i < end; ++i) work(p, i);
    });
  };
  for_each_slice([&](uint32_t p, size_t i) {
    uint32_t owner = p;
    auto index = static_cast<uint32_t>(i);
    for (uint32_t q = 0; q < p; ++q) {
      const uint32_t found = parts[q].find(parts[p].normals[i]);
      if (found != NormalInterner::kNotFound) {
        owner = q;
        index = found;
        break;
      }
    }
    first_part[p][i] = owner;
    renumber[p][i] = index;
  });
  std::vector<Vec3> joined;
  for (uint32_t p = 0; p < part_count; ++p)
    for (size_t i = 0; i < parts[p].normals.size(); ++i)
      if (first_part[p][i] == p) {
        renumber[p][i] = static_cast<uint32_t>(joined.size());
        joined.push_back(parts[p].normals[i]);
      }
  // A normal seen before takes the index its first part's copy got above (that copy was new there).
  for_each_slice([&](uint32_t p, size_t i) {
    if (first_part[p][i] != p) renumber[p][i] = renumber[first_part[p][i]][renumber[p][i]];
  });
  return joined;
}

/// Interns the blends group by group in the positions' sorted order; returns each blend's index in `normals`.
HugePageVector<uint32_t> intern_blends(const Blends& blends, const Weld& weld, std::vector<Vec3>& normals,
                                       ThreadPool& pool) {
  HugePageVector<uint32_t> index(blends.normals.size());
  const Ranges ranges(weld.sorted.size(), pool);
  std::vector<NormalInterner> interners;
  // Sized for one normal a group (a smooth mesh), so that the tables rarely grow.
  for (unsigned part = 0; part < ranges.parts; ++part) interners.emplace_back(ranges.end(part) - ranges.begin(part));
  ranges.run(pool, [&](size_t begin, size_t end, unsigned part, bool) {
    // Groups in sorted order are scattered over the blends, and each look-up lands anywhere in the table: the
    // group's start, its first blend and that blend's slot are fetched some groups ahead, so that their misses
    // overlap instead of following one another.
    const auto group = [&](size_t k) { return weld.sorted[std::min(k, end - 1)]; };
    const auto has_blends = [&](uint32_t v) { return blends.start[v] < blends.start[v + 1]; };
    for (size_t k = begin; k < end; ++k) {
      __builtin_prefetch(&blends.start[group(k + 24)]);
      if (const uint32_t ahead = group(k + 12); has_blends(ahead))
        __builtin_prefetch(&blends.normals[blends.start[ahead]]);
      if (const uint32_t ahead = group(k + 6); has_blends(ahead))
        interners[part].prefetch(blends.normals[blends.start[ahead]]);
      const uint32_t v = weld.sorted[k];
      for (uint32_t b = blends.start[v]; b < blends.start[v + 1]; ++b)
        index[b] = interners[part].intern(blends.normals[b]);
    }
  });
  std::vector<std::vector<uint32_t>> renumber;
  normals = join_interners(interners, renumber, pool);
  interners.clear();
  // The first range's indices are already the joined ones (all its normals are new there, in order).
  ranges.run(pool, [&](size_t begin, size_t end, unsigned part, bool) {
    if (part == 0) return;
    for (size_t k = begin; k < end; ++k) {
      const uint32_t v = weld.sorted[k];
      for (uint32_t b = blends.start[v]; b < blends.start[v + 1]; ++b) index[b] = renumber[part][index[b]];
    }
  });
  return index;
}

}  // namespace

void compute_smooth_normals(Scene& scene, float crease_degrees, unsigned threads,
                            const std::function<void(double done)>& progress) {
  ThreadPool pool(static_cast<int>(threads));
  // Reported at the end of each step by the rough share of the time up to there; the groups, group by group.
  const auto report = [&](double done) {
    if (progress) progress(done);
  };
  const float crease = std::clamp(std::isfinite(crease_degrees) ? crease_degrees : 60.0f, 0.0f, 180.0f);
  // The small slack lets faces with the same normal (dot rounding to just under 1) join even at crease 0.
  const float cos_crease = std::cos(crease * kPi / 180.0f) - 1e-6f;

  Faces faces = measure_faces(scene, pool);
  report(0.15);
  const Weld weld = weld_positions(scene.positions, pool);
  report(0.3);
  CornerGroups groups = group_corners(scene, weld, faces);
  report(0.4);
  for (Triangle& tri : scene.triangles) tri.n[0] = tri.n[1] = tri.n[2] = kNoNormal;
  Blends blends = blend_groups(scene, faces, groups, cos_crease, pool, [&](double done) { report(0.4 + 0.35 * done); });
  // What the interning does not need goes before its tables are made (this pass can be a load's peak).
  free_array(groups.corners);
  free_array(groups.start);
  free_array(faces.normal);
  free_array(faces.corner_weight);
  report(0.75);
  const HugePageVector<uint32_t> blend_index = intern_blends(blends, weld, scene.normals, pool);
  report(0.9);
  // Each corner's place within its group becomes its blend's index.
  Ranges(scene.triangles.size(), pool).run(pool, [&](size_t begin, size_t end, unsigned, bool) {
    for (size_t t = begin; t < end; ++t) {
      Triangle& tri = scene.triangles[t];
      if (tri.n[0] == kNoNormal) continue;  // a face without a normal takes no part
      for (uint32_t c = 0; c < 3; ++c) tri.n[c] = blend_index[blends.start[weld.representative[tri.v[c]]] + tri.n[c]];
    }
  });
  release_free_memory();
}

}  // namespace lueur
