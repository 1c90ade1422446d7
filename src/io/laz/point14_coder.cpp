/// \file point14_coder.cpp
/// \brief The POINT14 item of layered chunks: nine layers (channel / returns / XY, Z,
///        classification, flags, intensity, scan angle, user data, point source, GPS time).
///        Each record first codes which fields changed from the last record of its scanner
///        channel; the layers then code the new values, each from its own prediction.

#include "layered_items.h"
#include "point14_context.h"

namespace pcl_ls3d {
namespace io {
namespace laz {

namespace {

enum Point14Layer : unsigned
{
  kChannelReturnsXY,
  kZ,
  kClassification,
  kFlags,
  kIntensity,
  kScanAngle,
  kUserData,
  kPointSource,
  kGpsTime,
  kPoint14Layers
};

// Bits of the changed-fields symbol (128 values).
constexpr unsigned kReturnNumberBits = 3;  // 0 same, 1 plus one, 2 minus one, 3 coded
constexpr unsigned kNumberOfReturnsChanged = 1u << 2;
constexpr unsigned kScanAngleChanged = 1u << 3;
constexpr unsigned kGpsTimeChanged = 1u << 4;
constexpr unsigned kPointSourceChanged = 1u << 5;
constexpr unsigned kChannelChanged = 1u << 6;

std::int32_t
wrappingAdd(std::int32_t a, std::int32_t b)
{
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(a) + static_cast<std::uint32_t>(b));
}

std::int32_t
wrappingDiff(std::int32_t a, std::int32_t b)
{
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(a) - static_cast<std::uint32_t>(b));
}

/// Context of the Y corrector from the X corrector's bit count k (and likewise Z from the mean of
/// X's and Y's): k rounded down to even, capped.
std::uint32_t
kContext(std::uint32_t k, std::uint32_t cap)
{
  return k < cap ? (k & ~1u) : cap;
}

/// Classification models are chosen by the previous class (low 5 bits) and single return.
unsigned
classificationContext(std::uint8_t last_class, const ReturnContext& rc)
{
  return ((last_class & 0x1Fu) << 1) + (rc.cpr == 3 ? 1u : 0u);
}

// ------------------------------------------------------------------------------------------
class Point14Decoder final : public LayeredItemDecoder
{
public:
  explicit Point14Decoder(ContextSwitch rule) : rule_(rule)
  {}

  std::size_t
  layerCount() const override
  {
    return kPoint14Layers;
  }

  void
  start(const std::uint8_t* first, const Layer* layers, unsigned& channel) override
  {
    for (unsigned i = 0; i < kPoint14Layers; ++i) {
      // The channel / returns / XY layer is always read; any other empty layer means "unchanged".
      present_[i] = i == kChannelReturnsXY || layers[i].size != 0;
      if (present_[i])
        dec_[i].start(layers[i].data, layers[i].data + layers[i].size);
    }
    for (auto& c : contexts_)
      if (c)
        c->in_use = false;
    const Point14 p = unpackPoint14(first);
    current_ = channel = p.channel;
    contextOf(contexts_, current_).start(p);
  }

  void
  decode(std::uint8_t* item, unsigned& channel) override
  {
    Point14Context* c = contexts_[current_].get();
    const unsigned changed =
        dec_[kChannelReturnsXY].decodeSymbol(c->changed_values[previousReturnContext(c->last)]);
    if (changed & kChannelChanged)
      c = &decodeChannel(*c, channel);
    else if (rule_ == ContextSwitch::Version4)
      channel = current_;
    const bool gps_changed = (changed & kGpsTimeChanged) != 0;
    decodeReturns(*c, changed, gps_changed);
    const ReturnContext rc = returnContext(c->last.number_of_returns, c->last.return_number);
    decodeXY(*c, rc, gps_changed);
    decodeAttributes(*c, rc, changed, gps_changed);
    c->last.gps_time_changed = gps_changed;
    packPoint14(c->last, item);
  }

  std::size_t
  overrun() const override
  {
    std::size_t n = 0;
    for (unsigned i = 0; i < kPoint14Layers; ++i)
      if (present_[i])
        n += dec_[i].overrun();
    return n;
  }

private:
  /// The channel moves by 1–3 (mod 4); a channel not yet in use starts from the current record.
  Point14Context&
  decodeChannel(Point14Context& from, unsigned& channel)
  {
    const unsigned step = dec_[kChannelReturnsXY].decodeSymbol(from.scanner_channel) + 1;
    current_ = channel = (current_ + step) & 3;
    Point14Context& to = contextOf(contexts_, current_);
    if (!to.in_use)
      to.start(from.last);
    to.last.channel = static_cast<std::uint8_t>(current_);
    return to;
  }

  void
  decodeReturns(Point14Context& c, unsigned changed, bool gps_changed)
  {
    ArithmeticDecoder& dec = dec_[kChannelReturnsXY];
    const unsigned last_n = c.last.number_of_returns, last_r = c.last.return_number;
    if (changed & kNumberOfReturnsChanged)
      c.last.number_of_returns =
          static_cast<std::uint8_t>(dec.decodeSymbol(lazyModel(c.number_of_returns[last_n], 16)));
    unsigned r = last_r;
    switch (changed & kReturnNumberBits) {
    case 1:
      r = (last_r + 1) & 15;
      break;
    case 2:
      r = (last_r + 15) & 15;
      break;
    case 3:
      if (gps_changed)
        r = dec.decodeSymbol(lazyModel(c.return_number[last_r], 16));
      else
        r = (last_r + dec.decodeSymbol(c.return_number_gps_same) + 2) & 15;
      break;
    default:
      break;
    }
    c.last.return_number = static_cast<std::uint8_t>(r);
  }

  void
  decodeXY(Point14Context& c, const ReturnContext& rc, bool gps_changed)
  {
    ArithmeticDecoder& dec = dec_[kChannelReturnsXY];
    const unsigned single = c.last.number_of_returns == 1 ? 1u : 0u;
    const unsigned m = (rc.map << 1) | (gps_changed ? 1u : 0u);
    const std::int32_t dx = c.dx.decompress(dec, c.x_median[m].get(), single);
    c.last.x = wrappingAdd(c.last.x, dx);
    c.x_median[m].add(dx);
    const std::int32_t dy = c.dy.decompress(dec, c.y_median[m].get(), single + kContext(c.dx.k(), 20));
    c.last.y = wrappingAdd(c.last.y, dy);
    c.y_median[m].add(dy);
  }

  void
  decodeAttributes(Point14Context& c, const ReturnContext& rc, unsigned changed, bool gps_changed)
  {
    Point14& p = c.last;
    if (present_[kZ]) {
      const std::uint32_t k = (c.dx.k() + c.dy.k()) / 2;
      const unsigned single = p.number_of_returns == 1 ? 1u : 0u;
      p.z = c.z.decompress(dec_[kZ], c.last_z[rc.level], single + kContext(k, 18));
      c.last_z[rc.level] = p.z;
    }
    if (present_[kClassification])
      p.classification = static_cast<std::uint8_t>(dec_[kClassification].decodeSymbol(
          lazyModel(c.classification[classificationContext(p.classification, rc)], 256)));
    if (present_[kFlags])
      p.flags = static_cast<std::uint8_t>(dec_[kFlags].decodeSymbol(lazyModel(c.flags[p.flags & 63], 64)));
    if (present_[kIntensity]) {
      const unsigned i = (rc.cpr << 1) | (gps_changed ? 1u : 0u);
      p.intensity =
          static_cast<std::uint16_t>(c.intensity.decompress(dec_[kIntensity], c.last_intensity[i], rc.cpr));
      c.last_intensity[i] = p.intensity;
    }
    if (present_[kScanAngle] && (changed & kScanAngleChanged))
      p.scan_angle = static_cast<std::int16_t>(
          c.scan_angle.decompress(dec_[kScanAngle], p.scan_angle, gps_changed ? 1u : 0u));
    if (present_[kUserData])
      p.user_data = static_cast<std::uint8_t>(
          dec_[kUserData].decodeSymbol(lazyModel(c.user_data[p.user_data / 4], 256)));
    if (present_[kPointSource] && (changed & kPointSourceChanged))
      p.point_source =
          static_cast<std::uint16_t>(c.point_source.decompress(dec_[kPointSource], p.point_source));
    if (present_[kGpsTime] && gps_changed)
      p.gps_time = c.gps.decode(dec_[kGpsTime]);
  }

  ContextSwitch rule_;
  std::array<ArithmeticDecoder, kPoint14Layers> dec_;
  std::array<bool, kPoint14Layers> present_{};
  std::array<std::unique_ptr<Point14Context>, 4> contexts_;
  unsigned current_ = 0;
};

// ------------------------------------------------------------------------------------------
class Point14Encoder final : public LayeredItemEncoder
{
public:
  explicit Point14Encoder(ContextSwitch rule) : rule_(rule)
  {}

  std::size_t
  layerCount() const override
  {
    return kPoint14Layers;
  }

  void
  start(const std::uint8_t* first, unsigned& channel) override
  {
    for (ArithmeticEncoder& e : enc_)
      e.start();
    changed_.fill(false);
    for (auto& c : contexts_)
      if (c)
        c->in_use = false;
    const Point14 p = unpackPoint14(first);
    current_ = channel = p.channel;
    contextOf(contexts_, current_).start(p);
  }

  void
  encode(const std::uint8_t* item, unsigned& channel) override
  {
    const Point14 p = unpackPoint14(item);
    Point14Context* c = contexts_[current_].get();
    const unsigned lpr = previousReturnContext(c->last);
    // The record is compared with the last one of its own channel (or, for a channel not yet in
    // use, with the current one, from which that channel will start).
    Point14Context* own = p.channel != current_ ? contexts_[p.channel].get() : c;
    const Point14& last = own && own->in_use ? own->last : c->last;
    const unsigned changed = changedFields(p, last, p.channel != current_);
    enc_[kChannelReturnsXY].encodeSymbol(c->changed_values[lpr], changed);
    if (changed & kChannelChanged)
      c = &encodeChannel(*c, p.channel, channel);
    else if (rule_ == ContextSwitch::Version4)
      channel = current_;
    const bool gps_changed = (changed & kGpsTimeChanged) != 0;
    encodeReturns(*c, p, changed, gps_changed);
    const ReturnContext rc = returnContext(p.number_of_returns, p.return_number);
    encodeXY(*c, p, rc, gps_changed);
    encodeAttributes(*c, p, rc, gps_changed);
    c->last = p;
    c->last.gps_time_changed = gps_changed;
  }

  void
  finish(std::vector<std::uint8_t>* layers) override
  {
    // LASzip always writes the first two layers; the others only when their field changed.
    for (unsigned i = 0; i < kPoint14Layers; ++i) {
      if (i == kChannelReturnsXY || i == kZ || changed_[i])
        layers[i] = enc_[i].finish();
      else
        layers[i].clear();
    }
  }

private:
  static unsigned
  changedFields(const Point14& p, const Point14& last, bool channel_changed)
  {
    unsigned changed = channel_changed ? kChannelChanged : 0u;
    if (p.point_source != last.point_source)
      changed |= kPointSourceChanged;
    if (p.gps_time != last.gps_time)  // bit patterns: lossless for -0.0 and NaN too
      changed |= kGpsTimeChanged;
    if (p.scan_angle != last.scan_angle)
      changed |= kScanAngleChanged;
    if (p.number_of_returns != last.number_of_returns)
      changed |= kNumberOfReturnsChanged;
    if (p.return_number == ((last.return_number + 1) & 15))
      changed |= 1;
    else if (p.return_number == ((last.return_number + 15) & 15))
      changed |= 2;
    else if (p.return_number != last.return_number)
      changed |= 3;
    return changed;
  }

  Point14Context&
  encodeChannel(Point14Context& from, unsigned to_channel, unsigned& channel)
  {
    enc_[kChannelReturnsXY].encodeSymbol(from.scanner_channel, (to_channel - current_ + 3) & 3);
    current_ = channel = to_channel;
    Point14Context& to = contextOf(contexts_, current_);
    if (!to.in_use)
      to.start(from.last);
    return to;
  }

  void
  encodeReturns(Point14Context& c, const Point14& p, unsigned changed, bool gps_changed)
  {
    ArithmeticEncoder& enc = enc_[kChannelReturnsXY];
    const unsigned last_n = c.last.number_of_returns, last_r = c.last.return_number;
    if (changed & kNumberOfReturnsChanged)
      enc.encodeSymbol(lazyModel(c.number_of_returns[last_n], 16), p.number_of_returns);
    if ((changed & kReturnNumberBits) != 3)
      return;
    if (gps_changed)
      enc.encodeSymbol(lazyModel(c.return_number[last_r], 16), p.return_number);
    else
      enc.encodeSymbol(c.return_number_gps_same, (p.return_number - last_r + 14) & 15);
  }

  void
  encodeXY(Point14Context& c, const Point14& p, const ReturnContext& rc, bool gps_changed)
  {
    ArithmeticEncoder& enc = enc_[kChannelReturnsXY];
    const unsigned single = p.number_of_returns == 1 ? 1u : 0u;
    const unsigned m = (rc.map << 1) | (gps_changed ? 1u : 0u);
    const std::int32_t dx = wrappingDiff(p.x, c.last.x);
    c.dx.compress(enc, c.x_median[m].get(), dx, single);
    c.x_median[m].add(dx);
    const std::int32_t dy = wrappingDiff(p.y, c.last.y);
    c.dy.compress(enc, c.y_median[m].get(), dy, single + kContext(c.dx.k(), 20));
    c.y_median[m].add(dy);
  }

  void
  encodeAttributes(Point14Context& c, const Point14& p, const ReturnContext& rc, bool gps_changed)
  {
    const Point14& last = c.last;
    const std::uint32_t k = (c.dx.k() + c.dy.k()) / 2;
    c.z.compress(enc_[kZ], c.last_z[rc.level], p.z, (p.number_of_returns == 1 ? 1u : 0u) + kContext(k, 18));
    c.last_z[rc.level] = p.z;
    changed_[kClassification] |= p.classification != last.classification;
    enc_[kClassification].encodeSymbol(
        lazyModel(c.classification[classificationContext(last.classification, rc)], 256), p.classification);
    changed_[kFlags] |= p.flags != last.flags;
    enc_[kFlags].encodeSymbol(lazyModel(c.flags[last.flags & 63], 64), p.flags);
    const unsigned i = (rc.cpr << 1) | (gps_changed ? 1u : 0u);
    changed_[kIntensity] |= p.intensity != last.intensity;
    c.intensity.compress(enc_[kIntensity], c.last_intensity[i], p.intensity, rc.cpr);
    c.last_intensity[i] = p.intensity;
    if (p.scan_angle != last.scan_angle) {
      changed_[kScanAngle] = true;
      c.scan_angle.compress(enc_[kScanAngle], last.scan_angle, p.scan_angle, gps_changed ? 1u : 0u);
    }
    changed_[kUserData] |= p.user_data != last.user_data;
    enc_[kUserData].encodeSymbol(lazyModel(c.user_data[last.user_data / 4], 256), p.user_data);
    if (p.point_source != last.point_source) {
      changed_[kPointSource] = true;
      c.point_source.compress(enc_[kPointSource], last.point_source, p.point_source);
    }
    if (gps_changed) {
      changed_[kGpsTime] = true;
      c.gps.encode(enc_[kGpsTime], p.gps_time);
    }
  }

  ContextSwitch rule_;
  std::array<ArithmeticEncoder, kPoint14Layers> enc_;
  std::array<bool, kPoint14Layers> changed_{};
  std::array<std::unique_ptr<Point14Context>, 4> contexts_;
  unsigned current_ = 0;
};

}  // namespace

std::unique_ptr<LayeredItemDecoder>
makePoint14Decoder(ContextSwitch rule)
{
  return std::make_unique<Point14Decoder>(rule);
}

std::unique_ptr<LayeredItemEncoder>
makePoint14Encoder(ContextSwitch rule)
{
  return std::make_unique<Point14Encoder>(rule);
}

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
