// Binary files of a distributed strip adjustment (strip_files.h): contributions, matcher
// memory, discrepancy samples, matrices. Raw little-endian values behind a magic and a version.
#include <pcl_ls3d/strips/strip_files.h>

#include <cstring>
#include <fstream>
#include <type_traits>

namespace pcl_ls3d {
namespace strips {

namespace {

constexpr std::uint32_t kVersion = 3;  // 2: DirectionCounts::surface_variance; 3: sample normals

class Writer
{
public:
  Writer(const std::string& path, const char magic[8]) : out_(path, std::ios::binary | std::ios::trunc)
  {
    out_.write(magic, 8);
    put(kVersion);
  }
  template <typename T>
  void
  put(const T& v)
  {
    static_assert(std::is_trivially_copyable<T>::value, "raw values only");
    out_.write(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  template <typename T>
  void
  putVector(const std::vector<T>& v)
  {
    put<std::uint64_t>(v.size());
    if (!v.empty())
      out_.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(T)));
  }
  template <typename Derived>
  void
  putMatrix(const Eigen::MatrixBase<Derived>& m)
  {
    const typename Derived::PlainObject p = m;
    out_.write(reinterpret_cast<const char*>(p.data()),
               static_cast<std::streamsize>(p.size() * sizeof(double)));
  }
  bool
  finish(const std::string& path, std::string& error)
  {
    if (!out_ || !out_.flush()) {
      error = "cannot write " + path;
      return false;
    }
    return true;
  }

private:
  std::ofstream out_;
};

class Reader
{
public:
  Reader(const std::string& path, const char magic[8], std::string& error) : in_(path, std::ios::binary)
  {
    char m[8] = {};
    std::uint32_t version = 0;
    in_.read(m, 8);
    get(version);
    if (!in_ || std::memcmp(m, magic, 8) != 0 || version != kVersion) {
      error = path + ": not a file of this kind or version";
      ok_ = false;
    }
  }
  template <typename T>
  void
  get(T& v)
  {
    in_.read(reinterpret_cast<char*>(&v), sizeof(T));
  }
  template <typename T>
  void
  getVector(std::vector<T>& v)
  {
    std::uint64_t n = 0;
    get(n);
    if (!in_ || n > (std::uint64_t(1) << 40) / sizeof(T)) {
      ok_ = false;
      return;
    }
    v.resize(static_cast<std::size_t>(n));
    if (n)
      in_.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(n * sizeof(T)));
  }
  template <typename Derived>
  void
  getMatrix(Eigen::PlainObjectBase<Derived>& m)
  {
    in_.read(reinterpret_cast<char*>(m.data()), static_cast<std::streamsize>(m.size() * sizeof(double)));
  }
  bool
  finish(const std::string& path, std::string& error)
  {
    if (ok_ && !in_) {
      error = path + ": truncated";
      ok_ = false;
    }
    return ok_;
  }
  bool
  ok() const
  {
    return ok_;
  }

private:
  std::ifstream in_;
  bool ok_ = true;
};

struct RawCell
{
  std::int32_t x, y, z;
};

}  // namespace

bool
writeMatrix(const std::string& path, const Eigen::MatrixXd& m, std::string& error)
{
  Writer w(path, "PLS3DMAT");
  w.put<std::int64_t>(m.rows());
  w.put<std::int64_t>(m.cols());
  w.putMatrix(m);
  return w.finish(path, error);
}

bool
readMatrix(const std::string& path, Eigen::MatrixXd& m, std::string& error)
{
  Reader r(path, "PLS3DMAT", error);
  std::int64_t rows = 0, cols = 0;
  r.get(rows);
  r.get(cols);
  if (!r.ok() || rows < 0 || cols < 0 || rows > 100000 || cols > 100000) {
    error = path + ": not a matrix file";
    return false;
  }
  m.resize(rows, cols);
  r.getMatrix(m);
  return r.finish(path, error);
}

bool
writeContribution(const std::string& path, const OverlapContribution& c, std::string& error)
{
  Writer w(path, "PLS3DCON");
  w.put<std::int32_t>(c.overlap);
  w.put<std::int32_t>(c.i);
  w.put<std::int32_t>(c.j);
  w.put<std::int32_t>(c.iteration);
  w.put(c.spacing);
  w.putMatrix(c.normal.N);
  w.putMatrix(c.normal.b);
  w.put(c.normal.ltpl);
  w.put<std::uint64_t>(c.normal.n);
  w.putMatrix(c.noise_floor);
  for (const DirectionCounts* d : {&c.forward, &c.backward}) {
    w.put<std::uint64_t>(d->observations);
    w.put<std::uint64_t>(d->used);
    w.put(d->vtpv);
    w.put(d->robust_scale);
    w.put(d->surface_variance);
  }
  w.put<std::uint64_t>(c.cells.size());
  for (const PrecisionCell& pc : c.cells) {
    w.put(RawCell{pc.x, pc.y, pc.z});
    w.putMatrix(pc.score);
    w.putMatrix(pc.normal);
  }
  return w.finish(path, error);
}

bool
readContribution(const std::string& path, OverlapContribution& c, std::string& error)
{
  Reader r(path, "PLS3DCON", error);
  if (!r.ok())
    return false;
  c = OverlapContribution();
  std::int32_t v[4] = {};
  for (std::int32_t& x : v)
    r.get(x);
  c.overlap = v[0];
  c.i = v[1];
  c.j = v[2];
  c.iteration = v[3];
  r.get(c.spacing);
  r.getMatrix(c.normal.N);
  r.getMatrix(c.normal.b);
  r.get(c.normal.ltpl);
  std::uint64_t n = 0;
  r.get(n);
  c.normal.n = static_cast<std::size_t>(n);
  r.getMatrix(c.noise_floor);
  for (DirectionCounts* d : {&c.forward, &c.backward}) {
    std::uint64_t a = 0, b = 0;
    r.get(a);
    r.get(b);
    d->observations = static_cast<std::size_t>(a);
    d->used = static_cast<std::size_t>(b);
    r.get(d->vtpv);
    r.get(d->robust_scale);
    r.get(d->surface_variance);
  }
  std::uint64_t cells = 0;
  r.get(cells);
  if (!r.finish(path, error) || cells > (std::uint64_t(1) << 32))
    return false;
  c.cells.resize(static_cast<std::size_t>(cells));
  for (PrecisionCell& pc : c.cells) {
    RawCell raw{};
    r.get(raw);
    pc.x = raw.x;
    pc.y = raw.y;
    pc.z = raw.z;
    r.getMatrix(pc.score);
    r.getMatrix(pc.normal);
  }
  return r.finish(path, error);
}

bool
writeMatcherState(const std::string& path, const std::array<PairMatcher::State, 2>& state, std::string& error)
{
  Writer w(path, "PLS3DMST");
  for (const PairMatcher::State& s : state) {
    w.putVector(s.caches);
    w.putVector(s.missed);
  }
  return w.finish(path, error);
}

bool
readMatcherState(const std::string& path, std::array<PairMatcher::State, 2>& state, std::string& error)
{
  Reader r(path, "PLS3DMST", error);
  if (!r.ok())
    return false;
  for (PairMatcher::State& s : state) {
    r.getVector(s.caches);
    r.getVector(s.missed);
  }
  return r.finish(path, error);
}

bool
writeSamples(const std::string& path, const OverlapSamples& s, std::string& error)
{
  Writer w(path, "PLS3DSMP");
  for (const DiscrepancySamples* d : {&s.before, &s.after, &s.noise[0], &s.noise[1]}) {
    w.putVector(d->xy);
    w.putVector(d->value);
    w.putVector(d->normal);
  }
  return w.finish(path, error);
}

bool
readSamples(const std::string& path, OverlapSamples& s, std::string& error)
{
  Reader r(path, "PLS3DSMP", error);
  if (!r.ok())
    return false;
  for (DiscrepancySamples* d : {&s.before, &s.after, &s.noise[0], &s.noise[1]}) {
    r.getVector(d->xy);
    r.getVector(d->value);
    r.getVector(d->normal);
  }
  return r.finish(path, error);
}

}  // namespace strips
}  // namespace pcl_ls3d
