// lueur: the entry point. Parses the command line and runs the headless renderer; every error becomes one line on
// stderr and exit status 2.
#include <cstdio>
#include <exception>
#include <new>

#include "app/headless.h"
#include "app/options.h"
#include "app/scene_export.h"
#include "app/viewer.h"
#include "core/atomic_file.h"
#include "core/memory_budget.h"
#include "scene/default_scene.h"
#include "scene/obj_loader.h"
#include "scene/obj_writer.h"

int main(int argc, char** argv) {
  using namespace lueur;
  map_large_arrays_alone();
  try {
    const std::optional<AppOptions> options = parse_command_line(argc, argv);
    if (!options) return 0;
    if (!options->export_default_scene.empty()) {
      check_export_path(options->export_default_scene);
      write_obj(make_default_scene(), options->export_default_scene);
      std::printf("%s\n", options->export_default_scene.c_str());
      return 0;
    }
    if (!options->export_scene.empty()) {
      export_scene(*options);
      return 0;
    }
    if (!options->headless) return run_viewer(*options);
    return run_headless(*options);
  } catch (const UsageError& e) {
    std::fprintf(stderr, "lueur: error: %s (see lueur --help)\n", e.what());
  } catch (const SceneError& e) {
    std::fprintf(stderr, "lueur: error: %s\n", e.what());
  } catch (const IoError& e) {
    std::fprintf(stderr, "lueur: error: %s\n", e.what());
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "lueur: error: out of memory\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lueur: error: %s\n", e.what());
  }
  return 2;
}
