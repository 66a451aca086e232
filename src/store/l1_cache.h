// A world-space store of L1 (the report's improvement II-B): a hashed grid of cells over the surfaces seen, each
// the running sum of the light arriving there (L1 without the BRDF) that L1 estimates found, so that L2 can take
// L1(q) where the screen never saw q (and, in cells of their own, ln's further light: kFurtherLight). Cells are keyed
// by quantised position, size level, the normal's direction and what they hold, hold their full key (a collision is
// a different key, never a merge), and live in open-addressed shards that grow with the surfaces seen up to a cap. A
// frame only reads the store; what it found is merged in at its end, in pixel order, so that the image does not depend
// on the thread count. This folder, store/, is the integrator's cache: it is kept beside the film
// (integrator/renderer.h: Accumulation), saved beside it in the resume state, and depends on core only (the camera, the
// thread pool, byte streams).
#pragma once

#include <array>
#include <bit>
#include <cstdint>
#include <vector>

#include "core/byte_stream.h"
#include "core/camera.h"
#include "core/math.h"
#include "core/rng.h"
#include "core/thread_pool.h"

namespace lueur {

/// Which cell a surface point falls in.
struct L1CacheKey {
  int32_t x = 0, y = 0, z = 0;  ///< the position over the cell size, floored
  uint8_t level = 0;            ///< the cell size is base_size x 2^level
  uint8_t normal = 0;           ///< the normal's dominant axis and sign: 0..5 (+x -x +y -y +z -z)
  /// What the cell holds (kL1Light, kFurtherLight). Left out of the hash: a place's two cells start their probes in
  /// the same slot, so that the look-up of one brings the other's slot into the cache.
  uint16_t light = 0;
  bool operator==(const L1CacheKey&) const = default;
};

/// What a cell holds: the sum of the arriving light of every sample merged into it, and their count (kL1Light:
/// shadow-ray samples of L1; kFurtherLight: paths that went on from the cell, kFurtherMinSamples).
struct L1CacheCell {
  L1CacheKey key;
  uint32_t samples = 0;  ///< 0: an empty slot
  Vec3 sum{0.0f};
};

/// One estimate on its way to the store: its cell, and its arriving light summed over its `samples` samples.
struct L1CacheRecord {
  L1CacheKey key;
  uint64_t hash = 0;
  Vec3 sum{0.0f};
  uint32_t samples = 0;
};

/// The record of an estimate whose light arriving, averaged over `samples` samples, was `arriving`.
inline L1CacheRecord make_l1_record(const L1CacheKey& key, uint64_t hash, const Vec3& arriving, uint32_t samples) {
  return L1CacheRecord{key, hash, arriving * static_cast<float>(samples), samples};
}

/// How surface points map to cells: a size that covers `cell_pixels` pixels at the point's distance from the camera
/// (as wide as that many pixels would be at that depth straight ahead),
/// rounded to a power of two of `base_size` (so that neighbouring points of a surface mostly share a level), and
/// halved per `generation`.
struct L1CacheGrid {
  Vec3 origin{0.0f};       ///< the scene's bounding box corner: cell coordinates count from there
  float base_size = 1.0f;  ///< the smallest cell: the scene's diagonal / 2^20
  Vec3 eye{0.0f};
  float pixel_per_depth = 1.0f;  ///< a pixel's width at unit depth
  float cell_pixels = 8.0f;
  int generation = 0;
  float inverse_base_size = 1.0f;
  float ratio_per_distance = 1.0f;  ///< a point's cell size over base_size, per unit of distance from the eye

  /// The cell level at `position`, and the size of its cells.
  int level_at(const Vec3& position) const;
  float size_of(int level) const;
  /// The key of the cell of `level` that holds `position`, on the side `normal` faces.
  L1CacheKey key(const Vec3& position, const Vec3& normal, int level) const;
};

/// The grid of a frame: cells of `cell_pixels` pixels at their distance from `camera`, halved `generation` times,
/// counted from the scene's corner `lower` in powers of two of its `diagonal` / 2^20.
L1CacheGrid make_l1_cache_grid(const Camera& camera, const Vec3& lower, float diagonal, float cell_pixels,
                               int generation);

/// The key of a jittered look-up or feed at a surface point: the position moved uniformly across one cell, in the
/// plane of its normal (u1, u2 in [0, 1)), so that the grid shows as noise rather than as blocks (Binder, Fricke and
/// Keller 2018). The level is that of the point itself.
L1CacheKey jittered_key(const L1CacheGrid& grid, const Vec3& position, const Vec3& normal, float u1, float u2);

/// A cell serves look-ups once it holds this many samples of arriving light (below, L1 is traced and added to it).
/// Chosen with small cells (the automatic size, passes/render_settings.h) by measuring L2's error split into bias and
/// noise on the conference room and the default scene: most of the store's error was its cells' bias, not their
/// noise, so smaller cells that become ready sooner pay for their noisier start (the figures: BENCHMARKS.md and the
/// commit that set this constant).
inline constexpr uint32_t kL1CacheMinSamples = 16;

/// The shadow rays of an L1(q) traced at a bounce hit whose cell is not ready (in the store modes, instead of the
/// recompute ratio's share): two such estimates make the cell ready. At the ratio's 2 rays a cell would take 8 hits
/// to fill, each paying a recomputation and taking its noisier L1; the rays a cell gathers before it serves are the
/// same, spent in fewer hits, so more of the hits after them are served. Measured on the conference room: larger
/// fills served more of the hits and lowered L2's error, with diminishing returns past half of kL1CacheMinSamples.
inline constexpr int kL1CacheFillRays = static_cast<int>(kL1CacheMinSamples) / 2;

/// The share of the hits on a ready cell that trace L1 anew and feed it rather than read it (drawn from the
/// pixel's look-up numbers, so that the image stays a pure function of the settings): without them a cell that
/// only bounce rays reach (behind the camera, under a table) would keep its first kL1CacheMinSamples samples, and
/// their error, for its whole generation. With a fixed share a cell's samples grow as the frames do, and its error
/// falls as theirs. Chosen by L2's error after equal time (BENCHMARKS.md, "The L1 store by frames").
inline constexpr float kL1CacheLearningShare = 0.0625f;

/// What a cell holds (L1CacheKey::light): the light arriving by shadow rays (L1), or by two or more further bounces.
inline constexpr uint16_t kL1Light = 0;
inline constexpr uint16_t kFurtherLight = 1;

/// ln's paths and the store (the modes that read it): at a path's first bounce hit q, one bounce after a pixel's
/// surface seen directly, where q's BRDF is the same toward every direction, a cell that holds the further light of
/// this many paths (the light reaching q by two or more further bounces: all that ln adds past q, without q's BRDF)
/// gives their average, and the path ends there. Below it, and at kFurtherLearningShare of the hits on a ready cell,
/// the path goes on as without a store and feeds the cell the light it found past q over its throughput there, so
/// that every cell keeps learning; the cells shrink with the generations, as for L1, so their blur goes to nothing.
/// Chosen by the time ln's error takes to reach `off`'s after 60 s on the conference room (`--sections store-ln`): 4
/// and 8 did as well, 16 and 32 left more paths going on while their cells gathered.
inline constexpr uint32_t kFurtherMinSamples = 8;

/// The share of the hits on a cell with further light ready whose paths go on and feed it (measured as above: 1/32
/// did as well, 1/8 worse).
inline constexpr float kFurtherLearningShare = 0.0625f;

/// The normal's dominant axis and sign, 0..5: surfaces that face apart (the two sides of a wall; a floor and the wall
/// beside it) never share a cell.
uint8_t normal_bucket(const Vec3& normal);

uint64_t hash_of(const L1CacheKey& key);

/// The generation of frame `frame`: 0 for frames 0-3, then one more per 8x frames (4-31, 32-255, 256-2047, ...). Each
/// halves the cells' size, so that the store's blur shrinks to nothing as the frames accumulate (as frames^-1/3).
/// Measured on the default scene and the conference room (128x128, 15 s per mode): halving per 4x frames left most
/// cells cold for most of their generation (a cell is asked about as often per generation at every size, but must
/// first gather its kL1CacheMinSamples samples), and `screen+cache` rendered fewer frames than `frame`; per 16x frames the cells'
/// blur cost the conference room's L2 more than their noise saved; per 8x was best on both.
int l1_cache_generation(uint64_t frame);

struct L1CacheStats {
  uint64_t cells = 0;    ///< cells in use
  uint64_t bytes = 0;    ///< memory held by the shards
  uint64_t refused = 0;  ///< records of new cells dropped because the store had reached its cap (this generation)
  bool full = false;     ///< the cap has been reached
};

/// How many samples the cells held that served bounce hits: a histogram in eighths of an octave (within 9%), for
/// the statistics of the panel and the benchmarks, not for rendering.
struct ServedSamples {
  static constexpr int kPerOctave = 8;
  std::array<uint64_t, 32 * kPerOctave> counts{};
  uint64_t total = 0;
  void add(uint32_t samples) {
    if (samples == 0) return;
    const int octave = std::bit_width(samples) - 1;
    // The kPerOctave-th parts of the octave: the bits after the leading one.
    const uint32_t part = octave >= 3 ? (samples >> (octave - 3)) & 7u : (samples << (3 - octave)) & 7u;
    ++counts[static_cast<size_t>(kPerOctave * octave) + part];
    ++total;
  }
  void add(const ServedSamples& other) {
    for (size_t i = 0; i < counts.size(); ++i) counts[i] += other.counts[i];
    total += other.total;
  }
  /// The samples of the cell below which a share q of the served hits fell (the lower end of its eighth of an
  /// octave); 0 when none was served.
  uint32_t percentile(double q) const;
};

class L1Cache;

/// What one pixel's L2 needs of the store in a frame: the store as the previous frame left it, the frame's grid,
/// the pixel's jitter numbers, and where its new L1 estimates go.
struct L1CacheAccess {
  const L1Cache* store = nullptr;
  const L1CacheGrid* grid = nullptr;
  Pcg32* jitter = nullptr;
  std::vector<L1CacheRecord>* records = nullptr;
  ServedSamples* served = nullptr;  ///< where the samples of each cell that serves a hit are counted (may be null)
};

class L1Cache {
 public:
  static constexpr int kShards = 16;

  /// Empties the store and sets its cap (0: the store stays empty and refuses everything).
  void reset(uint64_t max_bytes);
  /// Empties the store, keeping its cap.
  void clear();

  /// The cell with this key, or null. (Here, to be inlined: it runs at most bounce hits.)
  const L1CacheCell* find(const L1CacheKey& key, uint64_t hash) const {
    const Shard& shard = shards_[shard_of(hash)];
    if (shard.cells.empty()) return nullptr;
    const size_t mask = shard.cells.size() - 1;
    for (size_t slot = hash & mask;; slot = (slot + 1) & mask) {
      const L1CacheCell& cell = shard.cells[slot];
      if (cell.samples == 0) return nullptr;
      if (cell.key == key) return &cell;
    }
  }
  /// Starts loading the slot where `find` begins for this hash.
  void prefetch(uint64_t hash) const {
    const Shard& shard = shards_[shard_of(hash)];
    if (!shard.cells.empty()) __builtin_prefetch(&shard.cells[hash & (shard.cells.size() - 1)]);
  }
  /// The shard a hash belongs to: its top four bits.
  static size_t shard_of(uint64_t hash) { return static_cast<size_t>(hash >> 60); }
  static_assert(kShards == 16);

  /// Whether a record of a cell not yet in the store, with this hash, would be refused: its shard is as large as the
  /// cap allows and too full to take one more. (A bounce hit whose cell is missing then traces no fill: its record
  /// would be dropped.)
  bool refuses_new_cell(uint64_t hash) const;

  /// Adds the records, batch after batch and each batch in order; one shard per task on `pool`.
  void merge(const std::vector<std::vector<L1CacheRecord>>& batches, ThreadPool& pool);

  /// Whether the next generation's cells, half the size and so about four times as many, would fit under the cap
  /// (a shard takes cells up to half its largest table). Where they would not, the store keeps its generation:
  /// most of the next one's cells would be refused, and their hits traced as without a store.
  bool has_room_for_next_generation() const;

  L1CacheStats stats() const;
  /// The samples its cells hold, summed: a scan of every slot, for tests and tools (not per frame).
  uint64_t samples_held() const;
  /// The store's whole state, slot for slot, appended to a byte stream (a resumed render goes on with the same
  /// store), and read back; reading throws ByteStreamError if the stream is cut short or impossible.
  void write_state(ByteWriter& out) const;
  void read_state(ByteReader& in);
  int generation = -1;  ///< the generation whose cells the store holds (-1: none yet)

 private:
  struct Shard {
    std::vector<L1CacheCell> cells;  ///< a power of two slots, or none
    uint64_t used = 0;
    uint64_t refused = 0;
  };
  void insert(Shard& shard, const L1CacheRecord& record);
  /// The one rule by which insert() refuses a new cell, and refuses_new_cell() foretells it.
  bool refuses_new_cell_in(const Shard& shard) const;
  static void rehash(Shard& shard, size_t capacity);

  std::array<Shard, kShards> shards_;
  size_t max_cells_per_shard_ = 0;
};

/// What a hit on the cell `key` does with the store: reads the cell (it holds `ready` samples, and this hit is not
/// one of the learning share), feeds it (traces its estimate and adds a record: the cell is missing, not ready, or
/// this hit is one of `learning_share`), or only traces (a missing cell that the full store would refuse). Draws one
/// of the pixel's look-up numbers where the cell is ready.
enum class StoreUse { kRead, kFeed, kTrace };
inline StoreUse use_of_cell(const L1CacheAccess& access, const L1CacheKey& key, uint64_t hash, uint32_t ready,
                            float learning_share, const L1CacheCell*& cell) {
  cell = access.store->find(key, hash);
  if (!cell) return access.store->refuses_new_cell(hash) ? StoreUse::kTrace : StoreUse::kFeed;
  if (cell->samples < ready) return StoreUse::kFeed;
  if (access.jitter->next_float() < learning_share) return StoreUse::kFeed;
  return StoreUse::kRead;
}

/// For L1 at a bounce hit: a fill traces kL1CacheFillRays; a read counts among the served samples.
inline StoreUse use_of_store(const L1CacheAccess& access, const L1CacheKey& key, uint64_t hash,
                             const L1CacheCell*& cell) {
  const StoreUse use = use_of_cell(access, key, hash, kL1CacheMinSamples, kL1CacheLearningShare, cell);
  if (use == StoreUse::kRead && access.served) access.served->add(cell->samples);
  return use;
}

/// For the further light at ln's first bounce hit, whose cell's key has kFurtherLight: a read ends the path, a feed
/// lets it go on and turns what it found into a record.
inline StoreUse further_use_of_store(const L1CacheAccess& access, const L1CacheKey& key, uint64_t hash,
                                     const L1CacheCell*& cell) {
  return use_of_cell(access, key, hash, kFurtherMinSamples, kFurtherLearningShare, cell);
}

}  // namespace lueur
