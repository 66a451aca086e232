// The resume state's format: a magic line, the identity, per side its film (exact sums and snapshots) and then its
// L1 store, and a final FNV-1a checksum of everything before it. Little-endian, as the machines Lueur runs on.
#include "runtime/resume_state.h"

#include <bit>
#include <cmath>
#include <stdexcept>

#include "core/byte_stream.h"

namespace lueur {
namespace {

/// The version counts changes of the layout and of what the frames draw: a state of frames sampled otherwise (2: Le's
/// own rays, runs of samples a power of two apart; 3: the further-bounce layer ln among the layers; 4: the store's
/// cells hold ln's further light) would resume into bytes no uninterrupted render gives.
constexpr std::string_view kMagic = "LUEUR-STATE 4\n";

uint32_t layer_mask(const Film& film) {
  uint32_t mask = 0;
  for (size_t l = 0; l < kLayerCount; ++l)
    if (!film.exact[l].empty()) mask |= 1u << l;
  return mask;
}

void write_film(ByteWriter& out, const Film& film) {
  out.put<int32_t>(film.width);
  out.put<int32_t>(film.height);
  out.put<uint64_t>(film.frames);
  out.put<double>(film.unit);
  out.put<uint32_t>(layer_mask(film));
  for (const auto& layer : film.exact)
    if (!layer.empty()) out.put_array(layer);
  for (const PassSnapshot& snapshot : film.checkpoints) {
    out.put<uint64_t>(snapshot.frames);
    for (const auto& pass : snapshot.sums) out.put_array(pass);
  }
}

void read_film(ByteReader& in, Film& film) {
  const int32_t width = in.get<int32_t>("the image size"), height = in.get<int32_t>("the image size");
  if (width != film.width || height != film.height)
    throw std::runtime_error("it holds a " + std::to_string(width) + "x" + std::to_string(height) + " image, not " +
                             std::to_string(film.width) + "x" + std::to_string(film.height));
  const uint64_t frames = in.get<uint64_t>("the frame count");
  const double unit = in.get<double>("the film's unit");
  // The unit is a power of two (film_unit): the exact sums' products with it are then exact, and a unit of any
  // other value is no film Lueur wrote.
  int exponent = 0;
  if (!(unit > 0.0) || !std::isfinite(unit) || std::frexp(unit, &exponent) != 0.5)
    throw std::runtime_error("it holds an impossible film unit (not a power of two)");
  if (in.get<uint32_t>("the passes") != layer_mask(film))
    throw std::runtime_error("it was rendered with other passes or reuse layers");
  const uint64_t channels = 3 * film.pixel_count();
  for (auto& layer : film.exact) {
    if (layer.empty()) continue;
    layer = in.get_array<int64_t>(channels, "the sums");
    if (layer.size() != channels) throw std::runtime_error("its sums are not of the image's size");
  }
  // The snapshots stand at the highest power of two of the frames, then at its halves (or at none, 0, where a
  // reduction passed them): any other count would make the noise estimate compare sums of other frames.
  const uint64_t newest = frames == 0 ? 0 : std::bit_floor(frames);
  for (size_t c = 0; c < film.checkpoints.size(); ++c) {
    PassSnapshot& snapshot = film.checkpoints[c];
    snapshot.frames = in.get<uint64_t>("the noise snapshots");
    if (snapshot.frames != 0 && snapshot.frames != (newest >> c))
      throw std::runtime_error("its noise snapshots are at impossible frame counts");
    for (auto& pass : snapshot.sums) {
      pass = in.get_array<float>(channels, "the noise snapshots");
      if (!pass.empty() && pass.size() != channels)
        throw std::runtime_error("its snapshots are not of the image's size");
    }
  }
  film.frames = frames;
  film.unit = unit;
  film.refresh_sums();
}

}  // namespace

std::string encode_resume_state(const RenderIdentity& identity, const std::vector<const Accumulation*>& sides) {
  ByteWriter out;
  out.bytes.append(kMagic);
  out.put<uint64_t>(identity.size());
  for (const std::string& line : identity) out.put_string(line);
  out.put<uint64_t>(sides.size());
  for (const Accumulation* side : sides) {
    write_film(out, side->film);
    side->store.write_state(out);
  }
  out.put<uint64_t>(fnv1a64(out.bytes));
  return std::move(out.bytes);
}

void decode_resume_state(std::string_view bytes, const RenderIdentity& identity,
                         const std::vector<Accumulation*>& sides) {
  if (bytes.substr(0, kMagic.size()) != kMagic) {
    if (bytes.substr(0, 12) == kMagic.substr(0, 12)) throw std::runtime_error("it is a state file of another version");
    throw std::runtime_error("it is not a Lueur state file");
  }
  if (bytes.size() < kMagic.size() + sizeof(uint64_t)) throw std::runtime_error("it is cut short");
  ByteReader checksum{bytes.substr(bytes.size() - sizeof(uint64_t))};
  if (checksum.get<uint64_t>("the checksum") != fnv1a64(bytes.substr(0, bytes.size() - sizeof(uint64_t))))
    throw std::runtime_error("it is cut short or altered (its checksum does not match)");
  ByteReader in{bytes.substr(kMagic.size(), bytes.size() - kMagic.size() - sizeof(uint64_t))};
  try {
    const uint64_t lines = in.get<uint64_t>("the settings");
    RenderIdentity stored;
    for (uint64_t i = 0; i < lines && i < 10000; ++i) stored.push_back(in.get_string("the settings"));
    for (size_t i = 0; i < std::max(stored.size(), identity.size()); ++i) {
      const std::string was = i < stored.size() ? stored[i] : "(nothing)";
      const std::string now = i < identity.size() ? identity[i] : "(nothing)";
      if (was != now) throw std::runtime_error("it was rendered with " + was + ", not " + now);
    }
    if (in.get<uint64_t>("the films") != sides.size())
      throw std::runtime_error("it holds another number of images (an A/B split or not)");
    for (Accumulation* side : sides) {
      read_film(in, side->film);
      side->store.read_state(in);
    }
  } catch (const ByteStreamError& e) {
    throw std::runtime_error(std::string("it is malformed: ") + e.what());
  }
}

}  // namespace lueur
