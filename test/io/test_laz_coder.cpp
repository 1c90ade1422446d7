/// \file test_laz_coder.cpp
/// \brief The LASzip arithmetic coder and integer compressor: whatever the encoder writes, the
///        decoder reads back, for every kind of symbol, across model updates and carries; and
///        garbage or truncated streams decode without reading outside their range.

#include "io/laz/arithmetic_decoder.h"
#include "io/laz/arithmetic_encoder.h"
#include "io/laz/integer_compressor.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

using namespace pcl_ls3d::io::laz;

namespace {

/// One coded item: what kind of call, its model (if any), its value.
struct Op
{
  int kind;  // 0 bit model, 1 symbol model, 2 raw bits, 3 short, 4 int, 5 int64, 6 int compressor
  int model;
  std::uint64_t value;
  std::int32_t pred = 0;
  std::uint32_t bits = 0;
};

std::vector<Op>
randomOps(std::mt19937_64& rng, std::size_t n)
{
  std::vector<Op> ops;
  std::uniform_int_distribution<int> kind(0, 6);
  for (std::size_t i = 0; i < n; ++i) {
    Op op{kind(rng), 0, 0};
    switch (op.kind) {
    case 0:
      op.model = rng() % 3;
      op.value = (rng() % 10) < 8 ? 0 : 1;
      break;  // skewed bits
    case 1:
      op.model = rng() % 4;
      op.value = rng() % (op.model == 0 ? 2 : op.model == 1 ? 17 : op.model == 2 ? 256 : 2048);
      if (rng() % 2)
        op.value %= 3;  // skew so the models adapt
      break;
    case 2:
      op.bits = 1 + rng() % 32;
      op.value = rng() & (op.bits == 32 ? 0xFFFFFFFFull : ((1ull << op.bits) - 1));
      break;
    case 3:
      op.value = rng() & 0xFFFF;
      break;
    case 4:
      op.value = rng() & 0xFFFFFFFF;
      break;
    case 5:
      op.value = rng();
      break;
    case 6:
      op.model = rng() % 3;
      op.pred = static_cast<std::int32_t>(rng());
      op.value = static_cast<std::uint32_t>(op.pred + static_cast<std::int32_t>(rng() % 2001) - 1000);
      if (rng() % 8 == 0)
        op.value = static_cast<std::uint32_t>(rng());
      break;
    }
    ops.push_back(op);
  }
  return ops;
}

struct Models
{
  BitModel bits[3];
  SymbolModel symbols[4] = {SymbolModel(2), SymbolModel(17), SymbolModel(256), SymbolModel(2048)};
  IntegerCompressor ic32{32, 2};
  IntegerCompressor ic16{16, 1, 8};
  IntegerCompressor ic_range{0, 1, 8, 1000};
};

}  // namespace

TEST(LazCoder, EveryKindOfSymbolRoundTrips)
{
  std::mt19937_64 rng(42);
  const std::vector<Op> ops = randomOps(rng, 200000);
  Models em;
  ArithmeticEncoder enc;
  enc.start();
  for (const Op& op : ops) {
    switch (op.kind) {
    case 0:
      enc.encodeBit(em.bits[op.model], static_cast<std::uint32_t>(op.value));
      break;
    case 1:
      enc.encodeSymbol(em.symbols[op.model], static_cast<std::uint32_t>(op.value));
      break;
    case 2:
      enc.writeBits(op.bits, static_cast<std::uint32_t>(op.value));
      break;
    case 3:
      enc.writeShort(static_cast<std::uint32_t>(op.value));
      break;
    case 4:
      enc.writeInt(static_cast<std::uint32_t>(op.value));
      break;
    case 5:
      enc.writeInt64(op.value);
      break;
    case 6:
      if (op.model == 0)
        em.ic32.compress(enc, op.pred, static_cast<std::int32_t>(op.value), 1);
      else if (op.model == 1)
        em.ic16.compress(enc, op.pred & 0xFFFF, static_cast<std::int32_t>(op.value & 0xFFFF));
      else
        em.ic_range.compress(enc, op.pred % 1000 < 0 ? -(op.pred % 1000) : op.pred % 1000,
                             static_cast<std::int32_t>(op.value % 1000));
      break;
    }
  }
  const std::vector<std::uint8_t> bytes = enc.finish();

  Models dm;
  ArithmeticDecoder dec(bytes.data(), bytes.data() + bytes.size());
  std::size_t wrong = 0;
  for (const Op& op : ops) {
    std::uint64_t got = 0, want = op.value;
    switch (op.kind) {
    case 0:
      got = dec.decodeBit(dm.bits[op.model]);
      break;
    case 1:
      got = dec.decodeSymbol(dm.symbols[op.model]);
      break;
    case 2:
      got = dec.readBits(op.bits);
      break;
    case 3:
      got = dec.readShort();
      break;
    case 4:
      got = dec.readInt();
      break;
    case 5:
      got = dec.readInt64();
      break;
    case 6:
      if (op.model == 0)
        got = static_cast<std::uint32_t>(dm.ic32.decompress(dec, op.pred, 1));
      else if (op.model == 1) {
        got = static_cast<std::uint32_t>(dm.ic16.decompress(dec, op.pred & 0xFFFF));
        want &= 0xFFFF;
      } else {
        got = static_cast<std::uint32_t>(
            dm.ic_range.decompress(dec, op.pred % 1000 < 0 ? -(op.pred % 1000) : op.pred % 1000));
        want %= 1000;
      }
      break;
    }
    wrong += (got != want);
  }
  EXPECT_EQ(wrong, 0u);
  EXPECT_EQ(dec.overrun(), 0u) << "the flush must cover the decoder's look-ahead";
}

TEST(LazCoder, ResetModelsRestartIdentically)
{
  // Two chunks coded with reset models give the same bytes as one chunk coded twice.
  IntegerCompressor ic(16);
  ArithmeticEncoder enc;
  auto code = [&]() {
    ic.reset();
    enc.start();
    for (int i = 0; i < 5000; ++i)
      ic.compress(enc, i % 700, (i * 37) % 900);
    return enc.finish();
  };
  const std::vector<std::uint8_t> first = code();
  const std::vector<std::uint8_t> second = code();
  EXPECT_EQ(first, second);
  EXPECT_GT(first.size(), 100u);
}

TEST(LazCoder, GarbageAndTruncatedStreamsStayInRange)
{
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<std::uint8_t> garbage(static_cast<std::size_t>(rng() % 64));
    for (auto& b : garbage)
      b = static_cast<std::uint8_t>(trial % 5 == 0 ? 0xFF : rng());
    ArithmeticDecoder dec(garbage.data(), garbage.data() + garbage.size());
    SymbolModel big(2048), small(5);
    IntegerCompressor ic(32, 1);
    for (int i = 0; i < 2000; ++i) {
      EXPECT_LT(dec.decodeSymbol(big), 2048u);
      EXPECT_LT(dec.decodeSymbol(small), 5u);
      ic.decompress(dec, 0);
      EXPECT_LE(dec.readBits(7), 128u);  // value == length after all-0xFF input gives at most 2^bits
    }
    if (garbage.size() < 64) {
      EXPECT_GT(dec.overrun(), 0u);
    }
  }
}
