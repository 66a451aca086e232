// The layers hold: every source file includes only from its own folder and the folders below it (the README's
// layout), and the core library never sees GL, GLFW or ImGui. Reads the sources in src/, so a new include that
// runs back up fails here, naming the file and the line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>

namespace lueur {
namespace {

namespace fs = std::filesystem;

/// Which folders each folder of src/ may include from (itself included).
/// The folders of the core library up to the integrator: the film and the L1 store sit beside light choice, below
/// the integrator, and see neither each other nor it.
const std::set<std::string> kBelowRuntime = {"core",   "scene", "bvh",  "accel", "passes",
                                             "lights", "store", "film", "integrator"};

std::set<std::string> with(std::set<std::string> folders, std::initializer_list<std::string> more) {
  folders.insert(more.begin(), more.end());
  return folders;
}

const std::map<std::string, std::set<std::string>> kAllowed = {
    {"core", {"core"}},
    {"scene", {"core", "scene"}},
    {"bvh", {"core", "bvh"}},
    {"accel", {"core", "bvh", "accel"}},
    {"passes", {"core", "passes"}},
    {"lights", {"core", "scene", "passes", "lights"}},
    {"store", {"core", "store"}},
    {"film", {"core", "passes", "film"}},
    {"integrator", kBelowRuntime},
    {"runtime", with(kBelowRuntime, {"runtime"})},
    {"settings", with(kBelowRuntime, {"runtime", "settings"})},
    {"image", {"core", "passes", "film", "image"}},
    {"display", with(kBelowRuntime, {"runtime", "settings", "image", "display"})},
    {"ui", with(kBelowRuntime, {"runtime", "settings", "image", "display", "ui"})},
    {"app", with(kBelowRuntime, {"runtime", "settings", "image", "display", "ui", "app"})},
    {"bench", with(kBelowRuntime, {"runtime", "settings", "image", "bench"})},
    {"mpi", with(kBelowRuntime, {"runtime", "settings", "image", "display", "ui", "app", "mpi"})},
};

/// The core library's folders: no windowing, GL or UI library.
const std::set<std::string> kCore = with(kBelowRuntime, {"runtime", "settings", "image"});

struct Include {
  std::string file, header;
  int line = 0;
};

std::vector<Include> includes_under(const fs::path& folder) {
  std::vector<Include> found;
  const std::regex include_line(R"(^\s*#\s*include\s*[<"]([^>"]+)[>"])");
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    if (!entry.is_regular_file()) continue;
    std::ifstream in(entry.path());
    std::string text;
    int line = 0;
    while (std::getline(in, text)) {
      ++line;
      std::smatch match;
      if (std::regex_search(text, match, include_line))
        found.push_back({entry.path().lexically_relative(folder.parent_path()).string(), match[1], line});
    }
  }
  return found;
}

TEST(Layers, EveryFolderIncludesOnlyFromItselfAndTheFoldersBelow) {
  const fs::path src = fs::path(LUEUR_SOURCE_DIR) / "src";
  std::set<std::string> folders_seen;
  size_t checked = 0;
  for (const auto& entry : fs::directory_iterator(src)) {
    if (!entry.is_directory()) continue;
    const std::string folder = entry.path().filename().string();
    folders_seen.insert(folder);
    ASSERT_TRUE(kAllowed.count(folder)) << "src/" << folder << " is not in the layer table: add it here and to the "
                                        << "README's layout";
    for (const Include& include : includes_under(entry.path())) {
      const size_t slash = include.header.find('/');
      if (slash == std::string::npos) continue;
      const std::string target = include.header.substr(0, slash);
      if (kAllowed.count(target) && !kAllowed.at(folder).count(target))
        ADD_FAILURE() << "src/" << include.file << ":" << include.line << " includes " << include.header << ": "
                      << folder << " may not depend on " << target;
      ++checked;
    }
  }
  EXPECT_EQ(folders_seen.size(), kAllowed.size()) << "a folder of the layer table is gone from src/";
  EXPECT_GT(checked, 100u) << "too few of Lueur's own includes found: is LUEUR_SOURCE_DIR right?";
}

TEST(Layers, TheCoreLibraryNeverSeesGlGlfwOrImGui) {
  const fs::path src = fs::path(LUEUR_SOURCE_DIR) / "src";
  const std::regex windowing(R"(^(GL|GLFW|EGL|KHR)/|^imgui|osmesa|glad|epoxy)");
  for (const std::string& folder : kCore)
    for (const Include& include : includes_under(src / folder))
      EXPECT_FALSE(std::regex_search(include.header, windowing))
          << "src/" << include.file << ":" << include.line << " includes " << include.header;
}

TEST(Layers, OnlyLueurMpiSeesMpi) {
  const fs::path src = fs::path(LUEUR_SOURCE_DIR) / "src";
  size_t seen = 0;
  for (const auto& [folder, below] : kAllowed)
    for (const Include& include : includes_under(src / folder)) {
      if (include.header != "mpi.h") continue;
      ++seen;
      EXPECT_EQ(folder, "mpi") << "src/" << include.file << ":" << include.line << " includes mpi.h";
    }
  EXPECT_GT(seen, 0u) << "src/mpi no longer includes mpi.h: is this test still looking at the right thing?";
}

}  // namespace
}  // namespace lueur
