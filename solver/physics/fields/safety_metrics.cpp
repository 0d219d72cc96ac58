#include "physics/fields/safety_metrics.hpp"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "model/tet_geometry.hpp"

namespace needlefem::fields {

namespace {

constexpr int kVoxelsPerRadius = 4;         // lattice spacing s = ℓ/4
constexpr long long kKeyBias = 1LL << 20;   // lattice indices from -2^20 to 2^20
// The bisection for a percentile stops at this share of the field's range (far below the 9
// digits the history and summary print of it).
constexpr double kPercentileTolerance = 1e-11;
// A ball's bound must fall below the best average by this share of their magnitudes for the
// ball to be skipped: far above the rounding of either sum, far below any difference that counts.
constexpr double kBoundMargin = 1e-9;

bool selected(std::span<const char> mask, std::size_t q) { return mask.empty() || mask[q]; }

long long floor_div(long long a, long long b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

long long key_of(const std::array<long long, 3>& i) {
  return ((i[0] + kKeyBias) << 42) | ((i[1] + kKeyBias) << 21) | (i[2] + kKeyBias);
}

}  // namespace

BallAverager::BallAverager(std::span<const Point3> positions, std::span<const double> volumes,
                           std::span<const Tetrahedron> tissue, double radius_m)
    : radius_(radius_m), spacing_(radius_m / kVoxelsPerRadius) {
  static_assert(kBlock == kVoxelsPerRadius, "a block's edge must be the ball's radius");
  if (!(radius_ > 0.0)) throw std::invalid_argument("critical distance: the ball radius must be positive");
  if (positions.size() != volumes.size()) throw std::invalid_argument("critical distance: one volume per point is needed");
  // Points by block, then by voxel inside the block.
  std::unordered_map<long long, int> block_at;
  std::vector<std::vector<std::pair<int, int>>> members;  // per block: (local voxel, point)
  for (std::size_t q = 0; q < positions.size(); ++q) {
    const auto v = voxel_of(positions[q]);
    const std::array<long long, 3> b{floor_div(v[0], kBlock), floor_div(v[1], kBlock), floor_div(v[2], kBlock)};
    for (long long i : b)
      if (std::abs(i) >= kKeyBias) throw std::invalid_argument("critical distance: the ball radius is too small for the tissue's extent");
    const auto [it, inserted] = block_at.try_emplace(key_of(b), static_cast<int>(blocks_.size()));
    if (inserted) {
      blocks_.push_back({b, {}, {}, {}});
      members.emplace_back();
    }
    const int local = static_cast<int>(((v[0] - kBlock * b[0]) * kBlock + (v[1] - kBlock * b[1])) * kBlock +
                                       (v[2] - kBlock * b[2]));
    members[it->second].emplace_back(local, static_cast<int>(q));
  }
  point_of_slot_.reserve(positions.size());
  for (std::size_t b = 0; b < blocks_.size(); ++b) {
    Block& block = blocks_[b];
    std::stable_sort(members[b].begin(), members[b].end());
    block.first.fill(static_cast<int>(point_of_slot_.size()));
    for (const auto& [local, q] : members[b]) {
      point_of_slot_.push_back(q);
      ++block.first[local + 1];
    }
    for (int l = 0; l < kBlockVoxels; ++l) block.first[l + 1] += block.first[l] - block.first[0];
    std::uint64_t occupied = 0;
    for (int l = 0; l < kBlockVoxels; ++l)
      if (block.first[l + 1] > block.first[l]) occupied |= std::uint64_t{1} << l;
    occupied_.push_back(occupied);
    int n = 0;
    for (long long i = -1; i <= 1; ++i)
      for (long long j = -1; j <= 1; ++j)
        for (long long k = -1; k <= 1; ++k) {
          const auto found = block_at.find(key_of({block.index[0] + i, block.index[1] + j, block.index[2] + k}));
          block.neighbours[n++] = found == block_at.end() ? -1 : found->second;
        }
  }
  for (int q : point_of_slot_) {
    positions_.push_back(positions[q]);
    volumes_.push_back(volumes[q]);
  }
  mark_centres_in_tissue(tissue, block_at);
  plan_reach();
}

void BallAverager::plan_reach() {
  // In lattice units the ball around a voxel's centre has radius 4: a voxel at offset o is wholly
  // inside when its farthest corner is, outside when its nearest point is beyond 4.
  const double r2 = kVoxelsPerRadius * kVoxelsPerRadius;
  const auto split = [](int l) { return std::array<int, 3>{l / (kBlock * kBlock), (l / kBlock) % kBlock, l % kBlock}; };
  for (int centre = 0; centre < kBlockVoxels; ++centre) {
    const auto c = split(centre);
    int neighbour = 0;
    for (int bi = -1; bi <= 1; ++bi)
      for (int bj = -1; bj <= 1; ++bj)
        for (int bk = -1; bk <= 1; ++bk, ++neighbour)
          for (int l = 0; l < kBlockVoxels; ++l) {
            const auto v = split(l);
            const std::array<int, 3> offset{kBlock * bi + v[0] - c[0], kBlock * bj + v[1] - c[1], kBlock * bk + v[2] - c[2]};
            double near = 0.0, far = 0.0;
            for (int o : offset) {
              near += std::pow(std::max(0.0, std::abs(o) - 0.5), 2);
              far += std::pow(std::abs(o) + 0.5, 2);
            }
            Reach& reach = reach_[centre][neighbour];
            const std::uint64_t bit = std::uint64_t{1} << l;
            if (far <= r2)
              reach.inside |= bit;
            else if (near <= r2)
              reach.rim |= bit;
          }
  }
}

void BallAverager::mark_centres_in_tissue(std::span<const Tetrahedron> tissue,
                                          const std::unordered_map<long long, int>& block_at) {
  // Barycentric coordinates relative to the tetrahedron's size: a centre on a face shared by two
  // elements, or on the tissue's boundary, counts as inside.
  constexpr double kOnFace = 1e-10;
  long long last_key = -1;  // keys are non-negative
  int last_block = -1;
  for (const Tetrahedron& t : tissue) {
    const double volume = oriented_volume(t[0], t[1], t[2], t[3]);
    std::array<long long, 3> first, last;  // voxels whose centres (i + 1/2) s lie in the bounding box
    for (int c = 0; c < 3; ++c) {
      const auto [lo, hi] = std::minmax({t[0][c], t[1][c], t[2][c], t[3][c]});
      first[c] = static_cast<long long>(std::ceil(lo / spacing_ - 0.5));
      last[c] = static_cast<long long>(std::floor(hi / spacing_ - 0.5));
    }
    for (long long i = first[0]; i <= last[0]; ++i)
      for (long long j = first[1]; j <= last[1]; ++j)
        for (long long k = first[2]; k <= last[2]; ++k) {
          const std::array<long long, 3> b{floor_div(i, kBlock), floor_div(j, kBlock), floor_div(k, kBlock)};
          if (const long long key = key_of(b); key != last_key) {  // the block changes every kBlock voxels of k
            const auto found = block_at.find(key);
            last_key = key;
            last_block = found == block_at.end() ? -1 : found->second;
          }
          if (last_block < 0) continue;  // no tissue point within ℓ: no maximum there
          Block& block = blocks_[last_block];
          const int local = static_cast<int>(((i - kBlock * b[0]) * kBlock + (j - kBlock * b[1])) * kBlock + (k - kBlock * b[2]));
          const std::uint64_t bit = std::uint64_t{1} << local;
          if (block.centres_in_tissue & bit) continue;
          const Point3 x = centre_of({i, j, k});
          const double sub[4] = {oriented_volume(x, t[1], t[2], t[3]), oriented_volume(t[0], x, t[2], t[3]),
                                 oriented_volume(t[0], t[1], x, t[3]), oriented_volume(t[0], t[1], t[2], x)};
          if (std::all_of(std::begin(sub), std::end(sub), [&](double v) { return v / volume >= -kOnFace; }))
            block.centres_in_tissue |= bit;
        }
  }
}

std::array<long long, 3> BallAverager::voxel_of(const Point3& x) const {
  return {static_cast<long long>(std::floor(x[0] / spacing_)), static_cast<long long>(std::floor(x[1] / spacing_)),
          static_cast<long long>(std::floor(x[2] / spacing_))};
}

Point3 BallAverager::centre_of(const std::array<long long, 3>& voxel) const {
  return {(voxel[0] + 0.5) * spacing_, (voxel[1] + 0.5) * spacing_, (voxel[2] + 0.5) * spacing_};
}

BallAverager::Sums BallAverager::accumulate(std::span<const double> field) const {
  if (field.size() != point_of_slot_.size()) throw std::invalid_argument("critical distance: one value per point is needed");
  Sums sums;
  sums.field.resize(field.size());
  for (std::size_t p = 0; p < field.size(); ++p) sums.field[p] = field[point_of_slot_[p]];
  const std::size_t n = blocks_.size() * kBlockVoxels;
  sums.weighted.assign(n, 0.0);
  sums.volume.assign(n, 0.0);
  sums.largest.assign(n, -std::numeric_limits<double>::infinity());
  sums.smallest.assign(n, std::numeric_limits<double>::infinity());
  for (std::size_t b = 0; b < blocks_.size(); ++b)
    for (int l = 0; l < kBlockVoxels; ++l) {
      const std::size_t v = b * kBlockVoxels + l;
      for (int p = blocks_[b].first[l]; p < blocks_[b].first[l + 1]; ++p) {
        sums.weighted[v] += volumes_[p] * sums.field[p];
        sums.volume[v] += volumes_[p];
        sums.largest[v] = std::max(sums.largest[v], sums.field[p]);
        sums.smallest[v] = std::min(sums.smallest[v], sums.field[p]);
      }
    }
  return sums;
}

double BallAverager::average(const Sums& sums, int block, int voxel) const {
  const Block& centre_block = blocks_[block];
  const Point3 c = centre_of({kBlock * centre_block.index[0] + voxel / (kBlock * kBlock),
                              kBlock * centre_block.index[1] + (voxel / kBlock) % kBlock,
                              kBlock * centre_block.index[2] + voxel % kBlock});
  const double r2 = radius_ * radius_;
  double weighted = 0.0, volume = 0.0;
  for (int n = 0; n < 27; ++n) {
    const int nb = centre_block.neighbours[n];
    if (nb < 0) continue;
    const Reach& reach = reach_[voxel][n];
    // The reached voxels that hold points, in ascending order, whole or point by point.
    for (std::uint64_t bits = (reach.inside | reach.rim) & occupied_[nb]; bits != 0; bits &= bits - 1) {
      const int l = std::countr_zero(bits);
      if (reach.inside >> l & 1) {
        weighted += sums.weighted[std::size_t(nb) * kBlockVoxels + l];
        volume += sums.volume[std::size_t(nb) * kBlockVoxels + l];
        continue;
      }
      const Block& other = blocks_[nb];
      for (int p = other.first[l]; p < other.first[l + 1]; ++p) {
        const Point3& x = positions_[p];
        const double dx = x[0] - c[0], dy = x[1] - c[1], dz = x[2] - c[2];
        if (dx * dx + dy * dy + dz * dz > r2) continue;
        weighted += volumes_[p] * sums.field[p];
        volume += volumes_[p];
      }
    }
  }
  return volume > 0.0 ? weighted / volume : 0.0;
}

double BallAverager::average_bound(const Sums& sums, int block, int voxel) const {
  const Block& centre_block = blocks_[block];
  double inside_weighted = 0.0, inside_volume = 0.0;
  // Per rim voxel: its volume V, sum S = Σ w f, largest L and smallest m value. The ball holds a
  // part of volume v of it, whose sum is at most min(v L, S - (V - v) m): v* = (S - V m)/(L - m)
  // of it at L, the rest at m.
  struct RimVoxel {
    double volume, weighted, largest, smallest, top;
  };
  thread_local std::vector<RimVoxel> rim;
  rim.clear();
  for (int n = 0; n < 27; ++n) {
    const int nb = centre_block.neighbours[n];
    if (nb < 0) continue;
    const Reach& reach = reach_[voxel][n];
    const std::size_t base = std::size_t(nb) * kBlockVoxels;
    for (std::uint64_t bits = reach.inside & occupied_[nb]; bits != 0; bits &= bits - 1) {
      const int l = std::countr_zero(bits);
      inside_weighted += sums.weighted[base + l];
      inside_volume += sums.volume[base + l];
    }
    for (std::uint64_t bits = reach.rim & occupied_[nb]; bits != 0; bits &= bits - 1) {
      const std::size_t l = base + std::countr_zero(bits);
      const double V = sums.volume[l], S = sums.weighted[l], L = sums.largest[l], m = sums.smallest[l];
      const double top = L > m ? std::clamp((S - V * m) / (L - m), 0.0, V) : V;
      rim.push_back({V, S, L, m, top});
    }
  }
  // Dinkelbach: with λ the ratio so far, each rim voxel takes the part that gains most against λ
  // (none above L, its top part between m and L, all of it below m); λ rises to the maximum ratio.
  double ratio = -std::numeric_limits<double>::infinity();
  for (std::size_t iteration = 0; iteration <= 2 * rim.size() + 1; ++iteration) {
    double weighted = inside_weighted, volume = inside_volume;
    for (const RimVoxel& r : rim)
      if (r.smallest >= ratio) weighted += r.weighted, volume += r.volume;
      else if (r.largest > ratio) weighted += r.top * r.largest, volume += r.top;
    if (volume <= 0.0) return 0.0;  // average() of a ball without points
    const double next = weighted / volume;
    if (!(next > ratio)) break;
    ratio = next;
  }
  return ratio;
}

LocatedValue BallAverager::average_around(const Point3& x, std::span<const double> field) const {
  const auto v = voxel_of(x);
  const std::array<long long, 3> b{floor_div(v[0], kBlock), floor_div(v[1], kBlock), floor_div(v[2], kBlock)};
  for (std::size_t block = 0; block < blocks_.size(); ++block)
    if (blocks_[block].index == b) {
      const int local = static_cast<int>(((v[0] - kBlock * b[0]) * kBlock + (v[1] - kBlock * b[1])) * kBlock +
                                         (v[2] - kBlock * b[2]));
      return {average(accumulate(field), static_cast<int>(block), local), centre_of(v)};
    }
  throw std::invalid_argument("critical distance: no tissue point near the ball's centre");
}

LocatedValue BallAverager::maximum(std::span<const double> field) const {
  const Sums sums = accumulate(field);
  std::vector<double> block_largest(blocks_.size(), -std::numeric_limits<double>::infinity());
  for (std::size_t b = 0; b < blocks_.size(); ++b)
    for (int l = 0; l < kBlockVoxels; ++l) block_largest[b] = std::max(block_largest[b], sums.largest[b * kBlockVoxels + l]);
  struct Candidate {
    double bound;
    int block;
  };
  std::vector<Candidate> candidates;
  candidates.reserve(blocks_.size());
  for (std::size_t b = 0; b < blocks_.size(); ++b) {
    double bound = -std::numeric_limits<double>::infinity();
    for (int nb : blocks_[b].neighbours)
      if (nb >= 0) bound = std::max(bound, block_largest[nb]);
    candidates.push_back({bound, static_cast<int>(b)});
  }
  // Descending bound, equal bounds in lattice order. The threads take candidates in that order
  // and stop at the first that cannot beat the best average found so far; the block holding
  // the true maximum always has a bound at least that large, so it is always evaluated. Equal
  // averages go to the earliest (candidate, voxel): the answer depends neither on hashing nor on
  // threads.
  std::sort(candidates.begin(), candidates.end(), [&](const Candidate& a, const Candidate& b) {
    return a.bound > b.bound || (a.bound == b.bound && blocks_[a.block].index < blocks_[b.block].index);
  });
  constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
  double best = -std::numeric_limits<double>::infinity();
  std::size_t best_slot = kNone;  // candidate * kBlockVoxels + voxel
  const auto better = [](double value, std::size_t slot, double than, std::size_t than_slot) {
    return value > than || (value == than && slot < than_slot);
  };
  std::atomic<std::size_t> next{0};
#pragma omp parallel
  {
    for (std::size_t c = next++; c < candidates.size(); c = next++) {
      double shared_best;
      std::size_t shared_slot;
#pragma omp critical(needlefem_ball_maximum)
      shared_best = best, shared_slot = best_slot;
      // Below the best average, or equal to it after its candidate (whose voxels' slots come
      // first, and equal averages go to the earliest): so are all later candidates. Without the
      // second case a field constant over the tissue (every field at t = 0) had every centre
      // averaged.
      if (candidates[c].bound < shared_best ||
          (candidates[c].bound == shared_best && c * kBlockVoxels > shared_slot))
        break;
      const Block& block = blocks_[candidates[c].block];
      double block_best = -std::numeric_limits<double>::infinity();
      std::size_t block_slot = kNone;
      for (int l = 0; l < kBlockVoxels; ++l) {
        if (!(block.centres_in_tissue & (std::uint64_t{1} << l))) continue;
        // A centre whose bound is below the best average found cannot beat it, nor tie it: the
        // margin covers the bound's and the average's different rounding.
        double known_best;
#pragma omp atomic read
        known_best = best;
        known_best = std::max(known_best, block_best);
        const double bound = average_bound(sums, candidates[c].block, l);
        if (bound + kBoundMargin * (std::abs(bound) + std::abs(known_best)) < known_best) continue;
        const double value = average(sums, candidates[c].block, l);
        if (better(value, c * kBlockVoxels + l, block_best, block_slot)) {
          block_best = value;
          block_slot = c * kBlockVoxels + l;
        }
      }
#pragma omp critical(needlefem_ball_maximum)
      if (better(block_best, block_slot, best, best_slot)) {
        best = block_best;
        best_slot = block_slot;
      }
    }
  }
  if (best_slot == kNone) throw std::invalid_argument("critical distance: no ball centre in the tissue");
  const Block& block = blocks_[candidates[best_slot / kBlockVoxels].block];
  const int l = static_cast<int>(best_slot % kBlockVoxels);
  return {best, centre_of({kBlock * block.index[0] + l / (kBlock * kBlock), kBlock * block.index[1] + (l / kBlock) % kBlock,
                           kBlock * block.index[2] + l % kBlock})};
}

TetrahedronPart part_above(const std::array<double, 4>& vertex_value, double limit) {
  using Bary = std::array<double, 4>;
  const auto vertex = [](int i) {
    Bary e{};
    e[i] = 1.0;
    return e;
  };
  // The point of edge (i, j), i above and j not, where the field equals the limit.
  const auto crossing = [&](int i, int j) {
    const double s = (vertex_value[i] - limit) / (vertex_value[i] - vertex_value[j]);
    Bary x = vertex(i);
    x[i] -= s;
    x[j] += s;
    return x;
  };
  // A tetrahedron of barycentric points, added to `part` by its volume share and centroid.
  const auto add = [](TetrahedronPart& part, const Bary& a, const Bary& b, const Bary& c, const Bary& d) {
    double m[3][3];
    for (int r = 0; r < 3; ++r) {
      m[0][r] = b[r + 1] - a[r + 1];
      m[1][r] = c[r + 1] - a[r + 1];
      m[2][r] = d[r + 1] - a[r + 1];
    }
    const double share = std::abs(m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                                  m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                                  m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]));
    for (int i = 0; i < 4; ++i) part.centroid[i] += share * (a[i] + b[i] + c[i] + d[i]) / 4.0;
    part.fraction += share;
  };
  std::array<int, 4> above{}, below{};
  int n_above = 0, n_below = 0;
  for (int i = 0; i < 4; ++i) (vertex_value[i] > limit ? above[n_above++] : below[n_below++]) = i;
  TetrahedronPart part;
  if (n_above == 0) return part;
  if (n_above == 4) return {1.0, {0.25, 0.25, 0.25, 0.25}};
  if (n_above == 1) {
    const int a = above[0];
    add(part, vertex(a), crossing(a, below[0]), crossing(a, below[1]), crossing(a, below[2]));
  } else if (n_above == 2) {
    // A prism: triangle (a, ac, ad) on face acd, triangle (b, bc, bd) on face bcd, in three
    // tetrahedra that split its quadrilateral faces consistently.
    const int a = above[0], b = above[1], c = below[0], d = below[1];
    const Bary p0 = vertex(a), p1 = crossing(a, c), p2 = crossing(a, d), p3 = vertex(b), p4 = crossing(b, c),
               p5 = crossing(b, d);
    add(part, p0, p1, p2, p3);
    add(part, p1, p2, p3, p4);
    add(part, p2, p3, p4, p5);
  } else {
    // The whole tetrahedron less the corner at the one vertex not above.
    const int d = below[0];
    TetrahedronPart corner;
    add(corner, vertex(d), crossing(above[0], d), crossing(above[1], d), crossing(above[2], d));
    part.fraction = 1.0 - corner.fraction;
    for (int i = 0; i < 4; ++i) part.centroid[i] = 0.25 - corner.centroid[i];
  }
  if (part.fraction > 0.0)
    for (double& x : part.centroid) x /= part.fraction;
  return part;
}

TissueElements::TissueElements(std::span<const Tetrahedron> tetrahedra,
                               std::span<const std::array<double, 4>> point_barycentric)
    : tetrahedra_(tetrahedra), points_(point_barycentric.size()) {
  if (points_ != 1 && points_ != 4) throw std::invalid_argument("volume above a level: elements have 1 or 4 points");
  if (points_ == 1) return;
  std::array<std::array<double, 8>, 4> m{};  // [Λ | I], reduced to [I | Λ⁻¹]
  for (int q = 0; q < 4; ++q) {
    for (int i = 0; i < 4; ++i) m[q][i] = point_barycentric[q][i];
    m[q][4 + q] = 1.0;
  }
  for (int col = 0; col < 4; ++col) {
    int pivot = col;
    for (int r = col + 1; r < 4; ++r)
      if (std::abs(m[r][col]) > std::abs(m[pivot][col])) pivot = r;
    if (!(std::abs(m[pivot][col]) > 1e-12))
      throw std::invalid_argument("volume above a level: the element points do not determine a linear field");
    std::swap(m[col], m[pivot]);
    const double diagonal = m[col][col];
    for (double& x : m[col]) x /= diagonal;
    for (int r = 0; r < 4; ++r)
      if (r != col) {
        const double factor = m[r][col];
        for (int k = 0; k < 8; ++k) m[r][k] -= factor * m[col][k];
      }
  }
  for (int i = 0; i < 4; ++i)
    for (int q = 0; q < 4; ++q) vertex_from_points_[i][q] = m[i][4 + q];
}

std::vector<double> TissueElements::selected_volumes(std::span<const double> point_volumes,
                                                     std::span<const char> mask) const {
  if (point_volumes.size() != points_ * tetrahedra_.size())
    throw std::invalid_argument("volume above a level: one volume per element point is needed");
  std::vector<double> out(tetrahedra_.size(), 0.0);
  for (std::size_t k = 0; k < tetrahedra_.size(); ++k)
    for (std::size_t q = k * points_; q < (k + 1) * points_; ++q)
      if (selected(mask, q)) out[k] += point_volumes[q];
  return out;
}

std::vector<std::array<double, 4>> TissueElements::vertex_values(std::span<const double> field) const {
  if (field.size() != points_ * tetrahedra_.size())
    throw std::invalid_argument("volume above a level: one value per element point is needed");
  std::vector<std::array<double, 4>> out(tetrahedra_.size());
  for (std::size_t k = 0; k < tetrahedra_.size(); ++k) {
    const std::size_t first = k * points_;
    std::array<double, 4>& c = out[k];
    if (points_ == 1) {
      c.fill(field[first]);
      continue;
    }
    for (int i = 0; i < 4; ++i)
      for (int q = 0; q < 4; ++q) c[i] += vertex_from_points_[i][q] * field[first + q];
  }
  return out;
}

VolumeAbove volume_above(const TissueElements& elements, std::span<const std::array<double, 4>> vertex_values,
                         std::span<const double> element_volumes, double limit) {
  VolumeAbove out;
  for (std::size_t k = 0; k < vertex_values.size(); ++k) {
    const std::array<double, 4>& c = vertex_values[k];
    if (element_volumes[k] == 0.0 || !(std::max({c[0], c[1], c[2], c[3]}) > limit)) continue;
    const TetrahedronPart part = part_above(c, limit);
    const double v = part.fraction * element_volumes[k];
    const Tetrahedron& t = elements.tetrahedra()[k];
    out.volume += v;
    for (int i = 0; i < 4; ++i)
      for (int d = 0; d < 3; ++d) out.centroid[d] += v * part.centroid[i] * t[i][d];
  }
  if (out.volume > 0.0)
    for (double& x : out.centroid) x /= out.volume;
  return out;
}

double volume_percentile(std::span<const std::array<double, 4>> vertex_values, std::span<const double> element_volumes,
                         double percent) {
  if (!(percent > 0.0 && percent < 100.0)) throw std::invalid_argument("percentile: must lie in (0, 100)");
  // The counted elements with their lowest and highest vertex values.
  struct Candidate {
    std::size_t element;
    double low, high;
  };
  std::vector<Candidate> straddling;
  double region = 0.0, lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::size_t k = 0; k < vertex_values.size(); ++k) {
    if (element_volumes[k] == 0.0) continue;
    const std::array<double, 4>& c = vertex_values[k];
    const auto [low, high] = std::minmax({c[0], c[1], c[2], c[3]});
    straddling.push_back({k, low, high});
    region += element_volumes[k];
    lo = std::min(lo, low);
    hi = std::max(hi, high);
  }
  if (straddling.empty()) return 0.0;
  // V(v), the volume above v, falls from the region's at v < lo to 0 at hi. Bisect for the
  // smallest v with V(v) <= the hottest share, keeping V(lo) > share >= V(hi): an element whose
  // lowest vertex value is above hi counts whole at every v of the bracket, one whose highest is
  // at most lo not at all, so each narrowing keeps only the elements that straddle the bracket.
  const double hottest = (1.0 - percent / 100.0) * region;
  if (!(lo < hi)) return hi;  // a constant field
  const double tolerance = kPercentileTolerance * (hi - lo);
  lo -= tolerance;
  double whole = 0.0;  // of the elements above the whole bracket
  while (hi - lo > tolerance) {
    const double mid = lo + (hi - lo) / 2;
    if (!(mid > lo && mid < hi)) break;  // a range of a few ulps: no double lies between
    double above = whole;
    for (const Candidate& e : straddling)
      above += element_volumes[e.element] * part_above(vertex_values[e.element], mid).fraction;
    (above > hottest ? lo : hi) = mid;
    std::erase_if(straddling, [&](const Candidate& e) {
      if (e.low > hi) whole += element_volumes[e.element];
      return e.low > hi || e.high <= lo;
    });
  }
  return hi;
}

}  // namespace needlefem::fields
