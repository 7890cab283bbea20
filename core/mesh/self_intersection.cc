#include "core/mesh/self_intersection.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <utility>

#include "core/base/parallel_tasks.h"
#include "core/engine/arena_allocator.h"
#include "core/mesh/triangle_intersection.h"

namespace membrane {
namespace {

// Whether any of flags[begin, end) is set, eight flags a read: the searches near moved faces
// read a flag per face of the whole mesh each time (15M at 10M points), and few are set.
bool AnyFlagged(const char* flags, int64_t begin, int64_t end) {
  int64_t f = begin;
  for (; f + 8 <= end; f += 8) {
    uint64_t word;
    std::memcpy(&word, flags + f, sizeof word);
    if (word != 0) return true;
  }
  for (; f < end; ++f)
    if (flags[f]) return true;
  return false;
}

// The indices f < count with flags[f] set, in increasing order, read as AnyFlagged reads them.
std::vector<int32_t> FlaggedIndices(const char* flags, int32_t count) {
  std::vector<int32_t> out;
  int32_t f = 0;
  for (; f + 8 <= count; f += 8) {
    if (!AnyFlagged(flags, f, f + 8)) continue;
    for (int32_t k = f; k < f + 8; ++k)
      if (flags[k]) out.push_back(k);
  }
  for (; f < count; ++f)
    if (flags[f]) out.push_back(f);
  return out;
}

// The search's big arrays, fresh on every call: plain pages (docs/engine-decisions.md "Plain
// pages for big arrays"). Sized without being filled: every element is written before it is
// read, so a value-initializing fill (a memset of tens of MB on a full search) would be one
// more pass over memory that the search writes anyway.
template <typename T>
using BigVector = std::vector<T, UnfilledAllocator<T>>;

using Box = FaceBlockBoxes::Box;

bool ValidFace(const std::array<int32_t, 3>& f, int64_t nv) {
  for (int32_t i : f)
    if (i < 0 || i >= nv) return false;
  return true;
}

// The faces taking part in a search, with everything indexed by position in `face`.
struct Participants {
  BigVector<int32_t> face;
  BigVector<Box> box;
  BigVector<char> dirty;  // empty: every pair counts
};

using CellCoord = std::array<int64_t, 3>;


// std::floor for the cell indices, inline: the library call would be a tenth of building the cells.
// Exact for |v| < 2^62, far beyond any cell index here (at most 2^20 cells per axis).
int64_t Floor(double v) {
  const int64_t t = static_cast<int64_t>(v);
  return t - (static_cast<double>(t) > v);
}

// A uniform grid of cells of side about one face, stored sparsely: one (cell key, lowest-cell
// bits, position) entry per cell a face's box touches, packed in a uint64 and sorted by the
// key (Sort). The lowest-cell bits (see SearchPairs) are known as the entry is made, so the pair
// search reads them instead of finding the cell of each member's low corner again. Memory
// follows the number of entries, not the box volume, and walking the sorted entries visits
// neighbouring cells one after the other, which keeps the faces' data in cache.
class SortedFaceCells {
 public:
  // The entries are made and sorted in blocks of boxes on `threads`; the sort is stable, so
  // the entries' order does not depend on the count.
  SortedFaceCells(const BigVector<Box>& boxes, int threads) {
    Box all = boxes[0];
    double extent_sum = 0;
    for (const Box& b : boxes) {
      double e = 0;
      for (int k = 0; k < 3; ++k) {
        all.lo[k] = std::min(all.lo[k], b.lo[k]);
        all.hi[k] = std::max(all.hi[k], b.hi[k]);
        e = std::max(e, static_cast<double>(b.hi[k]) - b.lo[k]);
      }
      extent_sum += e;
    }
    double diag = 0;
    for (int k = 0; k < 3; ++k) {
      lo_[k] = all.lo[k];
      diag = std::max(diag, static_cast<double>(all.hi[k]) - all.lo[k]);
    }
    // Cells twice the mean face extent (fewer entries per face for a few more pairs per cell:
    // 1.5 times was 10-45% slower, 2.5 to 4 times within the noise); coarser when the entry
    // count would not stay linear in the face count (a few huge faces) or the cell key, the
    // lowest-cell bits and the position would not fit in 64 bits together.
    pos_bits_ = std::bit_width(static_cast<uint64_t>(boxes.size()));
    SetCell(std::max({2.0 * extent_sum / boxes.size(), diag / ((1 << 20) - 2), 1e-30}));
    const double max_entries = 16.0 * boxes.size() + 64;
    std::vector<int64_t> counts;  // entries per block of boxes
    for (;;) {
      key_bits_ = 0;
      for (int k = 0; k < 3; ++k) {
        dims_[k] = Cell(all.hi[k], k) + 1;
        key_bits_ += std::bit_width(static_cast<uint64_t>(dims_[k] - 1));
      }
      if (key_bits_ + pos_bits_ + kLowBits > 64) {
        SetCell(cell_ * 2);
        continue;
      }
      counts = CountEntries(boxes, threads, max_entries);
      double entries = 0;
      for (int64_t count : counts) entries += static_cast<double>(count);
      if (entries <= max_entries) break;
      SetCell(cell_ * 1.5);
    }
    MakeSpreads();
    double total = 0;
    for (int64_t count : counts) total += static_cast<double>(count);
    Sort(boxes, static_cast<size_t>(total), threads);
  }

  // A product by the inverse, not a quotient: any rounding that is monotone in `v` keeps every
  // pair of overlapping boxes in a common cell, and a product is several times cheaper.
  int64_t Cell(float v, int axis) const { return Floor((v - lo_[axis]) * inverse_cell_); }
  CellCoord CellOf(const std::array<float, 3>& p) const {
    return {Cell(p[0], 0), Cell(p[1], 1), Cell(p[2], 2)};
  }
  size_t size() const { return entries_.size(); }
  uint64_t key(size_t e) const { return entries_[e] >> (pos_bits_ + kLowBits); }
  // Bit k set when the entry's face has its lowest cell (the cell of its box's low corner) at
  // this entry's cell's coordinate k.
  uint8_t at_low(size_t e) const { return static_cast<uint8_t>(entries_[e] >> pos_bits_ & 7); }
  int32_t position(size_t e) const {
    return static_cast<int32_t>(entries_[e] & ((uint64_t{1} << pos_bits_) - 1));
  }

 private:
  static constexpr size_t kBoxesPerBlock = 16384;
  static constexpr int kLowBits = 3;
  static constexpr int kMaxTopBits = 12;  // 4096 buckets: as many write streams as L2 holds

  // The cell keys are Morton codes (the coordinates' bits interleaved, an axis's bits left out
  // above its width): the cells are walked in the Z order the faces are stored in
  // (MortonOrder), so a face's box, indices and positions are read again from cache in its
  // next cell, not from memory after a whole slab of cells (x-major keys: the 1M torus's
  // search 20% slower). spread_[k][c]: coordinate c's bits at axis k's places.
  void MakeSpreads() {
    int width[3];
    for (int k = 0; k < 3; ++k) width[k] = std::bit_width(static_cast<uint64_t>(dims_[k] - 1));
    std::array<std::vector<uint64_t>, 3> place;  // place[k][i]: the key bit of bit i of axis k
    int next = 0;
    for (int i = 0; i < std::max({width[0], width[1], width[2]}); ++i)
      for (int k = 0; k < 3; ++k)
        if (i < width[k]) place[k].push_back(uint64_t{1} << next++);
    for (int k = 0; k < 3; ++k) {
      spread_[k].resize(dims_[k]);
      for (int64_t c = 0; c < dims_[k]; ++c) {
        uint64_t key = 0;
        for (int i = 0; i < width[k]; ++i)
          if (c >> i & 1) key |= place[k][i];
        spread_[k][c] = key;
      }
    }
  }

  void SetCell(double cell) {
    cell_ = cell;
    inverse_cell_ = 1 / cell;
  }

  // The entries of each block of kBoxesPerBlock boxes at the current cell size; a block stops
  // counting past `limit` (the caller then coarsens the cells anyway).
  std::vector<int64_t> CountEntries(const BigVector<Box>& boxes, int threads,
                                    double limit) const {
    std::vector<int64_t> counts((boxes.size() + kBoxesPerBlock - 1) / kBoxesPerBlock, 0);
    RunTasks(threads, static_cast<int64_t>(counts.size()), [&](int, int64_t block) {
      const size_t end = std::min(boxes.size(), static_cast<size_t>(block + 1) * kBoxesPerBlock);
      int64_t n = 0;
      for (size_t p = static_cast<size_t>(block) * kBoxesPerBlock; p < end; ++p) {
        int64_t cells = 1;
        for (int k = 0; k < 3; ++k) cells *= Cell(boxes[p].hi[k], k) - Cell(boxes[p].lo[k], k) + 1;
        n += cells;
        if (static_cast<double>(n) > limit) break;
      }
      counts[block] = n;
    });
    return counts;
  }

  // Calls visit(entry) for each of box p's entries, x fastest.
  template <typename Visit>
  void ForEachEntry(const Box& box, uint64_t p, Visit&& visit) const {
    const CellCoord lo = CellOf(box.lo), hi = CellOf(box.hi);
    for (int64_t z = lo[2]; z <= hi[2]; ++z)
      for (int64_t y = lo[1]; y <= hi[1]; ++y)
        for (int64_t x = lo[0]; x <= hi[0]; ++x) {
          const uint64_t key = spread_[0][x] | spread_[1][y] | spread_[2][z];
          const uint64_t at_low =
              (x == lo[0] ? 1 : 0) | (y == lo[1] ? 2 : 0) | (z == lo[2] ? 4 : 0);
          visit(key << (pos_bits_ + kLowBits) | at_low << pos_bits_ | p);
        }
  }

  // Makes the `total` entries sorted by key, each key's entries by increasing position, in
  // one array: a most-significant-digit split as they are made, then each bucket sorted on its
  // own. Chunks of boxes (several per thread) count their entries per bucket (the key's top
  // bits), then write them from their own offsets (bucket first, chunk second): each bucket
  // holds its entries in position order, as one loop would write them. A bucket (a few hundred
  // entries, a Z-order block of cells) is then sorted by the rest of its key, stably, in
  // cache. Against a least-significant-digit sort of the whole array, no second array of the
  // entries (8 bytes an entry, 2.6 entries a face: each page a fresh page fault) and one
  // pass over memory instead of two or three.
  void Sort(const BigVector<Box>& boxes, size_t total, int threads) {
    constexpr size_t kMinChunk = size_t{1} << 14;
    constexpr size_t kEntriesPerBucket = 256;
    const int top_bits = std::min(
        {key_bits_, kMaxTopBits, static_cast<int>(std::bit_width(total / kEntriesPerBucket))});
    const int top_shift = pos_bits_ + kLowBits + key_bits_ - top_bits;
    const size_t buckets = size_t{1} << top_bits;
    const size_t chunks = threads <= 1 ? 1
                                       : std::clamp<size_t>(boxes.size() / kMinChunk, 1,
                                                            4 * static_cast<size_t>(threads));
    auto chunk_begin = [&](size_t c) { return boxes.size() * c / chunks; };
    std::vector<std::vector<size_t>> at(chunks, std::vector<size_t>(buckets, 0));
    RunTasks(threads, static_cast<int64_t>(chunks), [&](int, int64_t c) {
      std::vector<size_t>& count = at[c];
      for (size_t p = chunk_begin(c); p < chunk_begin(c + 1); ++p)
        ForEachEntry(boxes[p], p, [&](uint64_t v) { ++count[v >> top_shift]; });
    });
    std::vector<size_t> bucket_start(buckets + 1);
    size_t start = 0;
    for (size_t b = 0; b < buckets; ++b) {
      bucket_start[b] = start;
      for (size_t c = 0; c < chunks; ++c) {
        const size_t count = at[c][b];
        at[c][b] = start;
        start += count;
      }
    }
    bucket_start[buckets] = start;
    entries_.resize(start);
    RunTasks(threads, static_cast<int64_t>(chunks), [&](int, int64_t c) {
      std::vector<size_t>& next = at[c];
      for (size_t p = chunk_begin(c); p < chunk_begin(c + 1); ++p)
        ForEachEntry(boxes[p], p, [&](uint64_t v) { entries_[next[v >> top_shift]++] = v; });
    });
    SortBuckets(bucket_start, key_bits_ - top_bits, threads);
  }

  // Sorts each bucket [start[b], start[b + 1]) of the entries by the low `key_bits` bits of
  // their key, stably: least-significant digit first, at most 8 bits a pass, through a
  // bucket-sized buffer per worker; insertion for the smallest.
  void SortBuckets(const std::vector<size_t>& start, int key_bits, int threads) {
    if (key_bits == 0) return;
    constexpr int kMaxBits = 8;
    constexpr size_t kInsertion = 16;
    constexpr int64_t kBucketsPerTask = 64;
    const int passes = (key_bits + kMaxBits - 1) / kMaxBits;
    const int bits = (key_bits + passes - 1) / passes;
    const uint64_t mask = (uint64_t{1} << bits) - 1;
    const int key_shift = pos_bits_ + kLowBits;
    const uint64_t key_mask = (uint64_t{1} << key_bits) - 1;
    const int64_t buckets = static_cast<int64_t>(start.size()) - 1;
    std::vector<std::vector<uint64_t>> other(std::max(threads, 1));
    const int64_t tasks = (buckets + kBucketsPerTask - 1) / kBucketsPerTask;
    RunTasks(threads, tasks, [&](int worker, int64_t task) {
      std::vector<uint64_t>& buffer = other[worker];
      std::array<size_t, (1 << kMaxBits)> at;
      const int64_t last = std::min(buckets, (task + 1) * kBucketsPerTask);
      for (int64_t b = task * kBucketsPerTask; b < last; ++b) {
        uint64_t* const first = entries_.data() + start[b];
        const size_t n = start[b + 1] - start[b];
        if (n <= kInsertion) {
          for (size_t i = 1; i < n; ++i) {
            const uint64_t v = first[i];
            const uint64_t key = v >> key_shift & key_mask;
            size_t j = i;
            for (; j > 0 && (first[j - 1] >> key_shift & key_mask) > key; --j)
              first[j] = first[j - 1];
            first[j] = v;
          }
          continue;
        }
        if (buffer.size() < n) buffer.resize(n);
        uint64_t* from = first;
        uint64_t* to = buffer.data();
        for (int pass = 0; pass < passes; ++pass) {
          const int shift = key_shift + pass * bits;
          std::fill(at.begin(), at.begin() + mask + 1, 0);
          for (size_t i = 0; i < n; ++i) ++at[from[i] >> shift & mask];
          size_t sum = 0;
          for (size_t d = 0; d <= mask; ++d) {
            const size_t count = at[d];
            at[d] = sum;
            sum += count;
          }
          for (size_t i = 0; i < n; ++i) to[at[from[i] >> shift & mask]++] = from[i];
          std::swap(from, to);
        }
        if (from != first) std::copy(from, from + n, first);
      }
    });
  }

  std::array<double, 3> lo_{0, 0, 0};
  double cell_ = 1;
  double inverse_cell_ = 1;
  std::array<int64_t, 3> dims_{1, 1, 1};
  int pos_bits_ = 1;
  int key_bits_ = 0;  // the cell keys are below 2^key_bits_
  std::array<std::vector<uint64_t>, 3> spread_;
  BigVector<uint64_t> entries_;
};

// A cell's member as the pair filter reads it: its face's box and a flags byte (SearchPairs).
struct Filtered {
  Box box;
  uint8_t flags;
};

// Whether the pair filter passes a and b: their flags or'ed are 15 (the pair counts, and this
// is the lowest cell their boxes share) and their boxes overlap. BoxesOverlap's comparisons,
// with & for && (every one evaluated, no branch).
inline bool Passes(const Filtered& a, const Filtered& f) {
  return ((a.flags | f.flags) == 15) & !(a.box.hi[0] < f.box.lo[0]) &
         !(f.box.hi[0] < a.box.lo[0]) & !(a.box.hi[1] < f.box.lo[1]) &
         !(f.box.hi[1] < a.box.lo[1]) & !(a.box.hi[2] < f.box.lo[2]) &
         !(f.box.hi[2] < a.box.lo[2]);
}

// A cell with more members than this has its pairs found by WalkCrowdedCell, not by trying
// each pair.
constexpr size_t kCrowdedCell = 512;

// A box's largest side.
float Extent(const Box& b) {
  return std::max({b.hi[0] - b.lo[0], b.hi[1] - b.lo[1], b.hi[2] - b.lo[2]});
}

struct CrowdedScratch {
  std::vector<float> extent, sorted;
  std::vector<int8_t> level;      // a member's width class; -1: wider than every class
  std::vector<uint32_t> huge;
  std::vector<uint64_t> entries;  // (sub-cell key, guest bit, lowest-sub-cell bits, member)
};

// The width classes of a crowded cell: class 0 holds the members no wider than twice the
// cell's median width, class j + 1 those no wider than twice the median of the ones left.
constexpr int kCrowdedClasses = 6;
// Classes are made while at least this many members are left; the members left after them
// are tried against every member.
constexpr size_t kCrowdedMinClass = 64;

// The pairs of a crowded cell's m members that pass the filter (Passes), each once, handed to
// test(a, n) as SearchPairs' loop hands them: member a and the n members written to `passed`.
// A cell fills up where the faces are much smaller than the mean that sized the cells (a cap
// folded into a patch a few hundredths of a voxel wide: 28,000 faces in one cell) or where
// many huge faces (a cap's, stretched over a hole) lie among small ones; trying every pair
// there costs m^2 / 2 (1e9 pairs a search in the caps' back-off of a 3M-point scan). Here the
// members are split into width classes; class j's members (the owners) go to sub-cells of
// its width together with the narrower classes' (the guests), each member spanning at most
// two a side, and each owner is tried against the owners after it and every guest of its
// sub-cell, a pair only in the lowest sub-cell the two share (as the cells do). A pair is
// tried in its wider member's class. The few members wider than every class are tried
// against every member.
template <typename Test>
void WalkCrowdedCell(const Filtered* members, size_t m, CrowdedScratch& s, uint32_t* passed,
                     Test&& test) {
  s.extent.resize(m);
  for (size_t i = 0; i < m; ++i) s.extent[i] = Extent(members[i].box);
  s.level.assign(m, -1);
  std::array<double, kCrowdedClasses> side{};
  int classes = 0;
  s.sorted.assign(s.extent.begin(), s.extent.end());
  while (classes < kCrowdedClasses && s.sorted.size() >= kCrowdedMinClass) {
    const size_t middle = s.sorted.size() / 2;
    std::nth_element(s.sorted.begin(), s.sorted.begin() + middle, s.sorted.end());
    const double width = 2.0 * s.sorted[middle];
    if (!(width >= 0)) break;  // NaN widths: no class
    side[classes] = width;
    std::erase_if(s.sorted, [&](float e) { return e <= width; });
    ++classes;
  }
  s.huge.clear();
  for (size_t i = 0; i < m; ++i) {
    int j = 0;
    while (j < classes && !(s.extent[i] <= side[j])) ++j;
    if (j < classes) {
      s.level[i] = static_cast<int8_t>(j);
    } else {
      s.huge.push_back(static_cast<uint32_t>(i));
    }
  }
  // The widest: against every member of a class, and against the widest after them.
  for (size_t h = 0; h < s.huge.size(); ++h) {
    const uint32_t a = s.huge[h];
    size_t n = 0;
    for (size_t b = 0; b < m; ++b) {
      passed[n] = static_cast<uint32_t>(b);
      n += (s.level[b] >= 0) & Passes(members[a], members[b]);
    }
    for (size_t k = h + 1; k < s.huge.size(); ++k) {
      passed[n] = s.huge[k];
      n += Passes(members[a], members[s.huge[k]]);
    }
    test(a, n);
  }
  constexpr int kKeyShift = 36, kGuestShift = 35;
  for (int j = 0; j < classes; ++j) {
    Box region{};
    bool any = false;
    for (size_t i = 0; i < m; ++i) {
      if (s.level[i] < 0 || s.level[i] > j) continue;
      const Box& b = members[i].box;
      if (!any) region = b;
      any = true;
      for (int k = 0; k < 3; ++k) {
        region.lo[k] = std::min(region.lo[k], b.lo[k]);
        region.hi[k] = std::max(region.hi[k], b.hi[k]);
      }
    }
    // Sub-cells no narrower than 1/512 of the region (keys below 2^28; faces of no width at
    // one point share one sub-cell, their pairs all tried).
    const double width = std::max(side[j], static_cast<double>(Extent(region)) / 512);
    std::array<int64_t, 3> dims{1, 1, 1};
    if (width > 0)
      for (int k = 0; k < 3; ++k)
        dims[k] = static_cast<int64_t>((region.hi[k] - region.lo[k]) / width) + 1;
    auto sub = [&](float v, int k) {
      if (!(width > 0)) return int64_t{0};
      return std::clamp<int64_t>(static_cast<int64_t>((v - region.lo[k]) / width), 0,
                                 dims[k] - 1);
    };
    s.entries.clear();
    for (size_t i = 0; i < m; ++i) {
      if (s.level[i] < 0 || s.level[i] > j) continue;
      const uint64_t guest = s.level[i] < j ? 1 : 0;
      const Box& b = members[i].box;
      const std::array<int64_t, 3> lo{sub(b.lo[0], 0), sub(b.lo[1], 1), sub(b.lo[2], 2)};
      const std::array<int64_t, 3> hi{sub(b.hi[0], 0), sub(b.hi[1], 1), sub(b.hi[2], 2)};
      for (int64_t z = lo[2]; z <= hi[2]; ++z)
        for (int64_t y = lo[1]; y <= hi[1]; ++y)
          for (int64_t x = lo[0]; x <= hi[0]; ++x) {
            const uint64_t key = static_cast<uint64_t>(x + dims[0] * (y + dims[1] * z));
            const uint64_t low =
                (x == lo[0] ? 1 : 0) | (y == lo[1] ? 2 : 0) | (z == lo[2] ? 4 : 0);
            s.entries.push_back(key << kKeyShift | guest << kGuestShift | low << 32 | i);
          }
    }
    // By sub-cell, its owners first.
    std::sort(s.entries.begin(), s.entries.end());
    for (size_t begin = 0; begin < s.entries.size();) {
      size_t end = begin + 1;
      while (end < s.entries.size() &&
             s.entries[end] >> kKeyShift == s.entries[begin] >> kKeyShift)
        ++end;
      for (size_t e = begin; e < end && !(s.entries[e] >> kGuestShift & 1); ++e) {
        const uint32_t a = static_cast<uint32_t>(s.entries[e]);
        const uint64_t low_a = s.entries[e] >> 32 & 7;
        size_t n = 0;
        for (size_t f = e + 1; f < end; ++f) {
          const uint32_t b = static_cast<uint32_t>(s.entries[f]);
          passed[n] = b;
          n += ((low_a | (s.entries[f] >> 32 & 7)) == 7) & Passes(members[a], members[b]);
        }
        test(a, n);
      }
      begin = end;
    }
  }
}

std::vector<std::pair<int32_t, int32_t>> SearchPairs(const TriangleMesh& mesh,
                                                     const Participants& p, int threads,
                                                     const CancelToken& cancel,
                                                     ProgressRange progress) {
  std::vector<std::pair<int32_t, int32_t>> pairs;
  if (p.face.empty()) {
    progress.Done();
    return pairs;
  }
  const SortedFaceCells cells(p.box, threads);
  auto triangle = [&](int32_t i) {
    const auto& idx = mesh.faces[p.face[i]];
    return Triangle3d{ToVec3d(mesh.vertices[idx[0]]), ToVec3d(mesh.vertices[idx[1]]),
                      ToVec3d(mesh.vertices[idx[2]])};
  };
  const bool all = p.dirty.empty();
  // A cell's faces, copied side by side before its pairs are walked, in two arrays: what the
  // pair filter reads (`Filtered`: the box and a flags byte, 28 bytes), and what the tests of
  // the pairs that pass it read (`Tested`). The filter then walks a few hundred contiguous
  // bytes a cell, and without a branch per pair: of the ~24 pairs a face meets in its cells,
  // ~6 pass, in no order a predictor could learn.
  // The flags' bits 0-2 are the entry's lowest-cell bits: bit k set when the face's lowest
  // cell (the cell of its box's low corner) has this cell's coordinate k. Both faces of a pair
  // touch this cell, so their lowest cells are at or below it on every axis, and the overlap's
  // lowest cell is this one exactly when every axis has a face at this coordinate:
  // (at_low_a | at_low_b) == 7, so each pair is tested once, in that cell. Bit 3: the face is
  // dirty (every pair with a dirty face counts). A pair passes when its flags or'ed are 15.
  // A face's triangle and plane are made in its member at the first pair that tests it, not
  // once per face into arrays of the participants: such arrays (84 bytes a face, 1.3 GB on
  // the 15M faces of a 10M-point torus) would be the process's peak on smaller clouds, each
  // of their pages a fresh page fault. A face met in two or three cells makes them again
  // there, from the same positions: the same bits.
  struct Tested {
    int32_t position;
    bool made;  // `triangle` and `plane` hold the face's
    Triangle3d triangle;
    FacePlane plane;
  };
  struct Scratch {
    CrowdedScratch crowded;
    std::vector<Filtered> filtered;
    std::vector<Tested> tested;
    std::vector<uint32_t> passed;  // the members that pass the filter with the current one
  };
  // Cells are independent: runs of whole cells go to the workers (several runs per worker, so
  // that a run of crowded cells does not leave the others idle), each run's pairs to a list
  // of its own; the sort at the end makes the result independent of the split.
  const int workers = std::max(threads, 1);
  const int64_t runs = workers == 1 ? 1 : 8 * workers;
  std::vector<size_t> run_start(runs + 1, cells.size());
  run_start[0] = 0;
  for (int64_t r = 1; r < runs; ++r) {
    size_t e = std::max(run_start[r - 1], cells.size() * r / runs);
    while (e > 0 && e < cells.size() && cells.key(e) == cells.key(e - 1)) ++e;
    run_start[r] = e;
  }
  std::vector<std::vector<std::pair<int32_t, int32_t>>> found(runs);
  std::vector<Scratch> scratch(workers);
  constexpr int kCellsPerPoll = 4096;
  TaskCancel stop(cancel, workers, kCellsPerPoll);
  progress.Begin(static_cast<int64_t>(cells.size()));
  RunTasks(workers, runs, [&](int worker, int64_t run) {
    std::vector<Filtered>& filtered = scratch[worker].filtered;
    std::vector<Tested>& tested = scratch[worker].tested;
    std::vector<uint32_t>& passed = scratch[worker].passed;
    std::vector<std::pair<int32_t, int32_t>>& out = found[run];
    int64_t uncounted = 0;  // cell entries walked, not yet added to `progress`
    for (size_t begin = run_start[run]; begin < run_start[run + 1];) {
      if (stop.Poll(worker)) break;
      size_t end = begin + 1;
      while (end < cells.size() && cells.key(end) == cells.key(begin)) ++end;
      uncounted += static_cast<int64_t>(end - begin);
      if (uncounted >= kCellsPerPoll) {
        progress.Add(uncounted);
        uncounted = 0;
      }
      const size_t m = end - begin;
      filtered.resize(m);
      tested.resize(m);
      passed.resize(m);
      for (size_t e = begin; e < end; ++e) {
        const int32_t i = cells.position(e);
        const bool dirty = all || p.dirty[i] != 0;
        filtered[e - begin] = {p.box[i], static_cast<uint8_t>(cells.at_low(e) | (dirty ? 8 : 0))};
        tested[e - begin].position = i;
        tested[e - begin].made = false;
      }
      auto make = [&](Tested& t) {
        if (t.made) return;
        t.triangle = triangle(t.position);
        t.plane = MakeFacePlane(t.triangle);
        t.made = true;
      };
      // Tests member a against the n members listed in `passed`.
      auto test = [&](size_t a, size_t n) {
        if (n == 0) return;
        Tested& ti = tested[a];
        make(ti);
        const int32_t fi = p.face[ti.position];
        for (size_t k = 0; k < n; ++k) {
          Tested& tj = tested[passed[k]];
          make(tj);
          const int32_t fj = p.face[tj.position];
          if (MeshTrianglesIntersect(mesh.faces[fi], ti.triangle, ti.plane, mesh.faces[fj],
                                     tj.triangle, tj.plane))
            out.emplace_back(std::min(fi, fj), std::max(fi, fj));
        }
      };
      if (m <= kCrowdedCell) {
        for (size_t a = 0; a < m; ++a) {
          const Filtered fa = filtered[a];
          size_t n = 0;
          for (size_t b = a + 1; b < m; ++b) {
            passed[n] = static_cast<uint32_t>(b);
            n += Passes(fa, filtered[b]);
          }
          test(a, n);
        }
      } else {
        WalkCrowdedCell(filtered.data(), m, scratch[worker].crowded, passed.data(), test);
      }
      begin = end;
    }
    progress.Add(uncounted);
  });
  for (const auto& f : found) pairs.insert(pairs.end(), f.begin(), f.end());
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

}  // namespace

std::vector<std::pair<int32_t, int32_t>> FindIntersectingFaces(const TriangleMesh& mesh,
                                                               const CancelToken& cancel,
                                                               int threads,
                                                               ProgressRange progress) {
  const int64_t nv = static_cast<int64_t>(mesh.vertices.size());
  const int32_t nf = static_cast<int32_t>(mesh.faces.size());
  // Blocks of faces count their valid faces, then write them from their own offsets: index
  // order, as one loop.
  constexpr int32_t kFacesPerBlock = 16384;
  const int64_t blocks = (int64_t{nf} + kFacesPerBlock - 1) / kFacesPerBlock;
  auto block_end = [&](int64_t block) {
    return static_cast<int32_t>(std::min<int64_t>(nf, (block + 1) * kFacesPerBlock));
  };
  std::vector<size_t> offset(blocks + 1, 0);
  RunTasks(threads, blocks, [&](int, int64_t block) {
    size_t valid = 0;
    for (int32_t f = static_cast<int32_t>(block * kFacesPerBlock); f < block_end(block); ++f)
      valid += ValidFace(mesh.faces[f], nv);
    offset[block + 1] = valid;
  });
  for (int64_t block = 0; block < blocks; ++block) offset[block + 1] += offset[block];
  Participants p;
  p.face.resize(offset.back());
  p.box.resize(offset.back());
  RunTasks(threads, blocks, [&](int, int64_t block) {
    size_t at = offset[block];
    for (int32_t f = static_cast<int32_t>(block * kFacesPerBlock); f < block_end(block); ++f) {
      if (!ValidFace(mesh.faces[f], nv)) continue;
      p.face[at] = f;
      p.box[at++] = BoxOfFace(mesh, f);
    }
  });
  return SearchPairs(mesh, p, threads, cancel, progress);
}

void FaceBlockBoxes::Update(const TriangleMesh& mesh, const std::vector<char>& dirty,
                            int threads) {
  const int32_t nf = static_cast<int32_t>(mesh.faces.size());
  const int32_t blocks = (nf + kFaces - 1) / kFaces;
  const bool all = faces_ != mesh.faces.size() || boxes_.size() != static_cast<size_t>(blocks);
  if (all) {
    faces_ = mesh.faces.size();
    boxes_.resize(blocks);
  }
  // Runs of blocks a task: every face is read (its flag, or its box when all are made), a
  // pass over the whole mesh (15M faces at 10M points) on the fit's last step.
  constexpr int32_t kBlocksPerTask = 1024;
  RunTasks(threads, (blocks + kBlocksPerTask - 1) / kBlocksPerTask, [&](int, int64_t task) {
    const int32_t first = static_cast<int32_t>(task) * kBlocksPerTask;
    const int32_t last = std::min(blocks, first + kBlocksPerTask);
    for (int32_t b = first; b < last; ++b) {
      if (all) {
        Remake(mesh, b);
        continue;
      }
      if (AnyFlagged(dirty.data(), int64_t{b} * kFaces, std::min(nf, (b + 1) * kFaces)))
        Remake(mesh, b);
    }
  });
}

void FaceBlockBoxes::Remake(const TriangleMesh& mesh, int32_t block) {
  const int64_t nv = static_cast<int64_t>(mesh.vertices.size());
  const int32_t nf = static_cast<int32_t>(mesh.faces.size());
  Box& box = boxes_[block];
  // Empty until a face is seen: lo above hi on every axis, so it overlaps nothing.
  box.lo.fill(std::numeric_limits<float>::infinity());
  box.hi.fill(-std::numeric_limits<float>::infinity());
  const int32_t end = std::min(nf, (block + 1) * kFaces);
  for (int32_t f = block * kFaces; f < end; ++f) {
    if (!ValidFace(mesh.faces[f], nv)) continue;
    const Box b = BoxOfFace(mesh, f);
    for (int k = 0; k < 3; ++k) {
      box.lo[k] = std::min(box.lo[k], b.lo[k]);
      box.hi[k] = std::max(box.hi[k], b.hi[k]);
    }
  }
}

std::vector<std::pair<int32_t, int32_t>> FindIntersectingFacesNear(const TriangleMesh& mesh,
                                                                   const std::vector<char>& dirty,
                                                                   int threads,
                                                                   FaceBlockBoxes* blocks) {
  const int64_t nv = static_cast<int64_t>(mesh.vertices.size());
  const int32_t nf = static_cast<int32_t>(mesh.faces.size());
  if (blocks != nullptr) blocks->Update(mesh, dirty, threads);
  // Boxes of the dirty faces, and the coarse cells they touch (a face overlapping a dirty box
  // touches one of that box's cells, whatever the cells' size).
  const std::vector<int32_t> flagged = FlaggedIndices(dirty.data(), nf);
  const int64_t n_dirty = static_cast<int64_t>(flagged.size());
  // Mostly dirty: selecting the neighbourhood would cost more than searching everything.
  if (4 * n_dirty > nf) {
    std::vector<std::pair<int32_t, int32_t>> pairs =
        FindIntersectingFaces(mesh, CancelToken::Never(), threads);
    std::erase_if(pairs, [&](const auto& p) { return !dirty[p.first] && !dirty[p.second]; });
    return pairs;
  }
  Participants p;
  p.face.reserve(n_dirty);
  p.box.reserve(n_dirty);
  std::vector<float> extents;
  extents.reserve(n_dirty);
  for (const int32_t f : flagged) {
    if (!ValidFace(mesh.faces[f], nv)) continue;
    p.face.push_back(f);
    p.box.push_back(BoxOfFace(mesh, f));
    const Box& b = p.box.back();
    extents.push_back(Extent(b));
  }
  if (p.face.empty()) return {};
  const size_t middle = extents.size() / 2;
  std::nth_element(extents.begin(), extents.begin() + middle, extents.end());
  p.dirty.assign(p.face.size(), 1);
  // Mark them in a dense bitmap over the dirty faces' bounding box: the clean faces are then
  // tested with a few bit reads each. Its cells start at twice the median dirty extent and
  // double until the bitmap stays small and the boxes mark at most kMarksPerFace cells each
  // on average. Cells sized by the largest dirty face instead (a cap's face stretched over a
  // hole, tens of voxels) took in every face within tens of voxels of any dirty one: 188,170
  // faces around 4,355 dirty ones in a back-off round of the caps.
  Box region = p.box[0];
  for (const Box& b : p.box)
    for (int k = 0; k < 3; ++k) {
      region.lo[k] = std::min(region.lo[k], b.lo[k]);
      region.hi[k] = std::max(region.hi[k], b.hi[k]);
    }
  constexpr int64_t kMarksPerFace = 64;
  const int64_t mark_budget = kMarksPerFace * static_cast<int64_t>(p.box.size());
  double coarse = std::max(2.0 * extents[middle], 1e-30);
  std::array<int64_t, 3> dims;
  auto cell = [&](float v, int k) {
    return Floor((v - region.lo[k]) / coarse);
  };
  for (;; coarse *= 2) {
    for (int k = 0; k < 3; ++k)
      dims[k] = static_cast<int64_t>(std::floor((region.hi[k] - region.lo[k]) / coarse)) + 1;
    if (dims[0] * dims[1] * dims[2] > (int64_t{1} << 24)) continue;
    int64_t marks = 0;
    for (const Box& b : p.box) {
      int64_t span = 1;
      for (int k = 0; k < 3; ++k) span *= cell(b.hi[k], k) - cell(b.lo[k], k) + 1;
      marks += span;
      if (marks > mark_budget) break;
    }
    if (marks <= mark_budget) break;
  }
  std::vector<bool> marked(static_cast<size_t>(dims[0] * dims[1] * dims[2]), false);
  for (const Box& b : p.box)
    for (int64_t z = cell(b.lo[2], 2); z <= cell(b.hi[2], 2); ++z)
      for (int64_t y = cell(b.lo[1], 1); y <= cell(b.hi[1], 1); ++y)
        for (int64_t x = cell(b.lo[0], 0); x <= cell(b.hi[0], 0); ++x)
          marked[x + dims[0] * (y + dims[1] * z)] = true;
  // Whether a box touches a marked cell; `limit` > 0: true without looking once the box spans
  // more cells than that.
  auto touches_marked = [&](const Box& b, int64_t limit) {
    if (!BoxesOverlap(b, region)) return false;
    std::array<int64_t, 3> lo, hi;
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::max<int64_t>(cell(b.lo[k], k), 0);
      hi[k] = std::min<int64_t>(cell(b.hi[k], k), dims[k] - 1);
    }
    if (limit > 0 && (hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1) > limit)
      return true;
    for (int64_t z = lo[2]; z <= hi[2]; ++z)
      for (int64_t y = lo[1]; y <= hi[1]; ++y)
        for (int64_t x = lo[0]; x <= hi[0]; ++x)
          if (marked[x + dims[0] * (y + dims[1] * z)]) return true;
    return false;
  };
  // The clean faces whose box touches a marked cell, in index order; with `blocks`, only those
  // of runs whose box does (a run spanning many cells is read face by face).
  constexpr int64_t kBlockCellLimit = 512;
  const int32_t run = blocks != nullptr ? FaceBlockBoxes::kFaces : nf;
  for (int32_t begin = 0; begin < nf; begin += run) {
    if (blocks != nullptr && !touches_marked(blocks->box(begin / run), kBlockCellLimit)) continue;
    const int32_t end = std::min(nf, begin + run);
    for (int32_t f = begin; f < end; ++f) {
      if (dirty[f] || !ValidFace(mesh.faces[f], nv)) continue;
      const Box b = BoxOfFace(mesh, f);
      if (!touches_marked(b, 0)) continue;
      p.face.push_back(f);
      p.box.push_back(b);
      p.dirty.push_back(0);
    }
  }
  return SearchPairs(mesh, p, threads, CancelToken::Never(), ProgressRange());
}

}  // namespace membrane
