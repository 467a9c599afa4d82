// SPDX-License-Identifier: BSD-3-Clause
// The synthetic cosmology's density field: halos placed by a portable random-number generator.
#include "amrsp/SyntheticCosmo.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

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
/// A power-law radius in [rmin, rmax] with dN/dR ~ R^-3 (inverse transform; sqrt only).
double PowerLawRadius(SplitMix64& rng, double rmin, double rmax)
{
  const double a = 1.0 / (rmin * rmin);
  const double b = 1.0 / (rmax * rmax);
  return 1.0 / std::sqrt(a - rng.Uniform() * (a - b));
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
    auto slabDistance2 = [](double c, int i)
    {
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
    auto forEachBucket = [&slabDistance2](const Halo& h, auto&& f)
    {
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
  explicit Impl(uint64_t seed, double time)
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
    auto addHalo = [this, &rng, epsBase](const glm::dvec3& centre, double r)
    {
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
    if (time != 0.0)
    {
      this->Drift(seed, time);
    }
    this->BuildBuckets();
  }

  /// Moves every halo by `time` times its velocity: a direction uniform on the sphere and a
  /// speed uniform in [0, HaloSpeed], from a stream of its own.
  void Drift(uint64_t seed, double time)
  {
    SplitMix64 rng(seed ^ 0x2545F4914F6CDD1DULL);
    for (Halo& h : this->Halos)
    {
      glm::dvec3 d;
      double n2 = 0.0;
      do
      {
        d = rng.UniformVector(-1.0, 1.0);
        n2 = d.x * d.x + d.y * d.y + d.z * d.z;
      } while (n2 > 1.0 || n2 < 1e-6);
      const double speed = rng.Uniform(0.0, CosmoField::HaloSpeed) / std::sqrt(n2);
      h.Cx += time * speed * d.x;
      h.Cy += time * speed * d.y;
      h.Cz += time * speed * d.z;
    }
  }
};

CosmoField::CosmoField(uint64_t seed, double time)
  : Internals(std::make_shared<const Impl>(seed, time))
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

} // namespace amrsp
