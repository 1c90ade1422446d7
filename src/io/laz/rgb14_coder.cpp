/// \file rgb14_coder.cpp
/// \brief The RGB14 and RGBNIR14 items of layered chunks: one layer for the colour, one for the
///        near infrared. Each byte of each channel is coded only when it changed; green and blue
///        are predicted from red's change (grey records code red alone).

#include "layered_items.h"

#include "io/las_format.h"

#include <algorithm>

namespace pcl_ls3d {
namespace io {
namespace laz {

namespace {

struct RgbModels
{
  SymbolModel used{128};  ///< which bytes changed (bits 0–5) and whether the record is not grey (6)
  std::array<SymbolModel, 6> diff{SymbolModel(256), SymbolModel(256), SymbolModel(256),
                                  SymbolModel(256), SymbolModel(256), SymbolModel(256)};
};

struct NirModels
{
  SymbolModel used{4};
  std::array<SymbolModel, 2> diff{SymbolModel(256), SymbolModel(256)};
};

struct Rgb14Context
{
  bool in_use = false;
  std::array<std::uint16_t, 4> last{};  ///< red, green, blue, near infrared
  std::unique_ptr<RgbModels> rgb;
  std::unique_ptr<NirModels> nir;
};

void
startContext(Rgb14Context& c, const std::uint16_t* from)
{
  if (!c.rgb) {
    c.rgb = std::make_unique<RgbModels>();
    c.nir = std::make_unique<NirModels>();
  }
  c.rgb->used.reset();
  for (SymbolModel& m : c.rgb->diff)
    m.reset();
  c.nir->used.reset();
  for (SymbolModel& m : c.nir->diff)
    m.reset();
  std::copy(from, from + 4, c.last.begin());
  c.in_use = true;
}

unsigned
byteOf(std::uint16_t v, unsigned lane)
{
  return (v >> (8 * lane)) & 0xFFu;
}

unsigned
clampByte(int v)
{
  return v <= 0 ? 0u : v >= 255 ? 255u : static_cast<unsigned>(v);
}

/// Red's bytes (lane 0 low, 1 high) are coded as changes; green's byte is predicted by adding
/// red's change to its last value, blue's by adding the mean of red's and green's changes.
void
decodeRgb(ArithmeticDecoder& dec, RgbModels& m, const std::uint16_t* last, std::uint16_t* out)
{
  const unsigned sym = dec.decodeSymbol(m.used);
  unsigned r[2], g[2], b[2];
  for (unsigned lane = 0; lane < 2; ++lane) {
    r[lane] = byteOf(last[0], lane);
    if (sym & (1u << lane))
      r[lane] = (dec.decodeSymbol(m.diff[lane]) + r[lane]) & 0xFFu;
  }
  if (!(sym & (1u << 6))) {
    out[0] = out[1] = out[2] = static_cast<std::uint16_t>(r[0] | (r[1] << 8));
    return;
  }
  for (unsigned lane = 0; lane < 2; ++lane) {
    const int last_g = static_cast<int>(byteOf(last[1], lane));
    const int last_b = static_cast<int>(byteOf(last[2], lane));
    int diff = static_cast<int>(r[lane]) - static_cast<int>(byteOf(last[0], lane));
    g[lane] = static_cast<unsigned>(last_g);
    if (sym & (4u << lane))
      g[lane] = (dec.decodeSymbol(m.diff[2 + lane]) + clampByte(diff + last_g)) & 0xFFu;
    b[lane] = static_cast<unsigned>(last_b);
    if (sym & (16u << lane)) {
      diff = (diff + static_cast<int>(g[lane]) - last_g) / 2;
      b[lane] = (dec.decodeSymbol(m.diff[4 + lane]) + clampByte(diff + last_b)) & 0xFFu;
    }
  }
  out[0] = static_cast<std::uint16_t>(r[0] | (r[1] << 8));
  out[1] = static_cast<std::uint16_t>(g[0] | (g[1] << 8));
  out[2] = static_cast<std::uint16_t>(b[0] | (b[1] << 8));
}

/// Codes one colour; true when any byte differs from `last`.
bool
encodeRgb(ArithmeticEncoder& enc, RgbModels& m, const std::uint16_t* last, const std::uint16_t* v)
{
  unsigned sym = 0;
  for (unsigned lane = 0; lane < 2; ++lane)
    for (unsigned c = 0; c < 3; ++c)
      if (byteOf(v[c], lane) != byteOf(last[c], lane))
        sym |= 1u << (2 * c + lane);
  if (v[0] != v[1] || v[0] != v[2])
    sym |= 1u << 6;
  enc.encodeSymbol(m.used, sym);
  int diff[2];
  for (unsigned lane = 0; lane < 2; ++lane) {
    diff[lane] = static_cast<int>(byteOf(v[0], lane)) - static_cast<int>(byteOf(last[0], lane));
    if (sym & (1u << lane))
      enc.encodeSymbol(m.diff[lane], static_cast<unsigned>(diff[lane]) & 0xFFu);
  }
  if (!(sym & (1u << 6)))
    return sym != 0;
  for (unsigned lane = 0; lane < 2; ++lane) {
    const int g = static_cast<int>(byteOf(v[1], lane)), b = static_cast<int>(byteOf(v[2], lane));
    const int last_g = static_cast<int>(byteOf(last[1], lane));
    const int last_b = static_cast<int>(byteOf(last[2], lane));
    if (sym & (4u << lane))
      enc.encodeSymbol(m.diff[2 + lane],
                       static_cast<unsigned>(g - static_cast<int>(clampByte(diff[lane] + last_g))) & 0xFFu);
    if (sym & (16u << lane)) {
      const int mean = (diff[lane] + g - last_g) / 2;
      enc.encodeSymbol(m.diff[4 + lane],
                       static_cast<unsigned>(b - static_cast<int>(clampByte(mean + last_b))) & 0xFFu);
    }
  }
  return true;
}

std::uint16_t
decodeNir(ArithmeticDecoder& dec, NirModels& m, std::uint16_t last)
{
  const unsigned sym = dec.decodeSymbol(m.used);
  unsigned bytes[2];
  for (unsigned lane = 0; lane < 2; ++lane) {
    bytes[lane] = byteOf(last, lane);
    if (sym & (1u << lane))
      bytes[lane] = (dec.decodeSymbol(m.diff[lane]) + bytes[lane]) & 0xFFu;
  }
  return static_cast<std::uint16_t>(bytes[0] | (bytes[1] << 8));
}

bool
encodeNir(ArithmeticEncoder& enc, NirModels& m, std::uint16_t last, std::uint16_t v)
{
  unsigned sym = 0;
  for (unsigned lane = 0; lane < 2; ++lane)
    if (byteOf(v, lane) != byteOf(last, lane))
      sym |= 1u << lane;
  enc.encodeSymbol(m.used, sym);
  for (unsigned lane = 0; lane < 2; ++lane)
    if (sym & (1u << lane))
      enc.encodeSymbol(m.diff[lane], (byteOf(v, lane) - byteOf(last, lane)) & 0xFFu);
  return sym != 0;
}

void
readColour(const std::uint8_t* item, std::size_t channels, std::uint16_t* v)
{
  for (std::size_t i = 0; i < channels; ++i)
    v[i] = las::get<std::uint16_t>(item + 2 * i);
}

// ------------------------------------------------------------------------------------------
class Rgb14Decoder final : public LayeredItemDecoder
{
public:
  Rgb14Decoder(bool nir, ContextSwitch rule) : nir_(nir), rule_(rule)
  {}

  std::size_t
  layerCount() const override
  {
    return nir_ ? 2 : 1;
  }

  void
  start(const std::uint8_t* first, const Layer* layers, unsigned& channel) override
  {
    rgb_present_ = layers[0].size != 0;
    if (rgb_present_)
      rgb_dec_.start(layers[0].data, layers[0].data + layers[0].size);
    nir_present_ = nir_ && layers[1].size != 0;
    if (nir_present_)
      nir_dec_.start(layers[1].data, layers[1].data + layers[1].size);
    for (Rgb14Context& c : contexts_)
      c.in_use = false;
    std::uint16_t v[4] = {0, 0, 0, 0};
    readColour(first, nir_ ? 4 : 3, v);
    current_ = channel & 3;
    startContext(contexts_[current_], v);
  }

  void
  decode(std::uint8_t* item, unsigned& channel) override
  {
    std::uint16_t* last = switchChannel(contexts_, current_, channel, rule_, startContext);
    Rgb14Context& c = contexts_[current_];
    if (rgb_present_) {
      std::uint16_t rgb[3];
      decodeRgb(rgb_dec_, *c.rgb, last, rgb);
      std::copy(rgb, rgb + 3, last);
    }
    if (nir_present_)
      last[3] = decodeNir(nir_dec_, *c.nir, last[3]);
    for (std::size_t i = 0; i < (nir_ ? 4u : 3u); ++i)
      las::put<std::uint16_t>(item + 2 * i, last[i]);
  }

  std::size_t
  overrun() const override
  {
    return (rgb_present_ ? rgb_dec_.overrun() : 0) + (nir_present_ ? nir_dec_.overrun() : 0);
  }

private:
  bool nir_;
  ContextSwitch rule_;
  ArithmeticDecoder rgb_dec_, nir_dec_;
  bool rgb_present_ = false, nir_present_ = false;
  std::array<Rgb14Context, kChannels> contexts_;
  unsigned current_ = 0;
};

// ------------------------------------------------------------------------------------------
class Rgb14Encoder final : public LayeredItemEncoder
{
public:
  Rgb14Encoder(bool nir, ContextSwitch rule) : nir_(nir), rule_(rule)
  {}

  std::size_t
  layerCount() const override
  {
    return nir_ ? 2 : 1;
  }

  void
  start(const std::uint8_t* first, unsigned& channel) override
  {
    rgb_enc_.start();
    nir_enc_.start();
    rgb_changed_ = nir_changed_ = false;
    for (Rgb14Context& c : contexts_)
      c.in_use = false;
    std::uint16_t v[4] = {0, 0, 0, 0};
    readColour(first, nir_ ? 4 : 3, v);
    current_ = channel & 3;
    startContext(contexts_[current_], v);
  }

  void
  encode(const std::uint8_t* item, unsigned& channel) override
  {
    std::uint16_t* last = switchChannel(contexts_, current_, channel, rule_, startContext);
    Rgb14Context& c = contexts_[current_];
    std::uint16_t v[4] = {0, 0, 0, last[3]};
    readColour(item, nir_ ? 4 : 3, v);
    rgb_changed_ |= encodeRgb(rgb_enc_, *c.rgb, last, v);
    if (nir_)
      nir_changed_ |= encodeNir(nir_enc_, *c.nir, last[3], v[3]);
    std::copy(v, v + 4, last);
  }

  void
  finish(std::vector<std::uint8_t>* layers) override
  {
    layers[0] = rgb_changed_ ? rgb_enc_.finish() : std::vector<std::uint8_t>();
    if (nir_)
      layers[1] = nir_changed_ ? nir_enc_.finish() : std::vector<std::uint8_t>();
  }

private:
  bool nir_;
  ContextSwitch rule_;
  ArithmeticEncoder rgb_enc_, nir_enc_;
  bool rgb_changed_ = false, nir_changed_ = false;
  std::array<Rgb14Context, kChannels> contexts_;
  unsigned current_ = 0;
};

}  // namespace

std::unique_ptr<LayeredItemDecoder>
makeRgb14Decoder(bool nir, ContextSwitch rule)
{
  return std::make_unique<Rgb14Decoder>(nir, rule);
}

std::unique_ptr<LayeredItemEncoder>
makeRgb14Encoder(bool nir, ContextSwitch rule)
{
  return std::make_unique<Rgb14Encoder>(nir, rule);
}

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
