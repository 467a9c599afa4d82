// SPDX-License-Identifier: BSD-3-Clause
#include "amrsp/SyntheticCosmo.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <limits>
#include <queue>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <utility>

namespace amrsp
{

namespace
{

// ------------------------------------------------------------------------------------------------
// Portable arithmetic: everything that decides the structure or the values goes through these
// (or through +, -, *, /, sqrt, floor, which IEEE 754 rounds identically everywhere).

/// splitmix64 (Steele, Lea, Flood 2014): a 64-bit state, one multiply-xorshift output function.
class SplitMix64
{
public:
  explicit SplitMix64(uint64_t seed)
    : State(seed)
  {
  }
  uint64_t Next()
  {
    uint64_t z = (this->State += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, 1): the top 53 bits scaled by 2^-53 (exact).
  double Uniform() { return static_cast<double>(this->Next() >> 11) * (1.0 / 9007199254740992.0); }
  /// Uniform in [a, b).
  double Uniform(double a, double b) { return a + (b - a) * this->Uniform(); }
  /// Uniform in [a, b)^3, drawn x, then y, then z. (Never draw twice within one expression or
  /// argument list: C++ leaves their evaluation order to the compiler.)
  glm::dvec3 UniformVector(double a, double b)
  {
    const double x = this->Uniform(a, b);
    const double y = this->Uniform(a, b);
    const double z = this->Uniform(a, b);
    return glm::dvec3(x, y, z);
  }
  /// A point uniformly distributed in the unit ball (rejection from the cube).
  glm::dvec3 InBall()
  {
    for (;;)
    {
      const glm::dvec3 v = this->UniformVector(-1.0, 1.0);
      if (v.x * v.x + v.y * v.y + v.z * v.z <= 1.0)
      {
        return v;
      }
    }
  }

private:
  uint64_t State;
};

/// Cube root of x > 0 by a fixed number of Newton steps from a power-of-two start (frexp and
/// ldexp are exact), so the result does not depend on the C library's cbrt.
double CubeRoot(double x)
{
  if (!(x > 0.0))
  {
    return 0.0;
  }
  int e = 0;
  std::frexp(x, &e);
  double y = std::ldexp(1.0, e / 3);
  for (int i = 0; i < 16; ++i)
  {
    y = (2.0 * y + x / (y * y)) / 3.0;
  }
  return y;
}

/// The integer n >= 1 whose cube is nearest to x (x >= 1), by integer bisection.
int64_t NearestIntegerCubeRoot(int64_t x)
{
  int64_t lo = 1;
  int64_t hi = 2097151; // 2097151^3 < 2^63
  while (hi - lo > 1)
  {
    const int64_t mid = (lo + hi) / 2;
    if (mid * mid * mid <= x)
    {
      lo = mid;
    }
    else
    {
      hi = mid;
    }
  }
  // lo^3 <= x < hi^3: pick the nearer one.
  return (x - lo * lo * lo <= hi * hi * hi - x) ? lo : hi;
}

/// A power-law radius in [rmin, rmax] with dN/dR ~ R^-3 (inverse transform; sqrt only).
double PowerLawRadius(SplitMix64& rng, double rmin, double rmax)
{
  const double a = 1.0 / (rmin * rmin);
  const double b = 1.0 / (rmax * rmax);
  return 1.0 / std::sqrt(a - rng.Uniform() * (a - b));
}

// ------------------------------------------------------------------------------------------------
// Threads. Every parallel loop writes disjoint outputs computed from read-only inputs, so results
// do not depend on the number of threads.

unsigned WorkerCount()
{
  const unsigned n = std::thread::hardware_concurrency();
  return std::max(1u, std::min(n, 64u));
}

/// Calls body(begin, end) on contiguous slices of [0, n), in parallel when n is large enough.
template <class Body>
void ParallelFor(int64_t n, int64_t minPerThread, const Body& body)
{
  const int64_t threads =
    std::min<int64_t>(WorkerCount(), std::max<int64_t>(1, n / std::max<int64_t>(1, minPerThread)));
  if (threads <= 1)
  {
    body(int64_t(0), n);
    return;
  }
  std::vector<std::thread> pool;
  pool.reserve(static_cast<std::size_t>(threads));
  for (int64_t t = 0; t < threads; ++t)
  {
    pool.emplace_back([&body, n, t, threads]() { body(n * t / threads, n * (t + 1) / threads); });
  }
  for (std::thread& th : pool)
  {
    th.join();
  }
}

} // namespace

// ------------------------------------------------------------------------------------------------
// The density field.

struct CosmoField::Impl
{
  /// One halo: support is the open ball |x - C| < R; see the profile in the header.
  struct Halo
  {
    double Cx, Cy, Cz;
    double R;
    double R2;    ///< R^2
    double InvR2; ///< 1 / R^2
    double Amp;   ///< A: density ~ A / r^2 for eps << r << R
    double Soft2; ///< eps^2
  };
  /// One background term: Amp * Bump(Kx x + Px) * Bump(Ky y + Py) * Bump(Kz z + Pz).
  struct Wave
  {
    double K[3];
    double P[3];
    double Amp;
  };

  static constexpr int NumberOfWaves = 4;
  /// Buckets per axis of the halo lookup grid over the unit cube.
  static constexpr int Buckets = 64;

  std::vector<Halo> Halos;
  std::array<Wave, NumberOfWaves> Waves{};
  double Base = 0.35;
  /// CSR lists: the halos whose support's bounding box meets bucket b are
  /// BucketHalos[BucketStart[b] .. BucketStart[b+1]), in increasing halo index. Buckets on the
  /// faces of the cube also receive the halos reaching past that face, so the lookup is right for
  /// points outside the cube too.
  std::vector<uint32_t> BucketStart;
  std::vector<uint32_t> BucketHalos;

  /// A smooth (C1) periodic bump with period 1, values in [0, 1].
  static double Bump(double t)
  {
    const double f = t - std::floor(t);
    const double g = f * (1.0 - f);
    return 16.0 * g * g;
  }

  static int BucketOf(double x)
  {
    const double b = std::floor(x * Buckets);
    if (!(b >= 0.0))
    {
      return 0;
    }
    return b >= Buckets - 1 ? Buckets - 1 : static_cast<int>(b);
  }

  /// Adds the halo terms to `sum`, in increasing halo index (the order fixes the rounding).
  static double AddHalo(double sum, const Halo& h, double x, double y, double z)
  {
    const double dx = x - h.Cx;
    const double dy = y - h.Cy;
    const double dz = z - h.Cz;
    const double d2 = dx * dx + dy * dy + dz * dz;
    if (d2 < h.R2)
    {
      const double t = 1.0 - d2 * h.InvR2;
      sum += h.Amp * t * t / (d2 + h.Soft2);
    }
    return sum;
  }

  double Background(double x, double y, double z) const
  {
    double bg = this->Base;
    for (const Wave& w : this->Waves)
    {
      bg +=
        w.Amp * Bump(w.K[0] * x + w.P[0]) * Bump(w.K[1] * y + w.P[1]) * Bump(w.K[2] * z + w.P[2]);
    }
    return bg;
  }

  double Evaluate(double x, double y, double z) const
  {
    double sum = this->Background(x, y, z);
    const int b = BucketOf(x) + Buckets * (BucketOf(y) + Buckets * BucketOf(z));
    for (uint32_t i = this->BucketStart[b]; i < this->BucketStart[b + 1]; ++i)
    {
      sum = AddHalo(sum, this->Halos[this->BucketHalos[i]], x, y, z);
    }
    return sum;
  }

  void AddHaloToCatalogue(const glm::dvec3& c, double r, double amp, double eps)
  {
    Halo h;
    h.Cx = c.x;
    h.Cy = c.y;
    h.Cz = c.z;
    h.R = r;
    h.R2 = r * r;
    h.InvR2 = 1.0 / h.R2;
    h.Amp = amp;
    h.Soft2 = eps * eps;
    this->Halos.push_back(h);
  }

  void BuildBuckets()
  {
    const std::size_t nb = static_cast<std::size_t>(Buckets) * Buckets * Buckets;
    std::vector<uint32_t> count(nb + 1, 0);
    // Squared distance from coordinate c to bucket slab i, the outermost slabs extending to
    // infinity (so that points outside the cube find their halos).
    auto slabDistance2 = [](double c, int i) {
      const double lo = static_cast<double>(i) / Buckets;
      const double hi = static_cast<double>(i + 1) / Buckets;
      double d = 0.0;
      if (i > 0 && c < lo)
      {
        d = lo - c;
      }
      else if (i < Buckets - 1 && c > hi)
      {
        d = c - hi;
      }
      return d * d;
    };
    auto forEachBucket = [&slabDistance2](const Halo& h, auto&& f) {
      const int x0 = BucketOf(h.Cx - h.R), x1 = BucketOf(h.Cx + h.R);
      const int y0 = BucketOf(h.Cy - h.R), y1 = BucketOf(h.Cy + h.R);
      const int z0 = BucketOf(h.Cz - h.R), z1 = BucketOf(h.Cz + h.R);
      for (int k = z0; k <= z1; ++k)
      {
        const double dz2 = slabDistance2(h.Cz, k);
        for (int j = y0; j <= y1; ++j)
        {
          const double dy2 = slabDistance2(h.Cy, j);
          for (int i = x0; i <= x1; ++i)
          {
            // Only buckets that the open support ball actually meets.
            if (slabDistance2(h.Cx, i) + dy2 + dz2 < h.R2)
            {
              f(static_cast<std::size_t>(i + Buckets * (j + Buckets * k)));
            }
          }
        }
      }
    };
    for (const Halo& h : this->Halos)
    {
      forEachBucket(h, [&count](std::size_t b) { ++count[b + 1]; });
    }
    for (std::size_t b = 0; b < nb; ++b)
    {
      count[b + 1] += count[b];
    }
    this->BucketStart = count;
    this->BucketHalos.assign(count[nb], 0);
    std::vector<uint32_t> fill(count.begin(), count.end() - 1);
    for (std::size_t i = 0; i < this->Halos.size(); ++i)
    {
      forEachBucket(this->Halos[i],
        [&](std::size_t b) { this->BucketHalos[fill[b]++] = static_cast<uint32_t>(i); });
    }
  }

  /// The catalogue: clusters with satellites, filaments between neighbouring clusters, field
  /// halos, and the background waves. All lengths in unit-cube (world) units.
  explicit Impl(uint64_t seed)
  {
    SplitMix64 rng(seed ^ 0x5DEECE66D1234567ULL);

    for (Wave& w : this->Waves)
    {
      for (int a = 0; a < 3; ++a)
      {
        w.K[a] = static_cast<double>(1 + (rng.Next() % 3)); // 1, 2 or 3 periods per domain
        w.P[a] = rng.Uniform();
      }
      w.Amp = rng.Uniform(0.25, 0.45);
    }

    // Softening length: tiny, the same order for every halo (as a simulation's force
    // softening), so the peak density A/eps^2 grows with the halo radius and the deepest levels
    // go to the most massive halos.
    const double epsBase = 3e-6;
    // Draws the amplitude factor, then the softening factor.
    auto addHalo = [this, &rng, epsBase](const glm::dvec3& centre, double r) {
      const double amp = 8.0 * rng.Uniform(0.75, 1.25) * r * r;
      const double eps = epsBase * rng.Uniform(0.5, 1.5);
      this->AddHaloToCatalogue(centre, r, amp, eps);
    };

    const int clusters = 32;
    const double clusterRMin = 0.05, clusterRMax = 0.18;
    std::vector<glm::dvec3> centres;
    std::vector<double> radii;
    for (int c = 0; c < clusters; ++c)
    {
      const glm::dvec3 p = rng.UniformVector(0.08, 0.92);
      const double r = PowerLawRadius(rng, clusterRMin, clusterRMax);
      centres.push_back(p);
      radii.push_back(r);
      addHalo(p, r);
    }
    // Satellites: uniformly in a ball of 1.3 cluster radii, more around bigger clusters.
    for (int c = 0; c < clusters; ++c)
    {
      const double rc = radii[static_cast<std::size_t>(c)];
      const double frac = rc / clusterRMax;
      const int satellites = 6 + static_cast<int>(50.0 * frac * frac * rng.Uniform(0.5, 1.5));
      const double rmax = std::max(0.3 * rc, 0.006);
      for (int s = 0; s < satellites; ++s)
      {
        const glm::dvec3 p = centres[static_cast<std::size_t>(c)] + 1.3 * rc * rng.InBall();
        const double r = PowerLawRadius(rng, 0.004, rmax);
        addHalo(p, r);
      }
    }
    // Filaments: each cluster to its two nearest neighbours (each pair once), a string of small
    // halos scattered by about 0.006 per axis around the segment.
    std::vector<std::pair<int, int>> pairs;
    for (int c = 0; c < clusters; ++c)
    {
      int best[2] = { -1, -1 };
      double bestD[2] = { std::numeric_limits<double>::max(), std::numeric_limits<double>::max() };
      for (int o = 0; o < clusters; ++o)
      {
        if (o == c)
        {
          continue;
        }
        const glm::dvec3 d =
          centres[static_cast<std::size_t>(o)] - centres[static_cast<std::size_t>(c)];
        const double d2 = d.x * d.x + d.y * d.y + d.z * d.z;
        if (d2 < bestD[0])
        {
          best[1] = best[0];
          bestD[1] = bestD[0];
          best[0] = o;
          bestD[0] = d2;
        }
        else if (d2 < bestD[1])
        {
          best[1] = o;
          bestD[1] = d2;
        }
      }
      for (int n : best)
      {
        const std::pair<int, int> pr(std::min(c, n), std::max(c, n));
        if (n >= 0 && std::find(pairs.begin(), pairs.end(), pr) == pairs.end())
        {
          pairs.push_back(pr);
        }
      }
    }
    for (const auto& pr : pairs)
    {
      const glm::dvec3 a = centres[static_cast<std::size_t>(pr.first)];
      const glm::dvec3 b = centres[static_cast<std::size_t>(pr.second)];
      const glm::dvec3 d = b - a;
      const double length = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
      const int n = static_cast<int>(length * 150.0);
      for (int i = 0; i < n; ++i)
      {
        const double t = rng.Uniform(0.1, 0.9);
        // A sum of three uniforms: a bell-shaped transverse offset.
        glm::dvec3 scatter = rng.UniformVector(-1.0, 1.0);
        scatter += rng.UniformVector(-1.0, 1.0);
        scatter += rng.UniformVector(-1.0, 1.0);
        const double r = PowerLawRadius(rng, 0.003, 0.02);
        addHalo(a + t * d + 0.006 * scatter, r);
      }
    }
    // Isolated field halos.
    for (int i = 0; i < 400; ++i)
    {
      const glm::dvec3 p = rng.UniformVector(0.0, 1.0);
      const double r = PowerLawRadius(rng, 0.003, 0.015);
      addHalo(p, r);
    }
    this->BuildBuckets();
  }
};

CosmoField::CosmoField(uint64_t seed)
  : Internals(std::make_shared<const Impl>(seed))
{
}

double CosmoField::operator()(const glm::dvec3& world) const
{
  return this->Internals->Evaluate(world.x, world.y, world.z);
}

std::size_t CosmoField::NumberOfHalos() const
{
  return this->Internals->Halos.size();
}

void CosmoField::Sample(const Box& box, double cellSize, std::vector<float>& values) const
{
  const Impl& f = *this->Internals;
  values.assign(static_cast<std::size_t>(box.Cells()), 0.0f);
  if (box.Empty())
  {
    return;
  }
  const glm::i64vec3 ext = box.Extent();
  constexpr int64_t block = 8;
  constexpr int waves = Impl::NumberOfWaves;

  std::vector<uint32_t> stamp(f.Halos.size(), 0);
  uint32_t currentStamp = 0;
  std::vector<uint32_t> list;
  // Per-axis tables for the block: cell centre coordinate and the waves' bump factors.
  double coord[3][block];
  double bump[3][waves][block];

  for (int64_t bz = 0; bz < ext.z; bz += block)
  {
    for (int64_t by = 0; by < ext.y; by += block)
    {
      for (int64_t bx = 0; bx < ext.x; bx += block)
      {
        const int64_t b0[3] = { bx, by, bz };
        int64_t n[3];
        for (int a = 0; a < 3; ++a)
        {
          n[a] = std::min(block, ext[a] - b0[a]);
          for (int64_t i = 0; i < n[a]; ++i)
          {
            // The cell centre exactly as a caller of operator() computes it.
            const double c = (static_cast<double>(box.Lo[a] + b0[a] + i) + 0.5) * cellSize;
            coord[a][i] = c;
            for (int w = 0; w < waves; ++w)
            {
              bump[a][w][i] = Impl::Bump(f.Waves[w].K[a] * c + f.Waves[w].P[a]);
            }
          }
        }
        const double lo[3] = { coord[0][0], coord[1][0], coord[2][0] };
        const double hi[3] = { coord[0][n[0] - 1], coord[1][n[1] - 1], coord[2][n[2] - 1] };

        // Gather the halos whose support meets the box of the block's cell centres.
        ++currentStamp;
        list.clear();
        const int x0 = Impl::BucketOf(lo[0]), x1 = Impl::BucketOf(hi[0]);
        const int y0 = Impl::BucketOf(lo[1]), y1 = Impl::BucketOf(hi[1]);
        const int z0 = Impl::BucketOf(lo[2]), z1 = Impl::BucketOf(hi[2]);
        for (int k = z0; k <= z1; ++k)
        {
          for (int j = y0; j <= y1; ++j)
          {
            for (int i = x0; i <= x1; ++i)
            {
              const int b = i + Impl::Buckets * (j + Impl::Buckets * k);
              for (uint32_t e = f.BucketStart[b]; e < f.BucketStart[b + 1]; ++e)
              {
                const uint32_t h = f.BucketHalos[e];
                if (stamp[h] == currentStamp)
                {
                  continue;
                }
                stamp[h] = currentStamp;
                const Impl::Halo& halo = f.Halos[h];
                const double c[3] = { halo.Cx, halo.Cy, halo.Cz };
                double d2 = 0.0;
                for (int a = 0; a < 3; ++a)
                {
                  const double d =
                    c[a] < lo[a] ? lo[a] - c[a] : (c[a] > hi[a] ? c[a] - hi[a] : 0.0);
                  d2 += d * d;
                }
                if (d2 < halo.R2)
                {
                  list.push_back(h);
                }
              }
            }
          }
        }
        // Increasing halo index: the same summation order as Impl::Evaluate, whose bucket list
        // is a superset in the same order (the extra halos contribute nothing).
        std::sort(list.begin(), list.end());

        for (int64_t k = 0; k < n[2]; ++k)
        {
          for (int64_t j = 0; j < n[1]; ++j)
          {
            float* out = values.data() + (b0[0] + ext.x * ((b0[1] + j) + ext.y * (b0[2] + k)));
            for (int64_t i = 0; i < n[0]; ++i)
            {
              double sum = f.Base;
              for (int w = 0; w < waves; ++w)
              {
                sum += f.Waves[w].Amp * bump[0][w][i] * bump[1][w][j] * bump[2][w][k];
              }
              const double x = coord[0][i], y = coord[1][j], z = coord[2][k];
              for (uint32_t h : list)
              {
                sum = Impl::AddHalo(sum, f.Halos[h], x, y, z);
              }
              out[i] = static_cast<float>(sum);
            }
          }
        }
      }
    }
  }
}

double CosmoDensity(uint64_t seed, const Hierarchy& h, const glm::dvec3& indexPos)
{
  const CosmoField field(seed);
  return field(h.Origin + indexPos * h.Spacing0);
}

// ------------------------------------------------------------------------------------------------
// Parameters.

namespace
{

std::string Trim(const std::string& s)
{
  const char* ws = " \t\r\n";
  const std::size_t b = s.find_first_not_of(ws);
  if (b == std::string::npos)
  {
    return std::string();
  }
  const std::size_t e = s.find_last_not_of(ws);
  return s.substr(b, e - b + 1);
}

std::string Lower(std::string s)
{
  for (char& c : s)
  {
    if (c >= 'A' && c <= 'Z')
    {
      c = static_cast<char>(c - 'A' + 'a');
    }
  }
  return s;
}

[[noreturn]] void BadValue(const std::string& key, const std::string& value, const std::string& why)
{
  throw std::invalid_argument(
    "cosmo parameters: bad value '" + value + "' for key '" + key + "': " + why);
}

/// Parses an unsigned integer; with `suffixes`, also "<digits>[.<digits>](k|K|M)" whose value
/// must be an integer. Overflow-checked.
uint64_t ParseUnsigned(const std::string& key, const std::string& value, bool suffixes)
{
  const uint64_t maxValue = std::numeric_limits<uint64_t>::max();
  std::size_t i = 0;
  uint64_t intPart = 0;
  std::size_t digits = 0;
  for (; i < value.size() && value[i] >= '0' && value[i] <= '9'; ++i, ++digits)
  {
    const uint64_t d = static_cast<uint64_t>(value[i] - '0');
    if (intPart > (maxValue - d) / 10)
    {
      BadValue(key, value, "number too large");
    }
    intPart = intPart * 10 + d;
  }
  if (digits == 0)
  {
    BadValue(key, value,
      suffixes ? "expected a non-negative integer, optionally with a k or M suffix"
               : "expected a non-negative integer");
  }
  uint64_t fracPart = 0;
  uint64_t fracScale = 1;
  bool hasFraction = false;
  if (suffixes && i < value.size() && value[i] == '.')
  {
    hasFraction = true;
    ++i;
    std::size_t fracDigits = 0;
    for (; i < value.size() && value[i] >= '0' && value[i] <= '9'; ++i, ++fracDigits)
    {
      if (fracDigits >= 6)
      {
        BadValue(key, value, "too many decimals");
      }
      fracPart = fracPart * 10 + static_cast<uint64_t>(value[i] - '0');
      fracScale *= 10;
    }
    if (fracDigits == 0)
    {
      BadValue(key, value, "expected digits after the decimal point");
    }
  }
  uint64_t multiplier = 1;
  if (suffixes && i < value.size())
  {
    if (value[i] == 'k' || value[i] == 'K')
    {
      multiplier = 1000;
      ++i;
    }
    else if (value[i] == 'M')
    {
      multiplier = 1000000;
      ++i;
    }
  }
  if (i != value.size())
  {
    BadValue(key, value,
      suffixes ? "expected a non-negative integer, optionally with a k or M suffix (e.g. 19M)"
               : "expected a non-negative integer");
  }
  if (hasFraction && multiplier == 1)
  {
    BadValue(key, value, "a decimal number needs a k or M suffix");
  }
  if (intPart > maxValue / multiplier)
  {
    BadValue(key, value, "number too large");
  }
  const uint64_t whole = intPart * multiplier;
  // fracPart < fracScale <= 10^6, multiplier <= 10^6: no overflow.
  const uint64_t fracScaled = fracPart * multiplier;
  if (fracScaled % fracScale != 0)
  {
    BadValue(key, value, "not an integer");
  }
  if (whole > maxValue - fracScaled / fracScale)
  {
    BadValue(key, value, "number too large");
  }
  return whole + fracScaled / fracScale;
}

int64_t ParseSigned(const std::string& key, const std::string& value, bool suffixes,
  int64_t minValue, int64_t maxValue)
{
  const uint64_t v = ParseUnsigned(key, value, suffixes);
  if (v > static_cast<uint64_t>(maxValue) || static_cast<int64_t>(v) < minValue)
  {
    BadValue(key, value,
      "must be between " + std::to_string(minValue) + " and " + std::to_string(maxValue));
  }
  return static_cast<int64_t>(v);
}

} // namespace

CosmoParameters ParseCosmoParameters(const std::string& spec)
{
  CosmoParameters p;
  const std::string all = Trim(spec);
  if (all.empty())
  {
    return p;
  }
  std::vector<std::string> seen;
  std::size_t start = 0;
  for (;;)
  {
    const std::size_t comma = all.find(',', start);
    const std::string item =
      Trim(all.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (item.empty())
    {
      throw std::invalid_argument("cosmo parameters: empty item in '" + spec + "'");
    }
    const std::size_t eq = item.find('=');
    if (eq == std::string::npos)
    {
      throw std::invalid_argument("cosmo parameters: item '" + item +
        "' is not key=value (keys: grids, levels, cells, seed, roots, values)");
    }
    const std::string key = Lower(Trim(item.substr(0, eq)));
    const std::string value = Trim(item.substr(eq + 1));
    if (std::find(seen.begin(), seen.end(), key) != seen.end())
    {
      throw std::invalid_argument("cosmo parameters: key '" + key + "' given twice");
    }
    seen.push_back(key);
    const int64_t maxCount = int64_t(1) << 50;
    if (key == "grids")
    {
      p.Grids = ParseSigned(key, value, true, 1, maxCount);
    }
    else if (key == "levels")
    {
      p.Levels = static_cast<int>(ParseSigned(key, value, false, 1, 30));
    }
    else if (key == "cells")
    {
      p.Cells = ParseSigned(key, value, true, 1, maxCount);
    }
    else if (key == "seed")
    {
      p.Seed = ParseUnsigned(key, value, false);
    }
    else if (key == "roots")
    {
      p.RootGrids = ParseSigned(key, value, true, 0, maxCount);
    }
    else if (key == "values")
    {
      const std::string v = Lower(value);
      if (v == "1" || v == "true" || v == "on" || v == "yes")
      {
        p.GenerateValues = true;
      }
      else if (v == "0" || v == "false" || v == "off" || v == "no")
      {
        p.GenerateValues = false;
      }
      else
      {
        BadValue(key, value, "expected 0 or 1");
      }
    }
    else
    {
      throw std::invalid_argument("cosmo parameters: unknown key '" + key +
        "' (keys: grids, levels, cells, seed, roots, values)");
    }
    if (comma == std::string::npos)
    {
      break;
    }
    start = comma + 1;
  }
  return p;
}

std::string FormatCosmoParameters(const CosmoParameters& p)
{
  std::ostringstream s;
  s << "grids=" << p.Grids << ",levels=" << p.Levels << ",cells=" << p.Cells << ",seed=" << p.Seed
    << ",roots=" << p.RootGrids << ",values=" << (p.GenerateValues ? 1 : 0);
  return s.str();
}

// ------------------------------------------------------------------------------------------------
// Structure.

namespace
{

/// Fraction of level-0 cells that the cell budget model gives to level 1, in units of the domain
/// volume: level 1 refines about this fraction of the domain.
constexpr double Level1VolumeFraction = 0.1;
/// Ratio of grid counts of consecutive refined levels (geometric distribution over levels).
constexpr double GridCountRatio = 0.75;
/// A level never covers more than this fraction of its parent level's volume.
constexpr double MaxVolumeFraction = 0.3;
/// Joining boxes pairwise (JoinToCount) is tried only up to this many boxes on a level.
constexpr int64_t MaxJoinBoxes = 64;
/// Smallest tile edge (cells) considered when tiling a parent.
constexpr double MinTile = 2.0;
/// A level's merged tiles are accepted when they form at least this fraction of the requested
/// grids (and not more than the requested grids); splitting makes up the rest.
constexpr double MinMergedFraction = 0.6;

/// Splits `box` into `count` boxes by recursive bisection of the longest axis, cutting in
/// proportion to the counts on either side. Appends in a deterministic order.
void SplitDomain(const Box& box, int64_t count, std::vector<Box>& out)
{
  if (count <= 1)
  {
    out.push_back(box);
    return;
  }
  const glm::i64vec3 e = box.Extent();
  int axis = 0;
  for (int a = 1; a < 3; ++a)
  {
    if (e[a] > e[axis])
    {
      axis = a;
    }
  }
  const int64_t c1 = count / 2;
  const int64_t c2 = count - c1;
  int64_t cut = box.Lo[axis] + (e[axis] * c1 + count / 2) / count;
  cut = std::max(box.Lo[axis] + 1, std::min(box.Hi[axis] - 1, cut));
  Box a = box;
  Box b = box;
  a.Hi[axis] = cut;
  b.Lo[axis] = cut;
  SplitDomain(a, c1, out);
  SplitDomain(b, c2, out);
}

/// One candidate set for a level: each parent (a level-(l-1) grid, refined to level l) cut into
/// a lattice of near-equal tiles of edge about T cells. Tile (i,j,k) of parent p spans cells
/// [Bound(p,a,i), Bound(p,a,i+1)) on axis a, so tiles of one parent partition it and never cross
/// its boundary; hence any union of tiles of one parent is properly nested.
struct Tiling
{
  struct Parent
  {
    int64_t Offset = 0;  ///< first tile's index in the flat tile arrays
    glm::i64vec3 N{ 1 }; ///< tiles per axis (>= 1, <= extent)
    glm::i64vec3 Lo{ 0 };
    glm::i64vec3 Ext{ 1 };
    int64_t Bound(int a, int64_t i) const { return this->Lo[a] + (i * this->Ext[a]) / this->N[a]; }
  };
  std::vector<Parent> Parents;
  std::vector<int32_t> ParentOf; ///< per tile
  std::vector<double> Density;   ///< per tile: the field at the tile centre
  int64_t TotalCells = 0;        ///< cells of all parents (refined)
  int64_t MaxTileCells = 0;      ///< cells of the biggest tile

  int64_t NumberOfTiles() const { return static_cast<int64_t>(this->ParentOf.size()); }

  glm::i64vec3 Local(int64_t tile, const Parent& p) const
  {
    const int64_t l = tile - p.Offset;
    return glm::i64vec3(l % p.N.x, (l / p.N.x) % p.N.y, l / (p.N.x * p.N.y));
  }

  Box TileBox(int64_t tile) const
  {
    const Parent& p = this->Parents[static_cast<std::size_t>(this->ParentOf[tile])];
    const glm::i64vec3 ijk = this->Local(tile, p);
    Box b;
    for (int a = 0; a < 3; ++a)
    {
      b.Lo[a] = p.Bound(a, ijk[a]);
      b.Hi[a] = p.Bound(a, ijk[a] + 1);
    }
    return b;
  }
};

/// A box of a refined level and the index of its parent in the parent level's box list.
struct LevelBox
{
  Box Cells;
  int32_t Parent = 0;
};

/// Candidate tiles and their selection for one level at a time. One builder serves all levels
/// so that its large scratch arrays are allocated (and touched) once.
class LevelBuilder
{
public:
  explicit LevelBuilder(const CosmoField& field)
    : Field(field)
  {
  }

  /// Starts a level: `parents` are the level-(l-1) boxes, `cellSize` the world size of a
  /// level-l cell.
  void SetParents(const std::vector<Box>& parents, double cellSize)
  {
    this->ParentsRefined.clear();
    this->MaxExtent = 1;
    for (const Box& b : parents)
    {
      const Box r = b.Refined(glm::i64vec3(2));
      this->ParentsRefined.push_back(r);
      const glm::i64vec3 e = r.Extent();
      this->MaxExtent = std::max(this->MaxExtent, std::max(e.x, std::max(e.y, e.z)));
    }
    this->CellSize = cellSize;
  }

  const CosmoField& GetField() const { return this->Field; }
  /// Longest parent edge in cells of the level being built.
  int64_t GetMaxExtent() const { return this->MaxExtent; }

  /// Tiles the parents with tiles of edge about `tile`, samples the field at the tile centres,
  /// selects the densest tiles worth `targetCells` cells and merges each parent's selected tiles
  /// into boxes (greedy: runs along x, then whole rows along y, then whole slabs along z).
  std::vector<LevelBox> Evaluate(double tile, int64_t targetCells)
  {
    this->BuildTiling(tile);
    const int64_t nt = this->T.NumberOfTiles();
    const double meanTileCells = static_cast<double>(this->T.TotalCells) / static_cast<double>(nt);
    int64_t k = static_cast<int64_t>(static_cast<double>(targetCells) / meanTileCells + 0.5);
    k = std::max<int64_t>(1, std::min(k, nt));

    // The k densest tiles; ties broken by tile index, so the set is unique.
    std::vector<int64_t>& order = this->Order;
    order.resize(static_cast<std::size_t>(nt));
    for (int64_t i = 0; i < nt; ++i)
    {
      order[static_cast<std::size_t>(i)] = i;
    }
    const std::vector<double>& dens = this->T.Density;
    auto denser = [&dens](int64_t a, int64_t b) {
      return dens[a] > dens[b] || (dens[a] == dens[b] && a < b);
    };
    if (k < nt)
    {
      std::nth_element(order.begin(), order.begin() + k, order.end(), denser);
    }
    // Tiles differ in size (a parent's edge is rarely a multiple of T), so correct k until the
    // selected cells match the budget to within half a mean tile: add the next-densest tiles or
    // drop the least dense of the selection, never more than the deficit or excess allows.
    // order[0, k) stays the k densest tiles throughout.
    auto cellsOf = [this, &order](int64_t begin, int64_t end) {
      int64_t n = 0;
      for (int64_t i = begin; i < end; ++i)
      {
        n += this->T.TileBox(order[static_cast<std::size_t>(i)]).Cells();
      }
      return n;
    };
    int64_t cells = cellsOf(0, k);
    const int64_t tolerance = std::max<int64_t>(1, static_cast<int64_t>(0.5 * meanTileCells));
    const int64_t maxTile = std::max<int64_t>(1, this->T.MaxTileCells);
    int lastStep = 0;
    for (int round = 0; round < 64; ++round)
    {
      const int64_t excess = cells - targetCells;
      if (excess > -tolerance && excess < tolerance)
      {
        break;
      }
      if (excess < 0)
      {
        const int64_t extra = std::min(nt - k, std::max<int64_t>(1, -excess / maxTile));
        if (extra == 0 || lastStep == -1)
        {
          break;
        }
        std::nth_element(order.begin() + k, order.begin() + k + extra, order.end(), denser);
        cells += cellsOf(k, k + extra);
        k += extra;
        lastStep = extra == 1 ? 1 : 0;
      }
      else
      {
        const int64_t drop = std::min(k - 1, std::max<int64_t>(1, excess / maxTile));
        if (drop == 0 || lastStep == 1)
        {
          break;
        }
        std::nth_element(order.begin(), order.begin() + (k - drop), order.begin() + k, denser);
        cells -= cellsOf(k - drop, k);
        k -= drop;
        lastStep = drop == 1 ? -1 : 0;
      }
    }
    std::vector<uint8_t>& selected = this->Selected;
    selected.assign(static_cast<std::size_t>(nt), 0);
    std::vector<int32_t> touched;
    std::vector<uint8_t> parentTouched(this->T.Parents.size(), 0);
    for (int64_t i = 0; i < k; ++i)
    {
      const int64_t t = order[static_cast<std::size_t>(i)];
      selected[static_cast<std::size_t>(t)] = 1;
      const int32_t p = this->T.ParentOf[static_cast<std::size_t>(t)];
      if (!parentTouched[static_cast<std::size_t>(p)])
      {
        parentTouched[static_cast<std::size_t>(p)] = 1;
        touched.push_back(p);
      }
    }
    std::sort(touched.begin(), touched.end());

    std::vector<LevelBox> boxes;
    for (int32_t pi : touched)
    {
      this->MergeParent(pi, selected, boxes);
    }
    return boxes;
  }

private:
  const CosmoField& Field;
  std::vector<Box> ParentsRefined;
  double CellSize = 1.0;
  int64_t MaxExtent = 1;
  Tiling T;
  // Scratch buffers reused between evaluations.
  std::vector<int64_t> Order;
  std::vector<uint8_t> Selected;
  std::vector<uint8_t> Used;

  void BuildTiling(double tile)
  {
    Tiling& t = this->T;
    t.Parents.clear();
    t.TotalCells = 0;
    t.MaxTileCells = 0;
    int64_t offset = 0;
    for (const Box& b : this->ParentsRefined)
    {
      Tiling::Parent p;
      p.Offset = offset;
      p.Lo = b.Lo;
      p.Ext = b.Extent();
      for (int a = 0; a < 3; ++a)
      {
        const int64_t n = static_cast<int64_t>(static_cast<double>(p.Ext[a]) / tile + 0.5);
        p.N[a] = std::max<int64_t>(1, std::min(n, p.Ext[a]));
      }
      offset += p.N.x * p.N.y * p.N.z;
      t.TotalCells += b.Cells();
      // Tile edges are floor or ceil of Ext / N.
      const glm::i64vec3 edge = (p.Ext + p.N - int64_t(1)) / p.N;
      t.MaxTileCells = std::max(t.MaxTileCells, edge.x * edge.y * edge.z);
      t.Parents.push_back(p);
    }
    t.ParentOf.resize(static_cast<std::size_t>(offset));
    t.Density.resize(static_cast<std::size_t>(offset));
    for (std::size_t pi = 0; pi < t.Parents.size(); ++pi)
    {
      const Tiling::Parent& p = t.Parents[pi];
      std::fill(t.ParentOf.begin() + p.Offset,
        t.ParentOf.begin() + p.Offset + p.N.x * p.N.y * p.N.z, static_cast<int32_t>(pi));
    }
    const double cs = this->CellSize;
    const CosmoField& field = this->Field;
    ParallelFor(offset, 8192, [&t, cs, &field](int64_t begin, int64_t end) {
      for (int64_t i = begin; i < end; ++i)
      {
        const Box b = t.TileBox(i);
        // Centre in cells of this level: (Lo + Hi) / 2, exact in double.
        const glm::dvec3 c = glm::dvec3(b.Lo + b.Hi) * 0.5;
        t.Density[static_cast<std::size_t>(i)] = field(c * cs);
      }
    });
  }

  void MergeParent(int32_t pi, const std::vector<uint8_t>& selected, std::vector<LevelBox>& out)
  {
    const Tiling::Parent& p = this->T.Parents[static_cast<std::size_t>(pi)];
    const int64_t nx = p.N.x, ny = p.N.y, nz = p.N.z;
    std::vector<uint8_t>& used = this->Used;
    used.assign(static_cast<std::size_t>(nx * ny * nz), 0);
    auto free = [&](int64_t x, int64_t y, int64_t z) {
      const int64_t l = x + nx * (y + ny * z);
      return selected[static_cast<std::size_t>(p.Offset + l)] && !used[static_cast<std::size_t>(l)];
    };
    for (int64_t z = 0; z < nz; ++z)
    {
      for (int64_t y = 0; y < ny; ++y)
      {
        for (int64_t x = 0; x < nx; ++x)
        {
          if (!free(x, y, z))
          {
            continue;
          }
          int64_t x1 = x + 1;
          while (x1 < nx && free(x1, y, z))
          {
            ++x1;
          }
          int64_t y1 = y + 1;
          for (;; ++y1)
          {
            bool ok = y1 < ny;
            for (int64_t i = x; ok && i < x1; ++i)
            {
              ok = free(i, y1, z);
            }
            if (!ok)
            {
              break;
            }
          }
          int64_t z1 = z + 1;
          for (;; ++z1)
          {
            bool ok = z1 < nz;
            for (int64_t j = y; ok && j < y1; ++j)
            {
              for (int64_t i = x; ok && i < x1; ++i)
              {
                ok = free(i, j, z1);
              }
            }
            if (!ok)
            {
              break;
            }
          }
          for (int64_t k = z; k < z1; ++k)
          {
            for (int64_t j = y; j < y1; ++j)
            {
              for (int64_t i = x; i < x1; ++i)
              {
                used[static_cast<std::size_t>(i + nx * (j + ny * k))] = 1;
              }
            }
          }
          LevelBox lb;
          lb.Parent = pi;
          lb.Cells.Lo = glm::i64vec3(p.Bound(0, x), p.Bound(1, y), p.Bound(2, z));
          lb.Cells.Hi = glm::i64vec3(p.Bound(0, x1), p.Bound(1, y1), p.Bound(2, z1));
          out.push_back(lb);
        }
      }
    }
  }
};

int64_t CellsOf(const std::vector<LevelBox>& boxes)
{
  int64_t n = 0;
  for (const LevelBox& b : boxes)
  {
    n += b.Cells.Cells();
  }
  return n;
}

/// Splits the boxes with the most cells in halves (longest axis, middle cell) until there are
/// `count` boxes or no box has more than one cell. Halves stay inside the parent.
void SplitToCount(std::vector<LevelBox>& boxes, int64_t count)
{
  // Max-heap on (cells, -index): the largest box first, the lowest index among equals.
  auto less = [&boxes](std::size_t a, std::size_t b) {
    const int64_t ca = boxes[a].Cells.Cells(), cb = boxes[b].Cells.Cells();
    return ca < cb || (ca == cb && a > b);
  };
  std::priority_queue<std::size_t, std::vector<std::size_t>, decltype(less)> heap(less);
  for (std::size_t i = 0; i < boxes.size(); ++i)
  {
    heap.push(i);
  }
  while (static_cast<int64_t>(boxes.size()) < count && !heap.empty())
  {
    const std::size_t i = heap.top();
    heap.pop();
    const glm::i64vec3 e = boxes[i].Cells.Extent();
    int axis = 0;
    for (int a = 1; a < 3; ++a)
    {
      if (e[a] > e[axis])
      {
        axis = a;
      }
    }
    if (e[axis] < 2)
    {
      break; // the largest box is a single cell: nothing can be split
    }
    LevelBox second = boxes[i];
    const int64_t cut = boxes[i].Cells.Lo[axis] + e[axis] / 2;
    boxes[i].Cells.Hi[axis] = cut;
    second.Cells.Lo[axis] = cut;
    boxes.push_back(second);
    heap.push(i);
    heap.push(boxes.size() - 1);
  }
}

/// Reduces the boxes to `count`: while there are at most MaxJoinBoxes, replaces the two boxes
/// of one parent whose bounding box adds the fewest cells (and meets no other box) by that
/// bounding box; otherwise, or when no pair can be joined, drops the box with the fewest cells.
/// Joined boxes stay inside their common parent and disjoint from the others.
void JoinToCount(std::vector<LevelBox>& boxes, int64_t count)
{
  while (static_cast<int64_t>(boxes.size()) > count)
  {
    const std::size_t n = boxes.size();
    std::size_t bi = n, bj = n;
    int64_t bestCost = std::numeric_limits<int64_t>::max();
    Box bestUnion;
    if (static_cast<int64_t>(n) <= MaxJoinBoxes)
    {
      for (std::size_t i = 0; i < n; ++i)
      {
        for (std::size_t j = i + 1; j < n; ++j)
        {
          if (boxes[i].Parent != boxes[j].Parent)
          {
            continue;
          }
          const Box u{ glm::min(boxes[i].Cells.Lo, boxes[j].Cells.Lo),
            glm::max(boxes[i].Cells.Hi, boxes[j].Cells.Hi) };
          const int64_t cost = u.Cells() - boxes[i].Cells.Cells() - boxes[j].Cells.Cells();
          if (cost >= bestCost)
          {
            continue;
          }
          bool clear = true;
          for (std::size_t o = 0; clear && o < n; ++o)
          {
            clear = o == i || o == j || !u.Overlaps(boxes[o].Cells);
          }
          if (clear)
          {
            bestCost = cost;
            bi = i;
            bj = j;
            bestUnion = u;
          }
        }
      }
    }
    if (bi < n)
    {
      boxes[bi].Cells = bestUnion;
      boxes.erase(boxes.begin() + static_cast<std::ptrdiff_t>(bj));
      continue;
    }
    std::size_t smallest = 0;
    for (std::size_t i = 1; i < n; ++i)
    {
      if (boxes[i].Cells.Cells() < boxes[smallest].Cells.Cells())
      {
        smallest = i;
      }
    }
    boxes.erase(boxes.begin() + static_cast<std::ptrdiff_t>(smallest));
  }
}

/// Shaves slabs off the biggest boxes, on the side where the field is lower, until the boxes
/// hold at most `targetCells` cells (within 2%) or every box is a single cell. Only needed when a
/// level has very few, coarse tiles (e.g. one grid on a level). Boxes only shrink, so they stay
/// inside their parents and disjoint.
void TrimToCells(
  std::vector<LevelBox>& boxes, int64_t targetCells, const CosmoField& field, double cellSize)
{
  int64_t total = CellsOf(boxes);
  const int64_t limit = targetCells + targetCells / 50;
  auto less = [&boxes](std::size_t a, std::size_t b) {
    const int64_t ca = boxes[a].Cells.Cells(), cb = boxes[b].Cells.Cells();
    return ca < cb || (ca == cb && a > b);
  };
  std::priority_queue<std::size_t, std::vector<std::size_t>, decltype(less)> heap(less);
  for (std::size_t i = 0; i < boxes.size(); ++i)
  {
    heap.push(i);
  }
  while (total > limit && !heap.empty())
  {
    const std::size_t i = heap.top();
    heap.pop();
    Box& b = boxes[i].Cells;
    const glm::i64vec3 e = b.Extent();
    int axis = 0;
    for (int a = 1; a < 3; ++a)
    {
      if (e[a] > e[axis])
      {
        axis = a;
      }
    }
    if (e[axis] < 2)
    {
      break; // the largest box is a single cell
    }
    const int64_t face = b.Cells() / e[axis];
    const int64_t excess = total - targetCells;
    const int64_t thickness =
      std::max<int64_t>(1, std::min<int64_t>(std::max<int64_t>(1, e[axis] / 4), excess / face));
    // Field at the centres of the two candidate slabs (in cells of this level, exact halves).
    glm::dvec3 lowSide = glm::dvec3(b.Lo + b.Hi) * 0.5;
    glm::dvec3 highSide = lowSide;
    lowSide[axis] = static_cast<double>(b.Lo[axis]) + 0.5 * static_cast<double>(thickness);
    highSide[axis] = static_cast<double>(b.Hi[axis]) - 0.5 * static_cast<double>(thickness);
    if (field(lowSide * cellSize) < field(highSide * cellSize))
    {
      b.Lo[axis] += thickness;
    }
    else
    {
      b.Hi[axis] -= thickness;
    }
    total -= thickness * face;
    heap.push(i);
  }
}

/// Builds one refined level with exactly `grids` boxes (when the parents have room) holding about
/// `targetCells` cells. `tileGuess` carries the tile edge, relative to the cube root of the mean
/// grid size, from level to level.
std::vector<LevelBox> BuildLevel(LevelBuilder& builder, const std::vector<Box>& parents,
  double cellSize, int64_t grids, int64_t targetCells, double& tileGuess)
{
  builder.SetParents(parents, cellSize);
  const CosmoField& field = builder.GetField();

  // Search the tile edge T. With the cell budget fixed, bigger tiles give fewer boxes (about
  // B ~ T^-2: a blob of volume V tiled by T^3 tiles merges into ~ (V^(1/3)/T)^2 runs). Aim for a
  // box count between MinMergedFraction and 1 times `grids`; the remainder comes from splitting
  // the biggest boxes. (Smaller tiles would need fewer splits but cost time: the field is
  // sampled at every candidate tile for every T tried.)
  const double meanGrid = static_cast<double>(targetCells) / static_cast<double>(grids);
  const double tmax = static_cast<double>(builder.GetMaxExtent()) + 1.0;
  double t = std::max(MinTile, std::min(tmax, tileGuess * CubeRoot(meanGrid)));
  double tBelow = 0.0;                                // largest T known to give too many boxes
  double tAbove = std::numeric_limits<double>::max(); // smallest T known to give few enough
  std::vector<LevelBox> best;
  double bestTile = t;
  std::vector<LevelBox> over; // the fewest boxes among the tilings with too many
  const double aim = 0.5 * (1.0 + MinMergedFraction) * static_cast<double>(grids);
  for (int iteration = 0; iteration < 10; ++iteration)
  {
    std::vector<LevelBox> boxes = builder.Evaluate(t, targetCells);
    const int64_t b = static_cast<int64_t>(boxes.size());
    if (b > grids && (over.empty() || b < static_cast<int64_t>(over.size())))
    {
      over = boxes;
    }
    if (b <= grids)
    {
      tAbove = std::min(tAbove, t);
      if (best.empty() || b > static_cast<int64_t>(best.size()))
      {
        best = std::move(boxes);
        bestTile = t;
      }
      if (static_cast<double>(b) >= MinMergedFraction * static_cast<double>(grids) || t <= MinTile)
      {
        break;
      }
    }
    else
    {
      tBelow = std::max(tBelow, t);
      if (t >= tmax)
      {
        break;
      }
    }
    double next = t * std::sqrt(static_cast<double>(b) / aim);
    next = std::max(0.5 * t, std::min(2.0 * t, next));
    if (next <= tBelow || next >= tAbove)
    {
      next =
        (tAbove < std::numeric_limits<double>::max()) ? std::sqrt(tBelow * tAbove) : 2.0 * tBelow;
    }
    next = std::max(MinTile, std::min(tmax, next));
    // B(T) jumps where the tile counts per parent change; once the bracket is this narrow,
    // further bisection only hops between the same few tilings.
    const bool bracketed = tAbove < std::numeric_limits<double>::max() && tBelow > 0.0;
    if (std::fabs(next - t) < 1e-3 * t || (bracketed && tAbove < 1.03 * tBelow))
    {
      break;
    }
    t = next;
  }
  if (!best.empty())
  {
    tileGuess = bestTile / CubeRoot(meanGrid);
  }

  // Bring the count to `grids` exactly and the cells to at most the target: split the tiling
  // with few enough boxes, or join (or, failing that, drop) boxes of the tiling with too many.
  // With only a handful of grids on a level B(T) jumps by more than the grid count, and either
  // can be the closer one in cells: keep the result nearer the cell target.
  auto finish = [&](std::vector<LevelBox> boxes) {
    if (static_cast<int64_t>(boxes.size()) < grids)
    {
      SplitToCount(boxes, grids);
    }
    else
    {
      JoinToCount(boxes, grids);
    }
    TrimToCells(boxes, targetCells, field, cellSize);
    return boxes;
  };
  auto miss = [targetCells](const std::vector<LevelBox>& boxes) {
    const int64_t d = CellsOf(boxes) - targetCells;
    return d < 0 ? -d : d;
  };
  if (best.empty())
  {
    best = finish(std::move(over));
  }
  else
  {
    best = finish(std::move(best));
    if (!over.empty() && static_cast<int64_t>(over.size()) <= MaxJoinBoxes &&
      miss(best) > targetCells / 20)
    {
      std::vector<LevelBox> joined = finish(std::move(over));
      if (static_cast<int64_t>(joined.size()) == grids && miss(joined) < miss(best))
      {
        best = std::move(joined);
      }
    }
  }
  std::sort(best.begin(), best.end(), [](const LevelBox& a, const LevelBox& b) {
    if (a.Parent != b.Parent)
    {
      return a.Parent < b.Parent;
    }
    for (int ax = 2; ax >= 0; --ax)
    {
      if (a.Cells.Lo[ax] != b.Cells.Lo[ax])
      {
        return a.Cells.Lo[ax] < b.Cells.Lo[ax];
      }
    }
    return false;
  });
  return best;
}

/// Grid counts of levels 1..levels-1: at least one each, the rest geometric with ratio
/// GridCountRatio, rounded so that they sum to `total` exactly.
std::vector<int64_t> GridsPerRefinedLevel(int64_t total, int levels)
{
  const int n = levels - 1;
  std::vector<int64_t> g(static_cast<std::size_t>(n), 1);
  if (n == 0)
  {
    return g;
  }
  std::vector<double> w(static_cast<std::size_t>(n));
  double sum = 0.0;
  double q = 1.0;
  for (int l = 0; l < n; ++l)
  {
    w[static_cast<std::size_t>(l)] = q;
    sum += q;
    q *= GridCountRatio;
  }
  const int64_t extra = total - n;
  double cumulative = 0.0;
  int64_t assigned = 0;
  for (int l = 0; l < n; ++l)
  {
    cumulative += w[static_cast<std::size_t>(l)];
    const int64_t upTo = (l == n - 1)
      ? extra
      : static_cast<int64_t>(static_cast<double>(extra) * cumulative / sum + 0.5);
    g[static_cast<std::size_t>(l)] += upTo - assigned;
    assigned = upTo;
  }
  return g;
}

} // namespace

Hierarchy GenerateCosmo(const CosmoParameters& p)
{
  const std::string what = "cosmo generator (" + FormatCosmoParameters(p) + "): ";
  if (p.Levels < 1 || p.Levels > 30)
  {
    throw std::invalid_argument(what + "levels must be between 1 and 30");
  }
  if (p.Grids < 1)
  {
    throw std::invalid_argument(what + "grids must be >= 1");
  }
  if (p.RootGrids < 0)
  {
    throw std::invalid_argument(what + "roots must be >= 0");
  }
  const int64_t roots = p.RootGrids > 0 ? p.RootGrids : (p.Levels == 1 ? p.Grids : 8);
  if (p.Levels == 1 && roots != p.Grids)
  {
    throw std::invalid_argument(
      what + "with levels=1 every grid is a root grid, so roots must equal grids");
  }
  if (p.Grids < roots + (p.Levels - 1))
  {
    throw std::invalid_argument(what + "grids must be at least the " + std::to_string(roots) +
      " root grids plus one grid per refined level (" + std::to_string(roots + p.Levels - 1) + ")");
  }
  constexpr int64_t minCellsPerGrid = 64;
  if (p.Cells / minCellsPerGrid < p.Grids)
  {
    throw std::invalid_argument(what + "cells too small for the grids: need at least " +
      std::to_string(minCellsPerGrid) +
      " cells per grid on average (cells >= " + std::to_string(minCellsPerGrid * p.Grids) + ")");
  }

  const std::vector<int64_t> refinedGrids = GridsPerRefinedLevel(p.Grids - roots, p.Levels);

  // Root edge N0: the cell budget model gives level 1 a tenth of the domain (8 * 0.1 * N0^3
  // cells) and every finer level the same mean cells per grid, so
  // Cells = N0^3 * (1 + 8 * 0.1 * sum_l G_l / G_1).
  double share = 1.0;
  for (std::size_t l = 0; l < refinedGrids.size(); ++l)
  {
    share += 8.0 * Level1VolumeFraction * static_cast<double>(refinedGrids[l]) /
      static_cast<double>(refinedGrids[0]);
  }
  const int64_t rootCellsWanted =
    std::max<int64_t>(1, static_cast<int64_t>(static_cast<double>(p.Cells) / share + 0.5));
  const int64_t n0 = NearestIntegerCubeRoot(rootCellsWanted);
  if (n0 * n0 * n0 < roots || (p.Levels > 1 && n0 < 2))
  {
    throw std::invalid_argument(what + "cells too small for " + std::to_string(roots) +
      " root grids (root domain would be " + std::to_string(n0) + "^3 cells)");
  }

  const CosmoField field(p.Seed);
  Hierarchy h;
  h.Origin = glm::dvec3(0.0);
  h.Spacing0 = glm::dvec3(1.0 / static_cast<double>(n0));
  h.RefinementRatio.assign(static_cast<std::size_t>(p.Levels), glm::ivec3(2));
  h.RefinementRatio[0] = glm::ivec3(1);
  h.ArrayName = "Density";
  h.VertexCentred = false;

  std::vector<Box> level;
  SplitDomain(Box{ glm::i64vec3(0), glm::i64vec3(n0) }, roots, level);
  int64_t levelCells = n0 * n0 * n0;
  int64_t remaining = p.Cells - levelCells;
  for (const Box& b : level)
  {
    h.Grids.push_back(Grid{ 0, b, static_cast<int64_t>(h.Grids.size()) });
  }

  LevelBuilder builder(field);
  double tileGuess = 0.6;
  double scale = static_cast<double>(n0); // cells of the current level per unit length
  for (int l = 1; l < p.Levels; ++l)
  {
    scale *= 2.0;
    const int64_t grids = refinedGrids[static_cast<std::size_t>(l - 1)];
    int64_t gridsLeft = 0;
    for (std::size_t j = static_cast<std::size_t>(l - 1); j < refinedGrids.size(); ++j)
    {
      gridsLeft += refinedGrids[j];
    }
    // This level's share of the remaining cell budget, capped by the room in the parents and
    // at least 8 cells per grid.
    double target =
      static_cast<double>(remaining) * static_cast<double>(grids) / static_cast<double>(gridsLeft);
    target = std::min(target, MaxVolumeFraction * 8.0 * static_cast<double>(levelCells));
    target = std::max(target, 8.0 * static_cast<double>(grids));
    const std::vector<LevelBox> boxes =
      BuildLevel(builder, level, 1.0 / scale, grids, static_cast<int64_t>(target + 0.5), tileGuess);
    if (boxes.empty())
    {
      throw std::invalid_argument(what + "no room for level " + std::to_string(l));
    }
    level.clear();
    for (const LevelBox& b : boxes)
    {
      level.push_back(b.Cells);
      h.Grids.push_back(Grid{ l, b.Cells, static_cast<int64_t>(h.Grids.size()) });
    }
    levelCells = CellsOf(boxes);
    remaining -= levelCells;
  }

  if (p.GenerateValues)
  {
    h.Values.resize(h.Grids.size());
    // Largest grids first for load balance; each grid is written by exactly one thread.
    std::vector<std::size_t> order(h.Grids.size());
    for (std::size_t i = 0; i < order.size(); ++i)
    {
      order[i] = i;
    }
    std::stable_sort(order.begin(), order.end(), [&h](std::size_t a, std::size_t b) {
      return h.Grids[a].Cells.Cells() > h.Grids[b].Cells.Cells();
    });
    std::atomic<std::size_t> next(0);
    const unsigned threads = WorkerCount();
    auto work = [&]() {
      for (;;)
      {
        const std::size_t i = next.fetch_add(1);
        if (i >= order.size())
        {
          return;
        }
        const std::size_t g = order[i];
        const Grid& grid = h.Grids[g];
        // Cell size of the grid's level in world units: Spacing0 / 2^level (exact scaling).
        const double cs = std::ldexp(h.Spacing0.x, -grid.Level);
        field.Sample(grid.Cells, cs, h.Values[g]);
      }
    };
    std::vector<std::thread> pool;
    for (unsigned t = 1; t < threads; ++t)
    {
      pool.emplace_back(work);
    }
    work();
    for (std::thread& th : pool)
    {
      th.join();
    }
  }
  return h;
}

CosmoStatistics ComputeCosmoStatistics(const Hierarchy& h)
{
  CosmoStatistics s;
  s.GridsPerLevel.assign(static_cast<std::size_t>(h.NumberOfLevels()), 0);
  s.CellsPerLevel.assign(static_cast<std::size_t>(h.NumberOfLevels()), 0);
  s.MinGridCells = h.Grids.empty() ? 0 : std::numeric_limits<int64_t>::max();
  for (const Grid& g : h.Grids)
  {
    const std::size_t l = static_cast<std::size_t>(g.Level);
    if (l >= s.GridsPerLevel.size())
    {
      s.GridsPerLevel.resize(l + 1, 0);
      s.CellsPerLevel.resize(l + 1, 0);
    }
    const int64_t c = g.Cells.Cells();
    ++s.GridsPerLevel[l];
    s.CellsPerLevel[l] += c;
    ++s.Grids;
    s.Cells += c;
    s.MinGridCells = std::min(s.MinGridCells, c);
    s.MaxGridCells = std::max(s.MaxGridCells, c);
  }
  return s;
}

} // namespace amrsp
