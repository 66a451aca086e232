// The L1 store's cells, keys and shards.
#include "store/l1_cache.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "core/rng.h"

namespace lueur {
namespace {

constexpr size_t kFirstShardCells = 1024;  // 32 KB per shard before the first growth

/// A shard grows (doubles) once it is half full, and at its largest stops taking new cells there: linear probing
/// then averages 2.5 slots for a key that is not there (8.5 at three-quarters full, where look-ups took 11% of a
/// frame).
bool over_load(uint64_t used, size_t capacity) { return 2 * used > static_cast<uint64_t>(capacity); }

/// 2^exponent built from its bits, for |exponent| <= 126 (here a cell level, 0..40): no call into libm.
float power_of_two(int exponent) { return std::bit_cast<float>(static_cast<uint32_t>(127 + exponent) << 23); }

}  // namespace

int L1CacheGrid::level_at(const Vec3& position) const {
  // The distance, not the depth: bounce hits behind the camera need cells as well (of the size they would have in
  // front of it). The level is round(log2(r)) for the ratio r = size / base_size, found without a square root or a
  // logarithm (this runs at every bounce hit): round(log2 r) = floor((1 + log2 r^2) / 2), and floor(log2 x) is the
  // exponent of the float x.
  const Vec3 to_eye = position - eye;
  const float ratio2 = glm::dot(to_eye, to_eye) * ratio_per_distance * ratio_per_distance;
  const float twice = 2.0f * ratio2;
  if (!(twice > 2.0f)) return 0;  // r <= 1, and a NaN position (a degenerate hit): the smallest cells
  if (!(twice < 0x1p81f)) return 40;
  const int exponent = static_cast<int>((std::bit_cast<uint32_t>(twice) >> 23) & 0xffu) - 127;
  return exponent / 2;
}

float L1CacheGrid::size_of(int level) const { return base_size * power_of_two(level); }

L1CacheKey L1CacheGrid::key(const Vec3& position, const Vec3& normal, int level) const {
  const float inv = inverse_base_size * power_of_two(-level);  // 1 / size_of(level), without a division
  const Vec3 cell = glm::floor((position - origin) * inv);
  // Surface points lie in the scene's box (cells past it by a jitter at most): far inside int32's range.
  const auto coordinate = [](float c) {
    return std::isnan(c) ? int32_t{0} : static_cast<int32_t>(std::clamp(c, -1073741824.0f, 1073741824.0f));
  };
  L1CacheKey k;
  k.x = coordinate(cell.x);
  k.y = coordinate(cell.y);
  k.z = coordinate(cell.z);
  k.level = static_cast<uint8_t>(level);
  k.normal = normal_bucket(normal);
  return k;
}

L1CacheGrid make_l1_cache_grid(const Camera& camera, const Vec3& lower, float diagonal, float cell_pixels,
                               int generation) {
  L1CacheGrid grid;
  grid.origin = lower;
  grid.base_size = std::max(diagonal, 1e-6f) * 0x1p-20f;
  grid.eye = camera.eye;
  grid.pixel_per_depth = 2.0f * camera.tan_half_fovy / static_cast<float>(std::max(camera.height, 1));
  grid.cell_pixels = cell_pixels;
  grid.generation = generation;
  grid.inverse_base_size = 1.0f / grid.base_size;
  grid.ratio_per_distance = cell_pixels * grid.pixel_per_depth * std::ldexp(1.0f, -generation) / grid.base_size;
  return grid;
}

L1CacheKey jittered_key(const L1CacheGrid& grid, const Vec3& position, const Vec3& normal, float u1, float u2) {
  const int level = grid.level_at(position);
  const float size = grid.size_of(level);
  const Frame frame = Frame::from_normal(normal);
  const Vec3 moved = position + ((u1 - 0.5f) * size) * frame.tangent + ((u2 - 0.5f) * size) * frame.bitangent;
  return grid.key(moved, normal, level);
}

uint8_t normal_bucket(const Vec3& n) {
  const Vec3 a = glm::abs(n);
  const int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
  return static_cast<uint8_t>(2 * axis + (n[axis] < 0.0f ? 1 : 0));
}

uint64_t hash_of(const L1CacheKey& key) {
  const uint64_t xy = (static_cast<uint64_t>(static_cast<uint32_t>(key.x)) << 32) | static_cast<uint32_t>(key.y);
  const uint64_t z_rest = (static_cast<uint64_t>(static_cast<uint32_t>(key.z)) << 32) |
                          (static_cast<uint64_t>(key.level) << 8) | key.normal;
  return hash_combine(mix64(xy), z_rest);
}

uint32_t ServedSamples::percentile(double q) const {
  if (total == 0) return 0;
  const auto wanted = static_cast<uint64_t>(q * static_cast<double>(total));
  uint64_t below = 0;
  for (size_t i = 0; i < counts.size(); ++i) {
    below += counts[i];
    if (below > wanted) {
      const int octave = static_cast<int>(i) / kPerOctave;
      const uint32_t part = static_cast<uint32_t>(i) % kPerOctave;
      return octave >= 3 ? (8u + part) << (octave - 3) : (8u + part) >> (3 - octave);
    }
  }
  return 0;
}

int l1_cache_generation(uint64_t frame) {
  int generation = 0;
  for (uint64_t start = 4; frame >= start && generation < 30; start *= 8) ++generation;
  return generation;
}

void L1Cache::reset(uint64_t max_bytes) {
  const uint64_t cells = max_bytes / sizeof(L1CacheCell) / kShards;
  max_cells_per_shard_ = cells == 0 ? 0 : std::bit_floor(static_cast<size_t>(cells));
  clear();
  generation = -1;
}

void L1Cache::write_state(ByteWriter& out) const {
  out.put<int32_t>(generation);
  out.put<uint64_t>(max_cells_per_shard_);
  for (const Shard& shard : shards_) {
    out.put<uint64_t>(shard.used);
    out.put<uint64_t>(shard.refused);
    out.put_array(shard.cells);
  }
}

void L1Cache::read_state(ByteReader& in) {
  generation = in.get<int32_t>("the L1 store");
  max_cells_per_shard_ = in.get<uint64_t>("the L1 store");
  if (max_cells_per_shard_ != 0 && !std::has_single_bit(max_cells_per_shard_))
    throw ByteStreamError("an impossible L1 store");
  for (Shard& shard : shards_) {
    shard.used = in.get<uint64_t>("the L1 store");
    shard.refused = in.get<uint64_t>("the L1 store");
    shard.cells = in.get_array<L1CacheCell>(max_cells_per_shard_, "the L1 store");
    if (!shard.cells.empty() && !std::has_single_bit(shard.cells.size()))
      throw ByteStreamError("an impossible L1 store");
    // A full table would make find() probe forever: the count must be true and leave an empty slot.
    const auto filled =
        std::count_if(shard.cells.begin(), shard.cells.end(), [](const L1CacheCell& c) { return c.samples != 0; });
    if (static_cast<uint64_t>(filled) != shard.used || (!shard.cells.empty() && shard.used >= shard.cells.size()))
      throw ByteStreamError("an impossible L1 store");
  }
}

void L1Cache::clear() {
  for (Shard& s : shards_) s = Shard{};
}

void L1Cache::rehash(Shard& shard, size_t capacity) {
  std::vector<L1CacheCell> old = std::move(shard.cells);
  shard.cells.assign(capacity, L1CacheCell{});
  const size_t mask = capacity - 1;
  for (const L1CacheCell& cell : old) {
    if (cell.samples == 0) continue;
    size_t slot = hash_of(cell.key) & mask;
    while (shard.cells[slot].samples != 0) slot = (slot + 1) & mask;
    shard.cells[slot] = cell;
  }
}

void L1Cache::insert(Shard& shard, const L1CacheRecord& record) {
  if (record.samples == 0 || max_cells_per_shard_ == 0) return;
  if (shard.cells.empty()) rehash(shard, std::min(kFirstShardCells, max_cells_per_shard_));
  size_t mask = shard.cells.size() - 1;
  size_t slot = record.hash & mask;
  for (; shard.cells[slot].samples != 0; slot = (slot + 1) & mask) {
    if (shard.cells[slot].key == record.key) {
      shard.cells[slot].sum += record.sum;
      shard.cells[slot].samples += record.samples;
      return;
    }
  }
  // A new cell: refused once the shard is full and as large as the cap allows, else grow first if it is getting full.
  if (refuses_new_cell_in(shard)) {
    ++shard.refused;
    return;
  }
  if (over_load(shard.used + 1, shard.cells.size())) {
    rehash(shard, shard.cells.size() * 2);
    mask = shard.cells.size() - 1;
    for (slot = record.hash & mask; shard.cells[slot].samples != 0;) slot = (slot + 1) & mask;
  }
  shard.cells[slot] = L1CacheCell{record.key, record.samples, record.sum};
  ++shard.used;
}

bool L1Cache::refuses_new_cell_in(const Shard& shard) const {
  if (max_cells_per_shard_ == 0) return true;
  // An empty shard gets its first slots before its first cell; one that a new cell would bring over its load grows,
  // unless growing would pass the cap.
  const size_t capacity = shard.cells.empty() ? std::min(kFirstShardCells, max_cells_per_shard_) : shard.cells.size();
  return over_load(shard.used + 1, capacity) && capacity * 2 > max_cells_per_shard_;
}

bool L1Cache::refuses_new_cell(uint64_t hash) const { return refuses_new_cell_in(shards_[shard_of(hash)]); }

void L1Cache::merge(const std::vector<std::vector<L1CacheRecord>>& batches, ThreadPool& pool) {
  // First each batch's records listed by shard (batches in parallel), so that a shard's task reads only its own
  // records, in the order the batches hold them, and can start loading the slot of a record a few ahead.
  std::vector<std::vector<uint32_t>> by_shard(batches.size());
  std::vector<std::array<uint32_t, kShards + 1>> starts(batches.size());
  pool.parallel_for(static_cast<int>(batches.size()), [&](int b, int) {
    const std::vector<L1CacheRecord>& batch = batches[static_cast<size_t>(b)];
    std::array<uint32_t, kShards + 1>& start = starts[static_cast<size_t>(b)];
    start.fill(0);
    for (const L1CacheRecord& r : batch) ++start[shard_of(r.hash) + 1];
    for (size_t s = 0; s < kShards; ++s) start[s + 1] += start[s];
    std::array<uint32_t, kShards> next;
    std::copy(start.begin(), start.end() - 1, next.begin());
    std::vector<uint32_t>& order = by_shard[static_cast<size_t>(b)];
    order.resize(batch.size());
    for (size_t i = 0; i < batch.size(); ++i) order[next[shard_of(batch[i].hash)]++] = static_cast<uint32_t>(i);
  });
  pool.parallel_for(kShards, [&](int s, int) {
    Shard& shard = shards_[static_cast<size_t>(s)];
    std::vector<const L1CacheRecord*> records;
    for (size_t b = 0; b < batches.size(); ++b)
      for (uint32_t j = starts[b][static_cast<size_t>(s)]; j < starts[b][static_cast<size_t>(s) + 1]; ++j)
        records.push_back(&batches[b][by_shard[b][j]]);
    constexpr size_t kAhead = 8;  // the slot loads in flight: enough to cover a miss to memory
    for (size_t i = 0; i < records.size(); ++i) {
      if (i + kAhead < records.size() && !shard.cells.empty())
        __builtin_prefetch(&shard.cells[records[i + kAhead]->hash & (shard.cells.size() - 1)], 1);
      insert(shard, *records[i]);
    }
  });
}

bool L1Cache::has_room_for_next_generation() const {
  const uint64_t cells = stats().cells;
  return 4 * cells <= static_cast<uint64_t>(kShards) * (max_cells_per_shard_ / 2);
}

L1CacheStats L1Cache::stats() const {
  L1CacheStats st;
  for (const Shard& s : shards_) {
    st.cells += s.used;
    st.bytes += s.cells.capacity() * sizeof(L1CacheCell);
    st.refused += s.refused;
  }
  st.full = st.refused > 0;
  return st;
}

uint64_t L1Cache::samples_held() const {
  uint64_t samples = 0;
  for (const Shard& s : shards_)
    for (const L1CacheCell& cell : s.cells) samples += cell.samples;
  return samples;
}

}  // namespace lueur
