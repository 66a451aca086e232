#include "test_support.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <mutex>
#include <sstream>
#include <thread>

namespace lueur::test {

namespace {

/// Removes `dir` and everything in it, first giving back the owner's rights that a test took away (an unreadable
/// file, a directory nobody may write): without them a user who is not root could not remove them. A link is
/// removed, never followed: its target's rights are not this clean-up's to change.
void remove_tree(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  std::error_code ignored;
  if (fs::is_symlink(dir, ignored)) {
    fs::remove(dir, ignored);
    return;
  }
  fs::permissions(dir, fs::perms::owner_all, fs::perm_options::add, ignored);
  for (auto it = fs::recursive_directory_iterator(dir, ignored); it != fs::recursive_directory_iterator();
       it.increment(ignored))
    if (!it->is_symlink(ignored)) fs::permissions(it->path(), fs::perms::owner_all, fs::perm_options::add, ignored);
  fs::remove_all(dir, ignored);
}

/// The directories make_temp_dir made in this process. Once every test of the executable has run, they are removed
/// (each test run used to leave about a hundred in the temp dir), unless a test failed: then they stay for a look,
/// and the executable says where.
class TempDirCleanup : public ::testing::Environment {
 public:
  static TempDirCleanup& instance() {
    // Owned by GoogleTest once registered; registered before main runs (this file's static initialiser below).
    static TempDirCleanup* const cleanup = [] {
      auto* made = new TempDirCleanup;
      ::testing::AddGlobalTestEnvironment(made);
      return made;
    }();
    return *cleanup;
  }
  void add(const std::string& dir) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (std::find(dirs_.begin(), dirs_.end(), dir) == dirs_.end()) dirs_.push_back(dir);
  }
  void TearDown() override {
    const std::lock_guard<std::mutex> lock(mutex_);
    const bool keep = ::testing::UnitTest::GetInstance()->Failed();
    for (const std::string& dir : dirs_) {
      if (keep)
        std::fprintf(stderr, "a test failed: its files are kept in %s\n", dir.c_str());
      else
        remove_tree(dir);
    }
    dirs_.clear();
  }

 private:
  std::mutex mutex_;
  std::vector<std::string> dirs_;
};

[[maybe_unused]] const TempDirCleanup& kRegisterCleanup = TempDirCleanup::instance();

}  // namespace

std::string make_temp_dir(const std::string& tag) {
  namespace fs = std::filesystem;
  const fs::path base = fs::temp_directory_path() / ("lueur-test-" + tag + "-" + std::to_string(::getpid()));
  remove_tree(base);
  fs::create_directories(base);
  TempDirCleanup::instance().add(base.string());
  return base.string();
}

std::string shell_quote(const std::string& text) {
  std::string quoted = "'";
  for (const char c : text) {
    if (c == '\'')
      quoted += "'\\''";
    else
      quoted += c;
  }
  quoted += '\'';
  return quoted;
}

CommandResult run_lueur(const std::string& arguments, const std::string& prefix) {
  return run_program(LUEUR_EXECUTABLE, arguments, prefix);
}

CommandResult run_program(const std::string& executable, const std::string& arguments, const std::string& prefix) {
  CommandResult result;
  // Generous: sanitizer builds are several times slower than release ones.
  std::string command = prefix;
  command += " timeout 300 ";
  command += shell_quote(executable);
  command += ' ';
  command += arguments;
  command += " 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return result;
  char buffer[4096];
  size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) result.output.append(buffer, n);
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return result;
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

bool file_exists(const std::string& path) { return std::filesystem::exists(path); }

std::string shared_scene(const std::string& relative) {
  const std::filesystem::path path = std::filesystem::path(LUEUR_SHARED_SCENES) / relative;
  return std::filesystem::exists(path) ? path.string() : std::string();
}

ScopedEnv::ScopedEnv(const char* name, const char* value) : name_(name) {
  if (const char* old = std::getenv(name)) previous_ = old;
  ::setenv(name, value, 1);
}

ScopedEnv::~ScopedEnv() {
  if (previous_)
    ::setenv(name_.c_str(), previous_->c_str(), 1);
  else
    ::unsetenv(name_.c_str());
}

bool wait_until(const std::function<bool()>& condition, double timeout_seconds, double poll_seconds) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point deadline =
      Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout_seconds));
  for (;;) {
    if (condition()) return true;
    if (Clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::duration<double>(poll_seconds));
  }
}

Scene make_closed_emitting_box(float h, Vec3 rho, Vec3 le) {
  Scene s;
  s.name = "closed-box";
  Material m;
  m.name = "wall";
  m.kd = rho;
  m.ke = le;
  s.materials.push_back(m);
  // Each face counter-clockwise as seen from inside the box, so every geometric normal points inwards.
  add_quad(s, {-h, -h, -h}, {-h, -h, h}, {h, -h, h}, {h, -h, -h}, 0);  // floor, normal +y
  add_quad(s, {-h, h, -h}, {h, h, -h}, {h, h, h}, {-h, h, h}, 0);      // ceiling, normal -y
  add_quad(s, {-h, -h, -h}, {-h, h, -h}, {-h, h, h}, {-h, -h, h}, 0);  // x = -h, normal +x
  add_quad(s, {h, -h, -h}, {h, -h, h}, {h, h, h}, {h, h, -h}, 0);      // x = +h, normal -x
  add_quad(s, {-h, -h, -h}, {h, -h, -h}, {h, h, -h}, {-h, h, -h}, 0);  // z = -h, normal +z
  add_quad(s, {-h, -h, h}, {-h, h, h}, {h, h, h}, {h, -h, h}, 0);      // z = +h, normal -z
  collect_emitters(s);
  return s;
}

Scene make_closed_emitting_sphere(float r, int segments, int rings, Vec3 rho, Vec3 le) {
  Scene s;
  s.name = "closed-sphere";
  Material m;
  m.name = "inside";
  m.kd = rho;
  m.ke = le;
  s.materials.push_back(m);
  auto vertex = [&](int ring, int segment) {
    const float theta = kPi * static_cast<float>(ring) / static_cast<float>(rings);
    const float phi = 2.0f * kPi * static_cast<float>(segment % segments) / static_cast<float>(segments);
    return r * Vec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
  };
  auto add_triangle = [&](Vec3 a, Vec3 b, Vec3 c) {
    // Wind so that the geometric normal points at the centre.
    if (glm::dot(glm::cross(b - a, c - a), a + b + c) > 0.0f) std::swap(b, c);
    const auto base = static_cast<uint32_t>(s.positions.size());
    s.positions.insert(s.positions.end(), {a, b, c});
    Triangle t;
    t.v[0] = base, t.v[1] = base + 1, t.v[2] = base + 2;
    s.triangles.push_back(t);
  };
  for (int ring = 0; ring < rings; ++ring)
    for (int seg = 0; seg < segments; ++seg) {
      const Vec3 a = vertex(ring, seg), b = vertex(ring, seg + 1), c = vertex(ring + 1, seg + 1),
                 d = vertex(ring + 1, seg);
      if (ring > 0) add_triangle(a, b, c);
      if (ring < rings - 1) add_triangle(a, c, d);
    }
  collect_emitters(s);
  return s;
}

Scene make_rect_light_over_floor(float w, float h, float height, Vec3 rho, Vec3 le) {
  Scene s;
  s.name = "rect-light";
  Material floor;
  floor.name = "floor";
  floor.kd = rho;
  Material light;
  light.name = "light";
  light.kd = Vec3(0.0f);
  light.ke = le;
  s.materials = {floor, light};
  const float f = 100.0f;
  add_quad(s, {-f, 0, -f}, {-f, 0, f}, {f, 0, f}, {f, 0, -f}, 0);  // normal +y
  const float x = 0.5f * w, z = 0.5f * h;
  add_quad(s, {-x, height, -z}, {x, height, -z}, {x, height, z}, {-x, height, z}, 1);  // normal -y
  collect_emitters(s);
  return s;
}

std::optional<SurfacePoint> surface_below(const TracedScene& traced, const Vec3& point, float height) {
  Ray down;
  down.origin = point + Vec3(0.0f, height, 0.0f);
  down.dir = Vec3(0.0f, -1.0f, 0.0f);
  const Hit hit = intersect_closest(traced.accel, down);
  if (!hit.found()) return std::nullopt;
  return make_surface_point(traced.scene, down, hit);
}

double lambert_irradiance(const std::vector<glm::dvec3>& polygon, const glm::dvec3& p, const glm::dvec3& n, double le) {
  // Newell's normal: the polygon's area vector, pointing to the emitting side whatever corner is concave.
  glm::dvec3 area_normal(0.0);
  for (size_t i = 0; i < polygon.size(); ++i) area_normal += glm::cross(polygon[i], polygon[(i + 1) % polygon.size()]);
  if (!(glm::dot(area_normal, p - polygon[0]) > 0.0)) return 0.0;  // behind the polygon or in its plane
  double sum = 0.0;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const glm::dvec3 a = polygon[i] - p, b = polygon[(i + 1) % polygon.size()] - p;
    if (glm::dot(a, n) < 0.0) return std::numeric_limits<double>::quiet_NaN();  // below the horizon
    // b x a, not a x b: for corners counter-clockwise seen from p, it is the inward normal of this side of the
    // pyramid from p through the polygon, so every edge adds to E when n faces the polygon.
    const glm::dvec3 normal = glm::cross(b, a);
    const double length = glm::length(normal);
    if (length == 0.0) continue;  // p on the edge's line: the edge subtends no angle
    // atan2 rather than acos of a dot product: exact for the small angles of a far polygon.
    const double theta = std::atan2(length, glm::dot(a, b));
    sum += theta * glm::dot(normal / length, n);
  }
  return 0.5 * le * sum;
}

bool chi_square_rejects(double statistic, int dof) {
  const double k = dof;
  const double z = (std::cbrt(statistic / k) - (1.0 - 2.0 / (9.0 * k))) / std::sqrt(2.0 / (9.0 * k));
  return z > 4.0;
}

std::string strategy_test_name(const ::testing::TestParamInfo<LightStrategy>& info) {
  return std::string(kLightStrategyNames[static_cast<size_t>(info.param)]);
}

}  // namespace lueur::test
