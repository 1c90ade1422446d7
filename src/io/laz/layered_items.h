#pragma once
/// \file layered_items.h
/// \brief Private: the item coders of LASzip's layered chunks (compressor 3, point formats 6–10).
///        A layered chunk stores its first record raw, then one arithmetic stream ("layer") per
///        field group, so a reader can skip the fields it does not need and a writer can drop a
///        layer whose field never changed in the chunk. Every item keeps up to four contexts, one
///        per scanner channel: POINT14 chooses the channel, the other items follow it.

#include "arithmetic_decoder.h"
#include "arithmetic_encoder.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace pcl_ls3d {
namespace io {
namespace laz {

/// One layer of a chunk as stored: empty when the writer left it out (its field never changed).
struct Layer
{
  const std::uint8_t* data = nullptr;
  std::size_t size = 0;
};

/// \brief Decodes one item of every record of a chunk, from that item's layers.
class LayeredItemDecoder
{
public:
  virtual ~LayeredItemDecoder() = default;
  /// Number of layers (and of 32-bit sizes in the chunk's size table) this item owns.
  virtual std::size_t
  layerCount() const = 0;
  /// Starts a chunk from its raw first record (this item's bytes) and this item's layers.
  /// `channel` is the scanner channel: POINT14 sets it, the other items read it.
  virtual void
  start(const std::uint8_t* first, const Layer* layers, unsigned& channel) = 0;
  /// Decodes the item of the next record into `item`. The chunk codec sets `channel` to 0 before
  /// each record, as LASzip does (see ContextSwitch).
  virtual void
  decode(std::uint8_t* item, unsigned& channel) = 0;
  /// Bytes the item's layers were asked for beyond their ends (0 for a well-formed chunk).
  virtual std::size_t
  overrun() const = 0;
};

/// \brief Encodes one item of every record of a chunk into that item's layers.
class LayeredItemEncoder
{
public:
  virtual ~LayeredItemEncoder() = default;
  virtual std::size_t
  layerCount() const = 0;
  /// Starts a chunk whose first record (stored raw by the caller) has this item `first`.
  virtual void
  start(const std::uint8_t* first, unsigned& channel) = 0;
  virtual void
  encode(const std::uint8_t* item, unsigned& channel) = 0;
  /// Ends the chunk: layer i of this item into `layers[i]` (left empty when the field never
  /// changed, as LASzip writes it).
  virtual void
  finish(std::vector<std::uint8_t>* layers) = 0;
};

/// Scanner channels, and so contexts, per item (two bits in the record).
constexpr unsigned kChannels = 4;

/// LASzip's item versions 3 and 4 differ only in how the scanner channel reaches the RGB / NIR /
/// BYTE coders, and version 3's way is part of its format:
/// - version 3's POINT14 hands the channel on only for a record where it changed; for every other
///   record the others receive channel 0 (LASzip's per-record context variable starts at 0), so
///   they drift into context 0 after the first record;
/// - after a switch to a context already in use, version 3's RGB / NIR / BYTE coders predict that
///   record from (and store it into) the previous context's last value.
/// Version 4 hands on the true channel for every record and uses the new context's own value.
enum class ContextSwitch
{
  Version3,
  Version4
};

/// Switches an RGB / NIR / BYTE coder to `channel` and returns the last value its next record is
/// predicted from. `init(context, from)` starts an unused context from the last value `from`.
template <typename Context, typename Init>
auto*
switchChannel(std::array<Context, kChannels>& contexts, unsigned& current, unsigned channel,
              ContextSwitch rule, Init init)
{
  auto* last = contexts[current].last.data();
  channel &= kChannels - 1;
  if (channel == current)
    return last;
  current = channel;
  if (!contexts[current].in_use) {
    init(contexts[current], last);
    return contexts[current].last.data();
  }
  return rule == ContextSwitch::Version4 ? contexts[current].last.data() : last;
}

// The item coders (point14_coder.cpp, rgb14_coder.cpp, byte14_coder.cpp).
std::unique_ptr<LayeredItemDecoder>
makePoint14Decoder(ContextSwitch rule);
std::unique_ptr<LayeredItemEncoder>
makePoint14Encoder(ContextSwitch rule);
/// RGB14 (6 bytes) or, with `nir`, RGBNIR14 (8 bytes).
std::unique_ptr<LayeredItemDecoder>
makeRgb14Decoder(bool nir, ContextSwitch rule);
std::unique_ptr<LayeredItemEncoder>
makeRgb14Encoder(bool nir, ContextSwitch rule);
/// BYTE14: `count` extra bytes, one layer each.
std::unique_ptr<LayeredItemDecoder>
makeByte14Decoder(std::size_t count, ContextSwitch rule);
std::unique_ptr<LayeredItemEncoder>
makeByte14Encoder(std::size_t count, ContextSwitch rule);

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
