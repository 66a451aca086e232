// The rounds of an MPI render. Every rank goes through the same sequence of collectives: plan (broadcast), render
// its share, report (gather), decision (broadcast), and when the decision says so, the reduction of the sums. Rank 0
// alone reads and writes files.
#include "mpi/mpi_render.h"

#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <new>
#include <thread>

#include "app/options.h"
#include "app/render_output.h"
#include "core/atomic_file.h"
#include "core/stopwatch.h"
#include "runtime/frame_plan.h"
#include "film/noise_estimate.h"
#include "integrator/renderer.h"
#include "scene/obj_loader.h"
#include "settings/compare.h"

namespace lueur {
namespace {

/// How long a round lasts, about (less when checkpoints come more often): rank 0 prints progress and checks the
/// time limit once per round.
constexpr double kRoundSeconds = 1.0;

/// What each rank tells rank 0 after a round.
struct RankReport {
  uint64_t frames = 0;
  double seconds = 0.0;  ///< rendering time of its share
  FrameTally tally;
};

/// What rank 0 decides after a round.
struct RoundDecision {
  int reduce = 0;  ///< gather the sums on rank 0 now
  int stop = 0;    ///< no more rounds
};

/// Rank 0's one line when mpirun stops the job (a rank died, a node was lost, or the user cancelled): written from
/// a signal handler, so made beforehand.
char g_stop_message[1024] = "lueur-mpi: error: the job was stopped (a rank died, or it was cancelled)\n";

extern "C" void on_stop_signal(int) {
  const ssize_t ignored = ::write(STDERR_FILENO, g_stop_message, std::strlen(g_stop_message));
  (void)ignored;
  ::_exit(3);
}

void install_stop_message(const AppOptions& options) {
  std::string text = "lueur-mpi: error: the job was stopped (a rank died, or it was cancelled)";
  if (options.checkpoint_seconds > 0.0)
    text += "; go on from the last checkpoint with --resume '" + state_path_of(options.out_path) + "'";
  text += "\n";
  std::snprintf(g_stop_message, sizeof g_stop_message, "%s", text.c_str());
  std::signal(SIGTERM, on_stop_signal);
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGHUP, on_stop_signal);
}

/// How many CPUs this process may run on (its affinity mask, which mpirun's binding sets).
int cpus_allowed() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) != 0) return static_cast<int>(std::thread::hardware_concurrency());
  return std::max(1, CPU_COUNT(&set));
}

/// One line for an error, as lueur prints it.
std::string error_line(const std::exception& e) {
  if (dynamic_cast<const UsageError*>(&e)) return std::string(e.what()) + " (see lueur-mpi --help)";
  if (dynamic_cast<const std::bad_alloc*>(&e)) return "out of memory";
  return e.what();
}

/// Settings whose frames depend on the frames before them cannot be split across ranks.
void refuse_frame_history(const RenderSettings& settings, const std::string& side) {
  if (!settings.pass_enabled(Pass::kL2)) return;
  if (settings.reuse == ReuseMode::kAverage || uses_cache(settings.reuse))
    throw UsageError("--reuse " + std::string(enum_name(kReuseModeNames, settings.reuse)) + side +
                     ": each frame reads what the frames before it left (the running average or the L1 store), so "
                     "the frames cannot be split across ranks; use lueur, or --reuse off|frame");
}

void check_mpi_options(AppOptions& options) {
  options.headless = true;
  if (!options.export_default_scene.empty()) throw UsageError("--export-default-scene: use lueur for that");
  if (options.out_path.empty()) throw UsageError("lueur-mpi needs --out FILE");
  refuse_frame_history(options.settings.render, "");
  if (const std::optional<Settings> right = compared_settings(options.settings))
    refuse_frame_history(right->render, " (the right side of --compare)");
}

/// The films one rank accumulates its share into: exact sums only, handed to rank 0 at each reduction. (Their L1
/// stores stay empty: lueur-mpi refuses the store modes.)
struct RankFilms {
  Accumulation left, right;
  bool has_right = false;
  void reset(const RenderJob& job, double unit) {
    left.film.mode = right.film.mode = FilmMode::kExactOnly;
    left.film.reset(job.left.film.width, job.left.film.height, layers_of(job.left.film));
    left.film.unit = unit;
    has_right = job.right.has_value();
    if (has_right) {
      right.film.reset(job.right_side.film.width, job.right_side.film.height, layers_of(job.right_side.film));
      right.film.unit = unit;
    }
  }
  static std::array<bool, kLayerCount> layers_of(const Film& film) {
    std::array<bool, kLayerCount> layers{};
    for (size_t l = 0; l < kLayerCount; ++l) layers[l] = film.has(static_cast<Layer>(l));
    return layers;
  }
};

/// Collective: sums every rank's films into rank 0's job films, which then hold `frames_after` frames; every
/// rank's own sums start again from zero.
void reduce_films(const MpiWorld& world, RankFilms& mine, RenderJob& job, uint64_t frames_after,
                  uint64_t snapshots_from) {
  const auto reduce = [&](Film& part, Film& whole) {
    for (auto& layer : part.exact)
      if (!layer.empty()) reduce_sum_to_root(world, layer);
    if (world.root()) whole.add_exact(part.exact, frames_after, snapshots_from);
    for (auto& layer : part.exact) std::fill(layer.begin(), layer.end(), 0);
  };
  reduce(mine.left.film, job.left.film);
  if (mine.has_right) reduce(mine.right.film, job.right_side.film);
}

struct Setup {
  AppOptions options;
  RenderJob job;
  int threads = 1;
};

}  // namespace

int run_mpi_render(const MpiWorld& world, int argc, char** argv) {
  // Only rank 0 speaks: the others' help text and progress would repeat it.
  if (!world.root() && !std::freopen("/dev/null", "w", stdout)) return 2;
  Setup setup;
  std::string error, message;
  const auto fail = [&]() {
    if (world.root()) std::fprintf(stderr, "lueur-mpi: error: %s\n", message.c_str());
    return 2;
  };
  bool help_only = false;
  try {
    const ProgramName program{"lueur-mpi",
                              "lueur-mpi: a headless Lueur render shared among MPI ranks (mpirun -n N lueur-mpi ...), "
                              "the bytes lueur --headless writes"};
    const std::optional<AppOptions> parsed = parse_command_line(argc, argv, program);
    if (!parsed) {
      help_only = true;
    } else {
      setup.options = *parsed;
      check_mpi_options(setup.options);
    }
  } catch (const std::exception& e) {
    error = error_line(e);
  }
  if (!all_fine(world, error, message)) return fail();
  if (help_only) return 0;
  AppOptions& options = setup.options;

  // Every rank opens the scene; rank 0 also checks the output and reads the state to resume from.
  try {
    setup.job = prepare_render_job(options, world.root());
    if (world.root() && !options.resume_path.empty())
      resume_render(options, *setup.job.opened.traced, setup.job.sides());
  } catch (const std::exception& e) {
    error = error_line(e);
  }
  if (!all_fine(world, error, message)) return fail();
  RenderJob& job = setup.job;
  const TracedScene& traced = *job.opened.traced;
  const RenderSettings& settings = options.settings.render;
  const double unit = film_unit(traced, job.camera, settings);
  if (world.root() && job.left.film.unit != 0.0 && job.left.film.unit != unit)
    error = "--resume '" + options.resume_path + "': its sums are in another unit (another version of Lueur wrote it)";
  if (!all_fine(world, error, message)) return fail();
  if (world.root()) {
    job.left.film.unit = unit;
    job.right_side.film.unit = unit;
    install_stop_message(options);
  }
  uint64_t done = job.left.film.frames;
  broadcast(done);

  // Ranks that share a machine share its cores, as far as mpirun's binding lets them: Open MPI binds each rank to one
  // core when there are two ranks or fewer, where threads beyond the first would only take turns.
  const int node_share = std::max(1, static_cast<int>(std::thread::hardware_concurrency()) / world.ranks_on_node);
  const int allowed = cpus_allowed();
  const int threads = options.threads > 0 ? options.threads : std::min(node_share, allowed);
  int bound = allowed < node_share ? 1 : 0, any_bound = 0;
  MPI_Allreduce(&bound, &any_bound, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  if (world.root() && any_bound)
    std::fprintf(stderr,
                 "lueur: warning: mpirun bound the ranks to fewer CPUs than their share of a machine (rank 0: %d of "
                 "%d): add --bind-to none, or --map-by ppr:1:node:PE=N, to use them all\n",
                 allowed, node_share);
  ThreadPool pool(threads);
  RankFilms mine;
  mine.reset(job, unit);
  const uint64_t total = static_cast<uint64_t>(std::max(options.settings.frames, 0));
  if (world.root()) {
    if (done > 0)
      std::fprintf(stderr, "lueur: resuming '%s' after %llu frames\n", options.resume_path.c_str(),
                   static_cast<unsigned long long>(done));
    print_render_header(options, job,
                        std::to_string(world.size) + (world.size == 1 ? " rank" : " ranks") + " x " +
                            std::to_string(threads) + (threads == 1 ? " thread" : " threads"));
  }

  // Rounds stop at the powers of two whose snapshots the noise estimate reads at the end; a render that may stop
  // early (or plots the estimate at every power of two) stops at all of them. The early rounds are then not
  // shorter than one frame per rank.
  const bool may_stop_early = options.settings.time_limit > 0.0 || options.settings.target_noise > 0.0 ||
                              (options.ui && options.gl != HeadlessGl::kNone);
  const uint64_t snapshots_from = may_stop_early ? 0 : needed_snapshots_from(total);
  // A round ends in time for the next checkpoint.
  const double round_seconds =
      options.checkpoint_seconds > 0.0 ? std::min(kRoundSeconds, options.checkpoint_seconds) : kRoundSeconds;
  const Clock::time_point start = Clock::now();
  Clock::time_point last_checkpoint = start;
  const uint64_t first = done;
  RunFigures figures;
  std::vector<double> rates(static_cast<size_t>(world.size), 0.0);  // frames per second, rank 0's view
  const bool tty = ::isatty(STDERR_FILENO);
  bool stopped_by_noise = false, out_of_time = false;
  double busy_seconds = 0.0;    // the ranks' rendering time, summed
  double reduce_seconds = 0.0;  // rank 0's time in the reductions (every rank has reported: no waiting for a slow one)
  int reductions = 0;
  try {
    while (done < total) {
      // The plan: this round's frames and each rank's share, in rank order.
      std::vector<uint64_t> shares(static_cast<size_t>(world.size), 0);
      uint64_t end = 0;
      if (world.root()) {
        shares = plan_round(done, total, snapshots_from, rates, round_seconds);
        end = done;
        for (const uint64_t share : shares) end += share;
      }
      broadcast(end);
      broadcast(shares);
      uint64_t my_first = done;
      for (int r = 0; r < world.rank; ++r) my_first += shares[static_cast<size_t>(r)];
      const uint64_t my_count = shares[static_cast<size_t>(world.rank)];

      RankReport report;
      const Clock::time_point round_start = Clock::now();
      mine.left.film.frames = my_first;
      mine.right.film.frames = my_first;
      for (uint64_t f = 0; f < my_count; ++f)
        render_frame_pair(traced, job.camera, settings, mine.left, mine.has_right ? &job.right->render : nullptr,
                          mine.has_right ? &mine.right : nullptr, pool, report.tally);
      report.frames = my_count;
      report.seconds = seconds_since(round_start);
      const std::vector<RankReport> reports = gather(world, report);

      RoundDecision decision;
      const double elapsed = seconds_since(start);
      if (world.root()) {
        for (size_t r = 0; r < reports.size(); ++r) {
          const RankReport& each = reports[r];
          // Smoothed over rounds: one slow frame on a shared machine must not swing the next shares.
          if (each.frames > 0 && each.seconds > 0.0) {
            const double rate = static_cast<double>(each.frames) / each.seconds;
            rates[r] = rates[r] > 0.0 ? 0.5 * (rates[r] + rate) : rate;
          }
          figures.tally.add(each.tally);
          busy_seconds += each.seconds;
        }
        out_of_time = options.settings.time_limit > 0.0 && elapsed >= options.settings.time_limit;
        const bool checkpoint_due =
            options.checkpoint_seconds > 0.0 && seconds_since(last_checkpoint) >= options.checkpoint_seconds;
        decision.stop = end == total || out_of_time;
        decision.reduce = decision.stop || (is_power_of_two(end) && end >= snapshots_from) || checkpoint_due ||
                          options.settings.target_noise > 0.0;
      }
      broadcast(decision);
      done = end;
      if (decision.reduce) {
        const Clock::time_point reduce_start = Clock::now();
        reduce_films(world, mine, job, end, snapshots_from);
        reduce_seconds += seconds_since(reduce_start);
        ++reductions;
      }
      if (world.root()) {
        if (decision.reduce) record_noise_history(options, job.left.film, elapsed, figures);
        if (decision.reduce && options.settings.target_noise > 0.0 &&
            estimate_image_noise(job.left.film, settings.enabled, options.settings.weights, settings.sampler).rel_mse <
                options.settings.target_noise) {
          stopped_by_noise = true;
          decision.stop = 1;
        }
        const double left = elapsed / static_cast<double>(done - first) * static_cast<double>(total - done);
        std::fprintf(stderr, "%slueur: frame %llu/%llu on %d ranks, %.1f s elapsed, about %.1f s left%s",
                     tty ? "\r" : "", static_cast<unsigned long long>(done), static_cast<unsigned long long>(total),
                     world.size, elapsed, left, tty ? "   " : "\n");
        if (stopped_by_noise)
          std::fprintf(stderr, "%slueur: target noise %g reached after %llu frames, %.2f s\n", tty ? "\n" : "",
                       options.settings.target_noise, static_cast<unsigned long long>(done), elapsed);
        if (decision.reduce && !decision.stop && options.checkpoint_seconds > 0.0 &&
            seconds_since(last_checkpoint) >= options.checkpoint_seconds) {
          figures.seconds = elapsed;
          write_checkpoint(options, job.left, job.right ? &job.right_side : nullptr, traced, figures);
          last_checkpoint = Clock::now();
        }
      }
      if (options.settings.target_noise > 0.0) broadcast(decision);
      if (decision.stop) break;
    }
  } catch (const std::exception& e) {
    // The other ranks wait in a collective: only an abort ends them without a hang.
    std::fprintf(stderr, "lueur-mpi: error: %s%s\n",
                 world.root() ? "" : ("rank " + std::to_string(world.rank) + ": ").c_str(), error_line(e).c_str());
    std::fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, 2);
  }

  if (!world.root()) return 0;
  figures.seconds = seconds_since(start);
  if (tty) std::fprintf(stderr, "\n");
  try {
    finish_render(options, job.left, job.right ? &job.right_side : nullptr, traced, figures, out_of_time,
                  stopped_by_noise);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lueur-mpi: error: %s\n", error_line(e).c_str());
    return 2;
  }
  print_run_summary(options, job.left.film, job.right_film(), figures);
  uint64_t reduced_bytes = 0;
  for (const Accumulation* side : job.sides())
    for (const auto& layer : side->film.exact) reduced_bytes += layer.size() * sizeof(int64_t);
  std::fprintf(stderr,
               "lueur: the %d ranks rendered %.1f%% of the time; %d reductions of %.1f MiB took %.3f s in all\n",
               world.size, 100.0 * busy_seconds / (world.size * figures.seconds), reductions,
               static_cast<double>(reduced_bytes) / (1 << 20), reduce_seconds);
  std::printf("%s\n", options.out_path.c_str());
  return 0;
}

}  // namespace lueur
