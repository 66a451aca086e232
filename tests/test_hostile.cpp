// The hostile scene corpus (tests/hostile/MANIFEST): every case runs through the real headless path and must
// end as its manifest says: refused with exit status 2 and one line naming the problem, leaving nothing in the
// output folder; or rendered with the named warning (or none) into a finite image. Never a crash or a hang.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "image/image_output.h"
#include "test_support.h"

namespace lueur {
namespace {

namespace fs = std::filesystem;

const std::string kHostile = std::string(LUEUR_SOURCE_DIR) + "/tests/hostile";

struct HostileCase {
  std::string scene;    ///< a file in tests/hostile, or "@name" for a generated case
  std::string outcome;  ///< refused, warned or loaded
  std::string text;     ///< expected in the message; " ~ " separates parts that appear in this order
  int line = 0;         ///< in the manifest
};

std::string trim(const std::string& s) {
  const size_t begin = s.find_first_not_of(" \t");
  if (begin == std::string::npos) return {};
  return s.substr(begin, s.find_last_not_of(" \t") - begin + 1);
}

std::vector<HostileCase> read_manifest() {
  std::vector<HostileCase> cases;
  std::ifstream in(kHostile + "/MANIFEST");
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    if (trim(line).empty() || trim(line)[0] == '#') continue;
    const size_t a = line.find('|'), b = line.find('|', a == std::string::npos ? a : a + 1);
    HostileCase c;
    c.line = number;
    c.scene = trim(line.substr(0, a));
    if (b != std::string::npos) {
      c.outcome = trim(line.substr(a + 1, b - a - 1));
      c.text = trim(line.substr(b + 1));
    }
    cases.push_back(c);
  }
  return cases;
}

/// Whether `text` holds the " ~ "-separated parts of `pattern`, in order.
bool matches(const std::string& text, const std::string& pattern) {
  size_t at = 0, part_begin = 0;
  while (true) {
    const size_t part_end = pattern.find(" ~ ", part_begin);
    const std::string part = pattern.substr(part_begin, part_end - part_begin);
    at = text.find(part, at);
    if (at == std::string::npos) return false;
    at += part.size();
    if (part_end == std::string::npos) return true;
    part_begin = part_end + 3;
  }
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

void write_file(const std::string& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

const char* kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

/// A star-shaped (concave) polygon of n vertices in one face.
std::string star_polygon(int n) {
  std::string obj;
  char line[96];
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * M_PI * i / n, r = (i % 2) ? 0.8 : 1.0;
    std::snprintf(line, sizeof line, "v %.7f %.7f 0\n", r * std::cos(a), r * std::sin(a));
    obj += line;
  }
  obj += "f";
  for (int i = 1; i <= n; ++i) {
    obj += ' ';
    obj += std::to_string(i);
  }
  obj += '\n';
  return obj;
}

/// A generated case: the scene path, what to put before the command (environment variables or a wrapper), and
/// why it cannot run here (empty: it can).
struct Generated {
  std::string path;
  std::string prefix;
  std::string skip;
  std::string executable = LUEUR_EXECUTABLE;
};

/// Root reads files whatever their permissions: as root, permission cases run lueur as the user nobody.
std::string drop_root(const std::string& dir, std::string& skip) {
  if (::geteuid() != 0) return {};
  if (::access("/usr/bin/setpriv", X_OK) != 0) {
    skip = "running as root without setpriv to run as another user: root reads any file";
    return {};
  }
  fs::permissions(dir, fs::perms::all);  // nobody writes the output there
  fs::permissions(dir + "/out", fs::perms::all);
  // The build tree may sit in a directory nobody cannot enter (a 0700 mktemp clone): run a copy from `dir`.
  const std::string copy = dir + "/lueur";
  fs::copy_file(LUEUR_EXECUTABLE, copy, fs::copy_options::overwrite_existing);
  fs::permissions(copy, fs::perms::all);
  return "/usr/bin/setpriv --reuid=65534 --regid=65534 --clear-groups";
}

Generated generate(const std::string& name, const std::string& dir) {
  Generated g{dir + "/" + name + ".obj", "", ""};
  if (name == "face-with-10000-vertices") {
    write_file(g.path, star_polygon(10000));
  } else if (name == "face-with-100000-vertices") {
    write_file(g.path, star_polygon(100000));
  } else if (name == "face-of-one-repeated-triangle") {
    std::string face = "f";
    for (int i = 0; i < 10000; ++i) face += " 1 2 3";
    write_file(g.path, kTriangle + face + "\n");
  } else if (name == "mtl-is-a-directory" || name == "mtl-is-a-fifo" || name == "mtl-without-permission") {
    write_file(g.path, std::string("mtllib odd.mtl\n") + kTriangle + "f 1 2 3\n");
    const std::string mtl = dir + "/odd.mtl";
    if (name == "mtl-is-a-directory") fs::create_directory(mtl);
    if (name == "mtl-is-a-fifo") ::mkfifo(mtl.c_str(), 0644);
    if (name == "mtl-without-permission") {
      write_file(mtl, "newmtl red\nKd 1 0 0\n");
      ::chmod(mtl.c_str(), 0);
      g.prefix = drop_root(dir, g.skip);
      if (!g.prefix.empty()) g.executable = dir + "/lueur";
      if (!g.prefix.empty()) g.executable = dir + "/lueur";
    }
  } else if (name == "megabyte-lines") {
    // A comment and a valid face, each a megabyte long (indices with many leading zeros).
    const std::string zeros(350000, '0');
    write_file(g.path, "# " + std::string(1 << 20, 'x') + "\n" + kTriangle + "f " + zeros + "1 " + zeros + "2 " +
                           zeros + "3\n");
  } else if (name == "megabyte-statement") {
    write_file(g.path, "# line 2 is one megabyte of a statement no OBJ has\n" + std::string(1 << 20, 'x') + "\n");
  } else if (name == "megabyte-number") {
    write_file(g.path, "v " + std::string(1 << 20, '1') + " 0 0\n");
  } else if (name == "scene-missing") {
    // nothing to make
  } else if (name == "scene-is-a-directory") {
    fs::create_directory(g.path);
  } else if (name == "scene-is-a-fifo") {
    ::mkfifo(g.path.c_str(), 0644);
  } else if (name == "scene-without-permission") {
    write_file(g.path, std::string(kTriangle) + "f 1 2 3\n");
    ::chmod(g.path.c_str(), 0);
    g.prefix = drop_root(dir, g.skip);
    if (!g.prefix.empty()) g.executable = dir + "/lueur";
  } else if (name == "scene-too-large-for-memory") {
    // 90000 vertices and 178802 triangles need about 50 MiB; 80 MiB less 64 MiB for the image leaves 16.
    std::string obj;
    const int n = 300;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) obj += "v " + std::to_string(i) + " " + std::to_string(j) + " 0\n";
    for (int i = 0; i + 1 < n; ++i)
      for (int j = 0; j + 1 < n; ++j) {
        const int a = i * n + j + 1;
        obj += "f " + std::to_string(a) + " " + std::to_string(a + 1) + " " + std::to_string(a + n + 1) + "\n";
        obj += "f " + std::to_string(a) + " " + std::to_string(a + n + 1) + " " + std::to_string(a + n) + "\n";
      }
    write_file(g.path, obj);
    g.prefix = "LUEUR_MEMORY_LIMIT_MB=80";
  } else if (name == "sparse-terabyte-file") {
    // A terabyte that takes no disk space: the size alone must be refused, before any reading.
    write_file(g.path, std::string(kTriangle) + "f 1 2 3\n");
    if (::truncate(g.path.c_str(), off_t{1} << 40) != 0) g.skip = "this filesystem has no sparse terabyte files";
  } else {
    ADD_FAILURE() << "no generator for @" << name;
  }
  return g;
}

std::set<std::string> entries(const std::string& dir) {
  std::set<std::string> names;
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
  return names;
}

/// Names a case by its manifest line in test listings (the scene itself may not be ASCII).
void PrintTo(const HostileCase& c, std::ostream* os) { *os << "MANIFEST:" << c.line; }

class Hostile : public ::testing::TestWithParam<HostileCase> {};

TEST_P(Hostile, EndsAsTheManifestSays) {
  const HostileCase& c = GetParam();
  ASSERT_TRUE(c.outcome == "refused" || c.outcome == "warned" || c.outcome == "loaded")
      << "MANIFEST:" << c.line << ": unknown outcome '" << c.outcome << "'";
  const std::string dir = test::make_temp_dir("hostile-" + std::to_string(c.line));
  const std::string out_dir = dir + "/out";
  fs::create_directory(out_dir);
  const std::string out = out_dir + "/image.pfm";

  std::string scene = kHostile + "/" + c.scene, prefix, executable = LUEUR_EXECUTABLE;
  if (c.scene[0] == '@') {
    const Generated g = generate(c.scene.substr(1), dir);
    if (!g.skip.empty()) GTEST_SKIP() << g.skip;
    scene = g.path;
    prefix = g.prefix;
    executable = g.executable;
  } else {
    ASSERT_TRUE(test::file_exists(scene)) << "MANIFEST:" << c.line << ": no file " << scene;
  }

  const test::CommandResult r =
      test::run_program(executable,
                        test::shell_quote(scene) + " --headless --size 16x16 --frames 1 --passes le,l1,l2,ao --out " +
                            test::shell_quote(out),
                        prefix);
  ASSERT_NE(r.exit_code, 124) << "hung (killed by timeout): " << r.output;
  ASSERT_LT(r.exit_code, 128) << "crashed: " << r.output;
  const std::vector<std::string> lines = lines_of(r.output);
  for (const std::string& line : lines) EXPECT_LT(line.size(), 600u) << "an overlong message line";

  size_t errors = 0, warnings = 0;
  bool text_found = c.text.empty();
  for (const std::string& line : lines) {
    const bool error = line.rfind("lueur: error: ", 0) == 0, warning = line.rfind("lueur: warning: ", 0) == 0;
    errors += error;
    warnings += warning;
    if ((c.outcome == "refused" ? error : warning) && matches(line, c.text)) text_found = true;
  }

  if (c.outcome == "refused") {
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_EQ(errors, 1u) << r.output;
    ASSERT_FALSE(lines.empty());
    EXPECT_EQ(lines.back().rfind("lueur: error: ", 0), 0u) << "the error is not the last line: " << r.output;
    EXPECT_TRUE(text_found) << "expected an error with '" << c.text << "' in:\n" << r.output;
    EXPECT_TRUE(entries(out_dir).empty()) << "left behind in the output folder: " << *entries(out_dir).begin();
  } else {
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(errors, 0u) << r.output;
    if (c.outcome == "loaded") {
      EXPECT_EQ(warnings, 0u) << r.output;
    }
    EXPECT_TRUE(text_found) << "expected a warning with '" << c.text << "' in:\n" << r.output;
    EXPECT_EQ(entries(out_dir), std::set<std::string>{"image.pfm"});
    const Image image = decode_pfm(test::read_file(out));
    EXPECT_EQ(image.width, 16);
    size_t non_finite = 0;
    for (const float v : image.rgb) non_finite += !std::isfinite(v);
    EXPECT_EQ(non_finite, 0u) << "non-finite values in the image";
  }
  // What the cases left unreadable, test::make_temp_dir's clean-up gives rights back to before it removes it.
}

std::string case_name(const ::testing::TestParamInfo<HostileCase>& info) {
  std::string name;
  for (const char c : info.param.scene) name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return "line" + std::to_string(info.param.line) + "_" + name;
}

INSTANTIATE_TEST_SUITE_P(Corpus, Hostile, ::testing::ValuesIn(read_manifest()), case_name);

TEST(HostileManifest, ListsEveryObjFileAndOnlyFilesThatExist) {
  const std::vector<HostileCase> cases = read_manifest();
  ASSERT_GT(cases.size(), 50u) << "MANIFEST missing or cut short";
  std::set<std::string> listed;
  for (const HostileCase& c : cases) {
    listed.insert(c.scene);
    if (c.scene[0] != '@') {
      EXPECT_TRUE(test::file_exists(kHostile + "/" + c.scene)) << c.scene;
    }
  }
  for (const fs::directory_entry& e : fs::directory_iterator(kHostile)) {
    const std::string name = e.path().filename().string();
    if (e.path().extension() == ".obj") {
      EXPECT_TRUE(listed.count(name)) << name << " is not in the MANIFEST";
    }
  }
}

}  // namespace
}  // namespace lueur
