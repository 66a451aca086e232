// Reads an OBJ text on every core: splits it into chunks at line boundaries, parses them at once (obj_parse.h) and
// joins them in file order, so that the result, and the first refused line's message, are those of a one-thread
// read. Internal to src/scene; depends on core and obj_parse.h only.
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "scene/obj_parse.h"

namespace lueur::obj {

/// An OBJ text parsed: its chunks in file order with every index placed and every line number the file's, and
/// what the lines add up to.
struct ParsedObj {
  std::vector<ObjChunk> chunks;
  std::vector<ObjCounts> before;  ///< the counts of the lines before each chunk
  ObjCounts totals;
  std::vector<MtlLib> mtllibs;
  std::vector<UseMtl> usemtls;
  std::vector<std::string> warnings;
  uint64_t triangles_before_usemtl = 0;  ///< triangles of faces above the file's first usemtl
  bool references_normals = false;
};

/// How parse_obj splits and schedules the work.
struct ReadSchedule {
  size_t chunk_bytes = 0;  ///< 0: a size giving every thread several chunks (1 MiB at least)
  unsigned threads = 0;    ///< 0: every core
  /// Told the share of the text parsed so far (0 to 1), from the calling thread. May be empty.
  std::function<void(double done)> progress;
};

/// Parses `text` (reported as `label`); throws SceneError "label:line: ..." for the first line refused, as a
/// one-thread read would, whatever the chunks.
ParsedObj parse_obj(std::string_view text, const std::string& label, const MemoryBudget& budget,
                    const ReadSchedule& schedule = {});

}  // namespace lueur::obj
