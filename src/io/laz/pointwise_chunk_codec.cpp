/// \file pointwise_chunk_codec.cpp
/// \brief The chunk codec of LASzip's pointwise compressors (1 and 2, point formats 0–5): a
///        chunk is its first record raw, then one arithmetic stream in which every following
///        record is coded item after item (pointwise_items.h).

#include "laszip_items.h"
#include "pointwise_items.h"

#include <cstring>

namespace pcl_ls3d {
namespace io {
namespace laz {

namespace {

/// \brief The item coders of one record layout, each with its byte offset in the record.
struct PointwiseItems
{
  std::vector<std::unique_ptr<PointwiseItemCoder>> coders;
  std::vector<std::size_t> offsets;
  std::size_t record_length = 0;

  void
  init(const std::uint8_t* first)
  {
    for (std::size_t i = 0; i < coders.size(); ++i)
      coders[i]->init(first + offsets[i]);
  }
};

std::unique_ptr<PointwiseItemCoder>
makeItemCoder(const Item& item, std::string& error)
{
  const int v = item.version;
  switch (item.type) {
  case ItemType::Point10:
    if (item.size == 20)
      return v == 1 ? makePoint10CoderV1() : makePoint10CoderV2();
    break;
  case ItemType::GpsTime11:
    if (item.size == 8)
      return v == 1 ? makeGpsTime11CoderV1() : makeGpsTime11CoderV2();
    break;
  case ItemType::Rgb12:
    if (item.size == 6)
      return makeRgb12Coder(v);
    break;
  case ItemType::Byte:
    return makeByteCoder(v, item.size);
  default:
    error = "item type " + std::to_string(static_cast<int>(item.type)) + " is not a pointwise LASzip item";
    return nullptr;
  }
  error = "LASzip item type " + std::to_string(static_cast<int>(item.type)) + " of " +
          std::to_string(item.size) + " bytes has the wrong size";
  return nullptr;
}

bool
makeItems(const LaszipVlr& vlr, PointwiseItems& items, std::string& error)
{
  for (const Item& item : vlr.items) {
    if (item.version < 1 || item.version > 2) {
      error = "pointwise LASzip items have versions 1 and 2, not " + std::to_string(item.version);
      return false;
    }
    std::unique_ptr<PointwiseItemCoder> coder = makeItemCoder(item, error);
    if (!coder)
      return false;
    items.coders.push_back(std::move(coder));
    items.offsets.push_back(items.record_length);
    items.record_length += item.size;
  }
  return true;
}

class PointwiseChunkDecoder final : public ChunkDecoder
{
public:
  explicit PointwiseChunkDecoder(PointwiseItems items) : items_(std::move(items))
  {}

  std::size_t
  decode(const std::uint8_t* begin, const std::uint8_t* end, std::size_t count, std::uint8_t* out,
         std::string& error) override;

private:
  PointwiseItems items_;
  ArithmeticDecoder dec_;
};

std::size_t
PointwiseChunkDecoder::decode(const std::uint8_t* begin, const std::uint8_t* end, std::size_t count,
                              std::uint8_t* out, std::string& error)
{
  const std::size_t length = items_.record_length;
  if (count == 0) {
    error = "a chunk of 0 points";
    return 0;
  }
  if (static_cast<std::size_t>(end - begin) < length) {
    error = "the chunk's " + std::to_string(end - begin) + " bytes end inside its first record";
    return 0;
  }
  std::memcpy(out, begin, length);
  items_.init(out);
  dec_.start(begin + length, end);
  for (std::size_t i = 1; i < count && dec_.overrun() == 0; ++i) {
    std::uint8_t* record = out + i * length;
    for (std::size_t k = 0; k < items_.coders.size(); ++k)
      if (!items_.coders[k]->decode(dec_, record + items_.offsets[k])) {
        error = "corrupt chunk: point " + std::to_string(i) + " holds a code no LASzip encoder writes";
        return 0;
      }
  }
  if (dec_.overrun() != 0) {
    error = "corrupt or truncated chunk: its " + std::to_string(count) + " points need more than its " +
            std::to_string(end - begin) + " bytes";
    return 0;
  }
  return length + dec_.consumed();
}

class PointwiseChunkEncoder final : public ChunkEncoder
{
public:
  explicit PointwiseChunkEncoder(PointwiseItems items) : items_(std::move(items))
  {}

  void
  encode(const std::uint8_t* records, std::size_t count, std::vector<std::uint8_t>& out) override
  {
    if (count == 0)
      return;
    const std::size_t length = items_.record_length;
    out.insert(out.end(), records, records + length);
    items_.init(records);
    enc_.start();
    for (std::size_t i = 1; i < count; ++i) {
      const std::uint8_t* record = records + i * length;
      for (std::size_t k = 0; k < items_.coders.size(); ++k)
        items_.coders[k]->encode(enc_, record + items_.offsets[k]);
    }
    const std::vector<std::uint8_t>& bytes = enc_.finish();
    out.insert(out.end(), bytes.begin(), bytes.end());
  }

private:
  PointwiseItems items_;
  ArithmeticEncoder enc_;
};

}  // namespace

std::unique_ptr<ChunkDecoder>
makePointwiseChunkDecoder(const LaszipVlr& vlr, std::string& error)
{
  PointwiseItems items;
  if (!makeItems(vlr, items, error))
    return nullptr;
  return std::make_unique<PointwiseChunkDecoder>(std::move(items));
}

std::unique_ptr<ChunkEncoder>
makePointwiseChunkEncoder(const LaszipVlr& vlr, std::string& error)
{
  PointwiseItems items;
  if (!makeItems(vlr, items, error))
    return nullptr;
  return std::make_unique<PointwiseChunkEncoder>(std::move(items));
}

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
