/// \file layered_chunk_codec.cpp
/// \brief Layered chunks (compressor 3, point formats 6–10). A chunk is: the first record raw;
///        its point count (u32, the raw record included); the byte size (u32) of every layer of
///        every item, in item order; then the layers in the same order.

#include "laszip_items.h"
#include "layered_items.h"

#include "io/las_format.h"

#include <algorithm>
#include <numeric>

namespace pcl_ls3d {
namespace io {
namespace laz {

namespace {

/// Where an item's bytes sit in the record.
struct ItemSlot
{
  std::size_t offset = 0, size = 0;
};

ContextSwitch
contextSwitchOf(const Item& item)
{
  return item.version >= 4 ? ContextSwitch::Version4 : ContextSwitch::Version3;
}

/// Checks the layered item list: POINT14 (30 bytes) first, since it sets the scanner channel the
/// others follow; then at most one of RGB14 (6) / RGBNIR14 (8); then at most one BYTE14 (> 0).
bool
checkLayeredItems(const LaszipVlr& vlr, std::string& error)
{
  const std::vector<Item>& items = vlr.items;
  if (items.empty() || items[0].type != ItemType::Point14 || items[0].size != 30) {
    error = "the LASzip VLR's layered item list does not start with a 30-byte POINT14";
    return false;
  }
  int rank = 0;  // 1 colour, 2 extra bytes: each at most once and in this order
  for (std::size_t i = 1; i < items.size(); ++i) {
    const Item& item = items[i];
    const bool colour = (item.type == ItemType::Rgb14 && item.size == 6) ||
                        (item.type == ItemType::RgbNir14 && item.size == 8);
    const bool bytes = item.type == ItemType::Byte14 && item.size > 0;
    const int item_rank = colour ? 1 : bytes ? 2 : 0;
    if (item_rank <= rank) {
      error = "the LASzip VLR's layered item " + std::to_string(i) + " (type " +
              std::to_string(static_cast<int>(item.type)) + ", " + std::to_string(item.size) +
              " bytes) is out of place or of the wrong size";
      return false;
    }
    rank = item_rank;
  }
  return true;
}

std::vector<ItemSlot>
slotsOf(const LaszipVlr& vlr)
{
  std::vector<ItemSlot> slots;
  std::size_t offset = 0;
  for (const Item& item : vlr.items) {
    slots.push_back({offset, item.size});
    offset += item.size;
  }
  return slots;
}

// ------------------------------------------------------------------------------------------
class LayeredChunkDecoder final : public ChunkDecoder
{
public:
  explicit LayeredChunkDecoder(const LaszipVlr& vlr)
      : slots_(slotsOf(vlr)), record_length_(vlr.recordLength())
  {
    for (const Item& item : vlr.items) {
      if (item.type == ItemType::Point14)
        coders_.push_back(makePoint14Decoder(contextSwitchOf(item)));
      else if (item.type == ItemType::Byte14)
        coders_.push_back(makeByte14Decoder(item.size, contextSwitchOf(item)));
      else
        coders_.push_back(makeRgb14Decoder(item.type == ItemType::RgbNir14, contextSwitchOf(item)));
      layer_count_ += coders_.back()->layerCount();
    }
    layers_.resize(layer_count_);
  }

  std::size_t
  decode(const std::uint8_t* begin, const std::uint8_t* end, std::size_t count, std::uint8_t* out,
         std::string& error) override
  {
    const std::size_t head = record_length_ + 4 + 4 * layer_count_;
    if (count == 0) {
      error = "a LAZ chunk of 0 points was requested";
      return 0;
    }
    if (end < begin || static_cast<std::size_t>(end - begin) < head) {
      error = "a layered LAZ chunk is truncated before its layer-size table";
      return 0;
    }
    const std::size_t stored = las::get<std::uint32_t>(begin + record_length_);
    if (stored != count) {
      error = "a layered LAZ chunk holds " + std::to_string(stored) + " points where " +
              std::to_string(count) + " were expected";
      return 0;
    }
    std::size_t layer_bytes = 0;
    if (!mapLayers(begin + record_length_ + 4, begin + head, end, layer_bytes)) {
      error = "a layered LAZ chunk's layers run past the end of the chunk data";
      return 0;
    }
    std::copy(begin, begin + record_length_, out);
    decodeRecords(out, count);
    // A one-point chunk decodes nothing from its layers (a writer may leave them all empty).
    for (std::size_t i = 0; i < coders_.size() && count > 1; ++i) {
      if (coders_[i]->overrun() != 0) {
        error = "a layered LAZ chunk's layers of item " + std::to_string(i) +
                " end before its records do (corrupt data)";
        return 0;
      }
    }
    return head + layer_bytes;
  }

private:
  /// Points layers_ at the layer bytes that follow the size table; false when they do not all
  /// fit before `end`.
  bool
  mapLayers(const std::uint8_t* table, const std::uint8_t* data, const std::uint8_t* end, std::size_t& total)
  {
    const auto room = static_cast<std::size_t>(end - data);
    total = 0;
    for (std::size_t i = 0; i < layer_count_; ++i) {
      const std::size_t n = las::get<std::uint32_t>(table + 4 * i);
      if (n > room - total)
        return false;
      layers_[i] = {data + total, n};
      total += n;
    }
    return true;
  }

  void
  decodeRecords(std::uint8_t* out, std::size_t count)
  {
    unsigned channel = 0;
    const Layer* layers = layers_.data();
    for (std::size_t k = 0; k < coders_.size(); ++k) {
      coders_[k]->start(out + slots_[k].offset, layers, channel);
      layers += coders_[k]->layerCount();
    }
    for (std::size_t i = 1; i < count; ++i) {
      std::uint8_t* record = out + i * record_length_;
      channel = 0;  // LASzip's per-record context (see ContextSwitch)
      for (std::size_t k = 0; k < coders_.size(); ++k)
        coders_[k]->decode(record + slots_[k].offset, channel);
    }
  }

  std::vector<ItemSlot> slots_;
  std::size_t record_length_;
  std::vector<std::unique_ptr<LayeredItemDecoder>> coders_;
  std::size_t layer_count_ = 0;
  std::vector<Layer> layers_;
};

// ------------------------------------------------------------------------------------------
class LayeredChunkEncoder final : public ChunkEncoder
{
public:
  explicit LayeredChunkEncoder(const LaszipVlr& vlr)
      : slots_(slotsOf(vlr)), record_length_(vlr.recordLength())
  {
    for (const Item& item : vlr.items) {
      if (item.type == ItemType::Point14)
        coders_.push_back(makePoint14Encoder(contextSwitchOf(item)));
      else if (item.type == ItemType::Byte14)
        coders_.push_back(makeByte14Encoder(item.size, contextSwitchOf(item)));
      else
        coders_.push_back(makeRgb14Encoder(item.type == ItemType::RgbNir14, contextSwitchOf(item)));
      layer_count_ += coders_.back()->layerCount();
    }
    layers_.resize(layer_count_);
  }

  void
  encode(const std::uint8_t* records, std::size_t count, std::vector<std::uint8_t>& out) override
  {
    if (count == 0)
      return;
    encodeRecords(records, count);
    const std::size_t at = out.size();
    const std::size_t bytes =
        std::accumulate(layers_.begin(), layers_.end(), std::size_t(0),
                        [](std::size_t n, const std::vector<std::uint8_t>& l) { return n + l.size(); });
    out.resize(at + record_length_ + 4 + 4 * layer_count_ + bytes);
    std::uint8_t* p = out.data() + at;
    p = std::copy(records, records + record_length_, p);
    las::put<std::uint32_t>(p, static_cast<std::uint32_t>(count));
    p += 4;
    for (const std::vector<std::uint8_t>& layer : layers_) {
      las::put<std::uint32_t>(p, static_cast<std::uint32_t>(layer.size()));
      p += 4;
    }
    for (const std::vector<std::uint8_t>& layer : layers_)
      p = std::copy(layer.begin(), layer.end(), p);
  }

private:
  void
  encodeRecords(const std::uint8_t* records, std::size_t count)
  {
    unsigned channel = 0;
    for (std::size_t k = 0; k < coders_.size(); ++k)
      coders_[k]->start(records + slots_[k].offset, channel);
    for (std::size_t i = 1; i < count; ++i) {
      const std::uint8_t* record = records + i * record_length_;
      channel = 0;  // LASzip's per-record context (see ContextSwitch)
      for (std::size_t k = 0; k < coders_.size(); ++k)
        coders_[k]->encode(record + slots_[k].offset, channel);
    }
    std::vector<std::uint8_t>* layers = layers_.data();
    for (const auto& coder : coders_) {
      coder->finish(layers);
      layers += coder->layerCount();
    }
  }

  std::vector<ItemSlot> slots_;
  std::size_t record_length_;
  std::vector<std::unique_ptr<LayeredItemEncoder>> coders_;
  std::size_t layer_count_ = 0;
  std::vector<std::vector<std::uint8_t>> layers_;
};

}  // namespace

std::unique_ptr<ChunkDecoder>
makeLayeredChunkDecoder(const LaszipVlr& vlr, std::string& error)
{
  if (!checkLayeredItems(vlr, error))
    return nullptr;
  return std::make_unique<LayeredChunkDecoder>(vlr);
}

std::unique_ptr<ChunkEncoder>
makeLayeredChunkEncoder(const LaszipVlr& vlr, std::string& error)
{
  if (!checkLayeredItems(vlr, error))
    return nullptr;
  return std::make_unique<LayeredChunkEncoder>(vlr);
}

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
