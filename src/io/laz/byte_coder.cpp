/// \file byte_coder.cpp
/// \brief BYTE: the extra bytes after a format's fields, each coded against the same byte of the
///        previous record (version 1 through the integer compressor, one context per byte;
///        version 2 as the byte difference, one adaptive model per byte).

#include "integer_compressor.h"
#include "pointwise_items.h"

#include <cstring>
#include <vector>

namespace pcl_ls3d {
namespace io {
namespace laz {

namespace {

class ByteCoderV1 final : public PointwiseItemCoder
{
public:
  explicit ByteCoderV1(std::size_t n) : last_(n), ic_(8, static_cast<std::uint32_t>(n))
  {}

  void
  init(const std::uint8_t* first) override
  {
    ic_.reset();
    std::memcpy(last_.data(), first, last_.size());
  }

  bool
  decode(ArithmeticDecoder& dec, std::uint8_t* out) override
  {
    for (std::uint32_t i = 0; i < last_.size(); ++i)
      last_[i] = static_cast<std::uint8_t>(ic_.decompress(dec, last_[i], i));
    std::memcpy(out, last_.data(), last_.size());
    return true;
  }

  void
  encode(ArithmeticEncoder& enc, const std::uint8_t* item) override
  {
    for (std::uint32_t i = 0; i < last_.size(); ++i)
      ic_.compress(enc, last_[i], item[i], i);
    std::memcpy(last_.data(), item, last_.size());
  }

private:
  std::vector<std::uint8_t> last_;
  IntegerCompressor ic_;
};

class ByteCoderV2 final : public PointwiseItemCoder
{
public:
  explicit ByteCoderV2(std::size_t n) : last_(n), models_(n, SymbolModel(256))
  {}

  void
  init(const std::uint8_t* first) override
  {
    for (SymbolModel& m : models_)
      m.reset();
    std::memcpy(last_.data(), first, last_.size());
  }

  bool
  decode(ArithmeticDecoder& dec, std::uint8_t* out) override
  {
    for (std::size_t i = 0; i < last_.size(); ++i)
      last_[i] = foldByte(static_cast<int>(dec.decodeSymbol(models_[i])) + last_[i]);
    std::memcpy(out, last_.data(), last_.size());
    return true;
  }

  void
  encode(ArithmeticEncoder& enc, const std::uint8_t* item) override
  {
    for (std::size_t i = 0; i < last_.size(); ++i)
      enc.encodeSymbol(models_[i], foldByte(item[i] - last_[i]));
    std::memcpy(last_.data(), item, last_.size());
  }

private:
  std::vector<std::uint8_t> last_;
  std::vector<SymbolModel> models_;
};

}  // namespace

std::unique_ptr<PointwiseItemCoder>
makeByteCoder(int version, std::size_t bytes)
{
  if (version == 1)
    return std::make_unique<ByteCoderV1>(bytes);
  return std::make_unique<ByteCoderV2>(bytes);
}

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
