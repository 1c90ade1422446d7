#pragma once
/// \file arithmetic_models.h
/// \brief Private: the adaptive probability models of the LASzip arithmetic coder (an adaptive
///        multi-symbol model and an adaptive bit model, after Amir Said's FastAC as LASzip uses
///        it). Encoder and decoder update them identically, so both stay in step.

#include <cstdint>
#include <vector>

namespace pcl_ls3d {
namespace io {
namespace laz {

// Interval and model constants of the LASzip coder (they are part of the format).
constexpr std::uint32_t kMinLength = 0x01000000u;
constexpr std::uint32_t kMaxLength = 0xFFFFFFFFu;
constexpr int kBitLengthShift = 13;
constexpr std::uint32_t kBitMaxCount = 1u << kBitLengthShift;
constexpr int kSymbolLengthShift = 15;
constexpr std::uint32_t kSymbolMaxCount = 1u << kSymbolLengthShift;

/// \brief Adaptive model of one binary symbol.
struct BitModel
{
  std::uint32_t bit_0_count = 1, bit_count = 2;
  std::uint32_t bit_0_prob = 1u << (kBitLengthShift - 1);
  std::uint32_t update_cycle = 4, bits_until_update = 4;

  void
  update();
};

/// \brief Adaptive model of `symbols` symbols (2–2048). Above 16 symbols the decoder keeps a
///        look-up table that narrows its interval search to a few comparisons.
class SymbolModel
{
public:
  explicit SymbolModel(std::uint32_t symbols = 2);

  /// Back to the initial (uniform) state, as at the start of every chunk.
  void
  reset();
  void
  update();

  std::uint32_t symbols = 0, last_symbol = 0;
  std::uint32_t table_size = 0, table_shift = 0;
  std::uint32_t total_count = 0, update_cycle = 0, symbols_until_update = 0;
  std::vector<std::uint32_t> distribution, symbol_count, decoder_table;
};

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
