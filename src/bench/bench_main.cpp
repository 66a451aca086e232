// lueur-bench: Lueur's BVH against Embree on the same rays (throughput, build time, memory), and time to quality
// of the light-sampling strategies and L2 reuse modes. Prints a table; --json FILE writes every figure.
// Not part of the tests' pass or fail: the figures depend on the machine.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>

#include "bench/bench_convergence.h"
#include "bench/bench_frame.h"
#include "bench/bench_rays.h"
#include "bench/bench_scenes.h"
#include "bench/bench_store.h"
#include "bench/bench_store_frames.h"
#include "bench/bench_store_ln.h"
#include "bench/bench_throughput.h"
#include "core/atomic_file.h"
#include "scene/obj_loader.h"
#include "settings/cli_check.h"
#include "settings/setting_table.h"

namespace lueur::bench {
namespace {

using Json = nlohmann::ordered_json;

// Builds of each back-end per scene, alternating; the fastest counts. Three for every scene: a single build of the
// 2M-triangle field varied by 30% between runs on a shared machine.
constexpr int kBuildRepeats = 3;

struct BenchOptions {
  bool quick = false;
  bool smoke = false;
  std::string json_path;
  std::string only;  ///< when set: only the scenes whose name contains it
  int rounds = 0;    ///< when set: alternating timing rounds
  std::string scenes_dir = LUEUR_SHARED_SCENES;
  std::set<std::string> sections = {"build", "throughput", "convergence"};
  int ray_size = 512;          ///< rays are generated for a ray_size x ray_size view
  double frame_seconds = 5.0;  ///< the renderer's frames per scene and thread count, over all rounds (section frame)
  TimingOptions timing;
  ConvergenceOptions convergence;
  StoreOptions store;
  StoreFramesOptions store_frames;
  StoreLnOptions store_ln;
};

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::optional<BenchOptions> parse(int argc, char** argv) {
  BenchOptions o;
  CLI::App app{"lueur-bench: Lueur's BVH against Embree on the same rays, and time to quality", "lueur-bench"};
  std::string sections;
  int reference_frames = 0, convergence_size = 0;
  double convergence_seconds = 0.0, store_seconds = 0.0, store_reference_seconds = 0.0, store_turn_seconds = 0.0;
  int store_size = 0;
  float store_cell_pixels = -1.0f;
  std::string store_conference_light;
  uint64_t store_frames = 0, store_frames_reference = 0;
  int store_frames_size = 0;
  std::vector<std::string> store_frames_modes;
  app.add_flag("--quick", o.quick, "a reduced set that runs in under a minute");
  app.add_flag("--smoke", o.smoke, "a tiny run that only checks the plumbing (seconds; for the test suite)");
  app.add_option("--json", o.json_path, "write every figure to FILE as JSON")->type_name("FILE");
  app.add_option("--scenes", o.scenes_dir, "folder of the shared scenes (default: ../shared/scenes of the source)")
      ->type_name("DIR");
  app.add_option("--only", o.only, "only the scenes whose name contains this text")->type_name("TEXT");
  app.add_option("--rounds", o.rounds, "alternating timing rounds per figure (default 5; the median is kept)")
      ->type_name("N")
      ->check(checked_by(whole_number_error, {1, 1000}));
  app.add_option(
         "--sections", sections,
         "comma-separated: build,throughput,convergence (default), traversal (nodes per ray), frame (the "
         "renderer's rays per second against the same rays in the benchmark's arrays), store (the reuse "
         "modes and the L1 store raced on the default scene and the conference room), store-frames (L2's error by "
         "frames per reuse mode on those and a closed room facing a wall), store-ln (ln's error by time with and "
         "without the L1 store on the conference room and CornellBox-Original)")
      ->type_name("LIST");
  app.add_option("--store-seconds", store_seconds,
                 "equal time per reuse mode in sections store and store-ln (default 60)")
      ->type_name("SECONDS")
      ->check(checked_by(finite_number_error, {0.001, 100000.0}));
  app.add_option("--store-reference-seconds", store_reference_seconds,
                 "time of each reference in sections store (default 240) and store-ln (default 120)")
      ->type_name("SECONDS")
      ->check(checked_by(finite_number_error, {0.001, 100000.0}));
  app.add_option("--store-turn-seconds", store_turn_seconds,
                 "the reuse modes of section store take turns of this long, each on its own frames' clock (default 2)")
      ->type_name("SECONDS")
      ->check(checked_by(finite_number_error, {0.001, 100000.0}));
  app.add_option("--store-size", store_size,
                 "image side in pixels in sections store (default 256) and store-ln (default 64)")
      ->type_name("PIXELS")
      ->check(checked_by(whole_number_error, {8, 8192}));
  app.add_option("--store-cell-pixels", store_cell_pixels,
                 "the L1 store's cell size in section store, as --cache-cell-pixels (default 0: automatic)")
      ->type_name("X")
      ->check(checked_by(finite_number_error, {0.0, 1024.0}));
  app.add_option("--store-conference-light", store_conference_light,
                 "the conference room's light in section store: bench (the benchmark's small ceiling light, the "
                 "default) or rig (the panel of Lueur's default light rig, as the viewer lights the room)")
      ->type_name("bench|rig")
      ->check(CLI::IsMember({"bench", "rig"}));
  app.add_option("--store-frames", store_frames, "frames per reuse mode in section store-frames (default 4096)")
      ->type_name("N")
      ->check(checked_by(whole_number_error, {64, 1 << 20}));
  app.add_option("--store-frames-reference", store_frames_reference,
                 "frames of each of the two references in section store-frames (default 8192)")
      ->type_name("N")
      ->check(checked_by(whole_number_error, {1, 1 << 22}));
  app.add_option("--store-frames-references", o.store_frames.reference_dir,
                 "keep section store-frames' references in DIR and read them from there when present")
      ->type_name("DIR");
  app.add_option("--store-frames-modes", store_frames_modes,
                 "the reuse modes of section store-frames (default off,frame,cache,screen+cache)")
      ->type_name("LIST")
      ->delimiter(',')
      ->check(CLI::IsMember({"off", "frame", "average", "cache", "screen+cache"}));
  app.add_option("--store-frames-size", store_frames_size, "image side in pixels in section store-frames (default 64)")
      ->type_name("PIXELS")
      ->check(checked_by(whole_number_error, {8, 8192}));
  app.add_option("--reference-frames", reference_frames, "frames of each convergence reference (default 128)")
      ->type_name("N")
      ->check(checked_by(whole_number_error, {1, 100000}));
  app.add_option("--convergence-seconds", convergence_seconds, "equal time per convergence variant (default 20)")
      ->type_name("SECONDS")
      ->check(checked_by(finite_number_error, {0.001, 100000.0}));
  app.add_option("--convergence-size", convergence_size, "convergence image side in pixels (default 512)")
      ->type_name("PIXELS")
      ->check(checked_by(whole_number_error, {8, 8192}));
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::printf("%s", app.help().c_str());
    return std::nullopt;
  } catch (const CLI::ParseError& e) {
    std::string message = e.what();
    if (const size_t nl = message.find('\n'); nl != std::string::npos) message.resize(nl);
    throw UsageError(message);
  }
  if (!sections.empty()) {
    o.sections.clear();
    std::istringstream in(sections);
    std::string name;
    while (std::getline(in, name, ',')) {
      if (name != "build" && name != "throughput" && name != "traversal" && name != "convergence" && name != "frame" &&
          name != "store" && name != "store-frames" && name != "store-ln")
        throw UsageError("--sections: '" + name +
                         "' is not one of build|throughput|traversal|convergence|frame|store|store-frames|store-ln");
      o.sections.insert(name);
    }
  }
  if (o.quick) {
    o.ray_size = 192;
    o.frame_seconds = 0.5;
    o.timing = {0.1, 3};
    o.convergence = {128, 128, 32, 1.5, 0, 1};
    o.store = {128, 5.0, 20.0, 1.0, 0};
  }
  if (o.smoke) {
    o.ray_size = 24;
    o.frame_seconds = 0.0;
    o.timing = {0.001, 1};
    o.convergence = {16, 16, 2, 0.001, 0, 1};
    o.store = {16, 0.02, 0.05, 0.01, 0};
    o.store_frames.size = 8;
    o.store_ln = {8, 0.05, 0.02, 0.01, 0};
    o.store_frames.frames = 64;
    o.store_frames.reference_frames = 16;
    o.scenes_dir.clear();
  }
  if (o.rounds > 0) o.timing.rounds = o.rounds;
  if (reference_frames > 0) o.convergence.reference_frames = reference_frames;
  if (convergence_seconds > 0.0) o.convergence.seconds = convergence_seconds;
  if (convergence_size > 0) o.convergence.width = o.convergence.height = convergence_size;
  if (store_seconds > 0.0) o.store.seconds = o.store_ln.seconds = store_seconds;
  if (store_reference_seconds > 0.0) o.store_ln.reference_seconds = store_reference_seconds;
  if (store_size > 0) o.store_ln.size = store_size;
  if (store_reference_seconds > 0.0) o.store.reference_seconds = store_reference_seconds;
  if (store_size > 0) o.store.size = store_size;
  if (store_turn_seconds > 0.0) o.store.turn_seconds = store_turn_seconds;
  if (store_cell_pixels >= 0.0f) o.store.cell_pixels = store_cell_pixels;
  o.store.conference_rig = store_conference_light == "rig";
  if (store_frames > 0) o.store_frames.frames = store_frames;
  if (store_frames_reference > 0) o.store_frames.reference_frames = store_frames_reference;
  if (store_frames_size > 0) o.store_frames.size = store_frames_size;
  if (!store_frames_modes.empty()) {
    o.store_frames.modes.clear();
    for (const std::string& name : store_frames_modes)
      o.store_frames.modes.push_back(*enum_from_name<ReuseMode>(kReuseModeNames, name));
  }
  if (!o.json_path.empty()) {
    std::filesystem::path dir = std::filesystem::path(o.json_path).parent_path();
    if (dir.empty()) dir = ".";
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec))
      throw UsageError("--json: cannot write '" + o.json_path + "': no directory '" + dir.string() + "'");
  }
  return o;
}

std::vector<Vec3> corners_of(const Scene& scene) {
  std::vector<Vec3> corners;
  corners.reserve(3 * scene.triangles.size());
  for (const Triangle& t : scene.triangles)
    for (const uint32_t v : t.v) corners.push_back(scene.positions[v]);
  return corners;
}

Json pair(double lueur, const std::optional<double>& embree) {
  return Json{{"lueur", lueur}, {"embree", embree ? Json(*embree) : Json(nullptr)}};
}

/// Lueur's work per ray on one ray array: a steadier figure than a timing for judging a change to the tree.
TraversalCounts count_traversal(const Bvh& bvh, const std::vector<Ray>& rays, Query query) {
  TraversalCounts counts;
  for (const Ray& r : rays) {
    if (query == Query::kClosest)
      (void)intersect_closest(bvh, r, counts);
    else
      (void)intersect_any(bvh, r, counts);
  }
  return counts;
}

int run(const BenchOptions& o) {
  Json results = Json::array(), builds = Json::array(), traversal = Json::array(), convergence = Json::array(),
       frames = Json::array();
  // The frame section compares with the throughput of the same scene's arrays, so it measures them too.
  const bool throughput = o.sections.count("throughput") || o.sections.count("frame");
  const bool need_rays = throughput || o.sections.count("traversal");
  const bool need_scenes = o.sections.count("build") || need_rays;
  if (!embree_available()) std::fprintf(stderr, "lueur-bench: this build has no Embree: Lueur's figures only\n");

  if (need_scenes) {
    std::vector<std::string> skipped;
    std::vector<BenchScene> scenes = load_bench_scenes(o.quick || o.smoke, o.scenes_dir, skipped);
    if (o.smoke) scenes.back() = make_sphere_field(4, 7);
    if (!o.only.empty())
      std::erase_if(scenes, [&](const BenchScene& b) { return b.name.find(o.only) == std::string::npos; });
    for (const std::string& s : skipped) std::fprintf(stderr, "lueur-bench: skipped %s\n", s.c_str());
    ThreadPool one(1), all(0);
    std::vector<ThreadPool*> pools = {&one};
    if (all.thread_count() > 1) pools.push_back(&all);

    if (throughput)
      std::printf("%-16s %9s %-8s %7s %10s %10s %7s %9s\n", "scene", "triangles", "rays", "threads", "lueur", "embree",
                  "ratio", "agree");
    for (BenchScene& b : scenes) {
      const std::vector<Vec3> corners = corners_of(b.scene);
      const size_t triangles = b.scene.triangles.size();
      Bvh bvh;
      std::shared_ptr<const EmbreeScene> embree;
      const BuildFigures build = measure_builds(corners, kBuildRepeats, bvh, embree);
      if (o.sections.count("build")) {
        builds.push_back(Json{{"scene", b.name},
                              {"triangles", triangles},
                              {"ms", pair(build.lueur_ms, build.embree_ms)},
                              {"bytes_per_triangle", pair(build.lueur_bytes, build.embree_bytes)},
                              {"resident_bytes_per_triangle",
                               pair(build.lueur_resident_bytes, build.embree_resident_bytes)}});
        std::fprintf(stderr, "lueur-bench: %s build: lueur %.1f ms %.1f B/tri (%.1f resident)", b.name.c_str(),
                     build.lueur_ms, build.lueur_bytes, build.lueur_resident_bytes);
        if (build.embree_ms)
          std::fprintf(stderr, ", embree %.1f ms (rtcCommitScene) %.1f B/tri (%.1f resident)", *build.embree_ms,
                       build.embree_bytes.value_or(0.0), build.embree_resident_bytes.value_or(0.0));
        std::fprintf(stderr, "\n");
      }
      if (!need_rays) continue;
      Accelerator lueur;
      lueur.bvh = std::move(bvh);
      const RaySets sets = make_ray_sets(b, lueur, o.ray_size, o.ray_size, 1);
      const struct {
        const char* name;
        const std::vector<Ray>* rays;
        Query query;
      } kinds[] = {{"primary", &sets.primary, Query::kClosest},
                   {"shadow", &sets.shadow, Query::kAny},
                   {"bounce", &sets.bounce, Query::kClosest}};
      for (const auto& kind : kinds) {
        if (!o.sections.count("traversal") || kind.rays->empty()) continue;
        const TraversalCounts c = count_traversal(lueur.bvh, *kind.rays, kind.query);
        const auto per_ray = [&](uint64_t n) { return static_cast<double>(n) / static_cast<double>(c.queries); };
        traversal.push_back(Json{{"scene", b.name},
                                 {"triangles", triangles},
                                 {"rays", kind.name},
                                 {"nodes_per_ray", per_ray(c.nodes)},
                                 {"leaves_per_ray", per_ray(c.leaves)},
                                 {"groups_per_ray", per_ray(c.groups)}});
        std::fprintf(stderr, "lueur-bench: %s %s rays: %.2f nodes, %.2f leaves, %.2f triangle groups per ray\n",
                     b.name.c_str(), kind.name, per_ray(c.nodes), per_ray(c.leaves), per_ray(c.groups));
      }
      if (!throughput) continue;
      std::map<std::pair<std::string, int>, double> mrays;  // (kind, threads) -> Lueur's Mrays/s
      for (const auto& kind : kinds)
        for (ThreadPool* pool : pools) {
          const Throughput t = measure_throughput(*kind.rays, kind.query, lueur.bvh, embree.get(), *pool, o.timing);
          const bool has_ratio = t.embree && *t.embree > 0.0;
          const double ratio = has_ratio ? t.lueur / *t.embree : 0.0;
          results.push_back(Json{{"scene", b.name},
                                 {"triangles", triangles},
                                 {"rays", kind.name},
                                 {"threads", pool->thread_count()},
                                 {"mrays", pair(t.lueur, t.embree)},
                                 {"ratio", has_ratio ? Json(ratio) : Json(nullptr)}});
          std::printf("%-16s %9zu %-8s %7d %10.2f %10.2f %7.3f %9.6f\n", b.name.c_str(), triangles, kind.name,
                      pool->thread_count(), t.lueur, t.embree.value_or(0.0), ratio, t.agreement);
          std::fflush(stdout);
          mrays[{kind.name, pool->thread_count()}] = t.lueur;
        }
      if (!o.sections.count("frame")) continue;
      for (ThreadPool* pool : pools) {
        const int threads = pool->thread_count();
        const FrameComparison c =
            compare_frames_with_arrays(b, lueur.bvh, sets, o.ray_size, *pool, o.frame_seconds, o.timing);
        const FrameFigures& f = c.frames;
        frames.push_back(Json{{"scene", b.name},
                              {"threads", threads},
                              {"frames", f.frames},
                              {"seconds", f.seconds},
                              {"rays", {{"primary", f.primary}, {"bounce", f.bounce}, {"any_hit", f.any_hit}}},
                              {"renderer_mrays", c.renderer_mrays},
                              {"arrays_mrays", c.arrays_mrays},
                              {"ratio", c.ratio},
                              {"round_ratios", c.ratios}});
        std::printf("%-16s %9zu %-8s %7d %10.2f %10.2f %7.3f  (renderer; the same rays in the arrays)\n",
                    b.name.c_str(), triangles, "frame", threads, c.renderer_mrays, c.arrays_mrays, c.ratio);
        std::fflush(stdout);
      }
    }
  }
  if (o.sections.count("convergence")) convergence = run_convergence(o.convergence, stderr);
  Json store = Json::array();
  if (o.sections.count("store")) {
    std::vector<std::string> skipped;
    std::vector<BenchScene> scenes = load_bench_scenes(o.quick || o.smoke, o.scenes_dir, skipped);
    if (!o.only.empty())
      std::erase_if(scenes, [&](const BenchScene& b) { return b.name.find(o.only) == std::string::npos; });
    for (const std::string& s : skipped) std::fprintf(stderr, "lueur-bench: skipped %s\n", s.c_str());
    store = run_store_comparison(scenes, o.store, stderr);
  }
  Json store_frames = Json::array();
  if (o.sections.count("store-frames")) {
    std::vector<std::string> skipped;
    std::vector<BenchScene> scenes;
    scenes.push_back(make_default_bench_scene());
    if (std::optional<BenchScene> conference = load_shared_bench_scene("conference", o.scenes_dir, skipped))
      scenes.push_back(std::move(*conference));
    scenes.push_back(make_room_facing_wall());
    for (const std::string& s : skipped) std::fprintf(stderr, "lueur-bench: skipped %s\n", s.c_str());
    if (!o.only.empty())
      std::erase_if(scenes, [&](const BenchScene& b) { return b.name.find(o.only) == std::string::npos; });
    store_frames = run_store_frames(scenes, o.store_frames, stderr);
  }
  Json store_ln = Json::array();
  if (o.sections.count("store-ln")) {
    std::vector<std::string> skipped;
    std::vector<BenchScene> scenes;
    for (const char* name : {"conference", "cornell-original"})
      if (std::optional<BenchScene> b = load_shared_bench_scene(name, o.scenes_dir, skipped))
        scenes.push_back(std::move(*b));
    for (const std::string& s : skipped) std::fprintf(stderr, "lueur-bench: skipped %s\n", s.c_str());
    if (!o.only.empty())
      std::erase_if(scenes, [&](const BenchScene& b) { return b.name.find(o.only) == std::string::npos; });
    store_ln = run_store_ln(scenes, o.store_ln, stderr);
  }

  if (!o.json_path.empty()) {
    Json out{{"results", results}, {"build", builds}, {"convergence", convergence}};
    if (o.sections.count("traversal")) out["traversal"] = traversal;
    if (o.sections.count("frame")) out["frames"] = frames;
    if (o.sections.count("store")) out["store"] = store;
    if (o.sections.count("store-frames")) out["store_frames"] = store_frames;
    if (o.sections.count("store-ln")) out["store_ln"] = store_ln;
    write_file_atomically(o.json_path, out.dump(2) + "\n");
    std::printf("%s\n", o.json_path.c_str());
  }
  return 0;
}

}  // namespace
}  // namespace lueur::bench

int main(int argc, char** argv) {
  using namespace lueur;
  map_large_arrays_alone();
  try {
    const auto options = bench::parse(argc, argv);
    if (!options) return 0;
    return bench::run(*options);
  } catch (const bench::UsageError& e) {
    std::fprintf(stderr, "lueur-bench: error: %s (see lueur-bench --help)\n", e.what());
  } catch (const SceneError& e) {
    std::fprintf(stderr, "lueur-bench: error: %s\n", e.what());
  } catch (const IoError& e) {
    std::fprintf(stderr, "lueur-bench: error: %s\n", e.what());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lueur-bench: error: %s\n", e.what());
  }
  return 2;
}
