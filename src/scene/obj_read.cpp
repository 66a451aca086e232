// The parallel OBJ read (see obj_read.h): chunking, the threads, and the join that places what a chunk could not
// place alone (relative indices, line numbers, materials named before it) and refuses what only the whole file
// shows (an index beyond the vertices so far, the memory budget), at the line a one-thread read would name.
#include "scene/obj_read.h"

#include <algorithm>
#include <atomic>

#include "core/thread_pool.h"
#include "scene/obj_loader.h"
#include "scene/obj_text.h"

namespace lueur::obj {
namespace {

using std::string_view;

/// The chunks' spans: each ends just after a '\n' (or at the end of the text), so every chunk holds whole lines and
/// a "\r\n" is never split.
std::vector<string_view> split_into_chunks(string_view text, size_t chunk_bytes) {
  std::vector<string_view> chunks;
  size_t begin = 0;
  while (begin < text.size()) {
    size_t end = text.size();
    if (text.size() - begin > chunk_bytes) {
      const size_t newline = text.find('\n', begin + chunk_bytes - 1);
      if (newline != string_view::npos) end = newline + 1;
    }
    chunks.push_back(text.substr(begin, end - begin));
    begin = end;
  }
  return chunks;
}

/// Whether a chunk parsed without the counts before it holds up once they are known: nothing refused, every index
/// in range, and no check that only the whole file can make (the budget, ear clipping's) failing within it.
bool holds_with(const ObjChunk& chunk, const ObjCounts& before, uint64_t text_bytes, const MemoryBudget& budget) {
  if (chunk.refused) return false;
  if (chunk.needed_before[0] > before.vertices || chunk.needed_before[1] > before.texcoords ||
      chunk.needed_before[2] > before.normals)
    return false;
  ObjCounts after = before;
  after.add(chunk.counts);
  // Both grow with every line, so the chunk's last line is the one to check.
  return after.triangulation_work <= kMaxTriangulationWork && scene_fits(after, text_bytes, budget);
}

/// Gives a chunk parsed without the counts before it the file's line numbers and indices.
void place(ObjChunk& chunk, const ObjCounts& before) {
  for (MtlLib& lib : chunk.mtllibs) lib.line += before.lines;
  for (UseMtl& use : chunk.usemtls) {
    use.line += before.lines;
    use.after_mtllib = use.after_mtllib || before.seen_mtllib;
  }
  for (size_t& line : chunk.empty_mtllib_lines) line += before.lines;
  const uint64_t base[3] = {before.vertices, before.texcoords, before.normals};
  for (const RelativeIndex& r : chunk.relative) {
    Corner& corner = chunk.corners[r.corner];
    uint32_t* field = r.slot == 0 ? &corner.v : r.slot == 1 ? &corner.t : &corner.n;
    *field = static_cast<uint32_t>(static_cast<int64_t>(base[r.slot]) + r.local);
  }
  free_array(chunk.relative);
}

}  // namespace

ParsedObj parse_obj(string_view text, const std::string& label, const MemoryBudget& budget,
                    const ReadSchedule& schedule) {
  ThreadPool pool(static_cast<int>(schedule.threads));
  const auto threads = static_cast<size_t>(pool.thread_count());
  const size_t chunk_bytes = schedule.chunk_bytes > 0
                                 ? schedule.chunk_bytes
                                 : std::max<size_t>(size_t{1} << 20, text.size() / (8 * threads) + 1);
  const std::vector<string_view> spans = split_into_chunks(text, chunk_bytes);

  ParsedObj parsed;
  parsed.chunks.resize(spans.size());
  std::atomic<uint64_t> memory_needed{0}, bytes_done{0};
  // Anything but a refused line (out of memory) ends the loop and is rethrown here by the pool.
  pool.parallel_for(static_cast<int>(spans.size()), [&](int k, int worker) {
    ParseContext context{label, budget, text.size()};
    context.memory_needed = &memory_needed;
    try {
      parse_chunk(spans[k], context, parsed.chunks[k]);
    } catch (const SceneError&) {
      parsed.chunks[k].refused = true;  // read again below, with the counts before it, for the message
    }
    const uint64_t done = bytes_done.fetch_add(spans[k].size()) + spans[k].size();
    // Worker 0 is the calling thread, the one progress is told from.
    if (worker == 0 && schedule.progress)
      schedule.progress(static_cast<double>(done) / static_cast<double>(text.size()));
  });

  // The join, in file order: a chunk that does not hold up with the counts before it is parsed again with them,
  // which refuses its first bad line by the file's number (or finds it sound: then its new reading stands).
  ObjCounts before;
  parsed.before.resize(spans.size());
  for (size_t k = 0; k < spans.size(); ++k) {
    ObjChunk& chunk = parsed.chunks[k];
    if (holds_with(chunk, before, text.size(), budget)) {
      place(chunk, before);
    } else {
      chunk = ObjChunk{};
      ParseContext context{label, budget, text.size()};
      context.before = &before;
      parse_chunk(spans[k], context, chunk);
    }
    parsed.before[k] = before;
    if (!before.seen_usemtl) parsed.triangles_before_usemtl += chunk.triangles_before_usemtl;
    parsed.references_normals = parsed.references_normals || chunk.references_normals;
    for (const size_t line : chunk.empty_mtllib_lines)
      parsed.warnings.push_back(label + ":" + std::to_string(line) + ": mtllib without a file name");
    parsed.mtllibs.insert(parsed.mtllibs.end(), chunk.mtllibs.begin(), chunk.mtllibs.end());
    parsed.usemtls.insert(parsed.usemtls.end(), chunk.usemtls.begin(), chunk.usemtls.end());
    before.add(chunk.counts);
  }
  parsed.totals = before;
  return parsed;
}

}  // namespace lueur::obj
