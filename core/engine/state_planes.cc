#include "core/engine/state_planes.h"

#include <algorithm>
#include <cstring>
#include <vector>

#include "core/base/parallel_tasks.h"
#include "core/engine/word_blocks.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace membrane {
namespace {

constexpr uint64_t kHigh = 0x8080808080808080ull;  // the top bit of every byte
constexpr uint64_t kLow7 = 0x7f7f7f7f7f7f7f7full;
constexpr uint64_t kOnes = 0x0101010101010101ull;
constexpr uint64_t kHardness = kOnes * kHardnessMask;

static_assert(kOutsideBit == 0x80 && kHardnessMask == 0x06 && kBoundarySoft == 0x01,
              "the byte tricks below rely on the state layout of voxel_state.h");

// The top bit of every byte of `x` that is zero (exact: no carry crosses a byte).
constexpr uint64_t ZeroBytes(uint64_t x) { return ~(((x & kLow7) + kLow7) | x) & kHigh; }

// The top bit of every byte whose state satisfies P.
template <StatePredicate P>
constexpr uint64_t Matches(uint64_t x) {
  const uint64_t outside = x & kHigh;
  if constexpr (P == StatePredicate::kOutside) {
    return outside;
  } else if constexpr (P == StatePredicate::kBoundarySoft) {
    return ZeroBytes(x ^ (kOnes * kBoundarySoft));
  } else if constexpr (P == StatePredicate::kFree) {
    // Hardness bits are 0 (soft) or the voxel is outside; (x & 6) + 0x7e reaches the top bit
    // exactly when some hardness bit is set.
    const uint64_t hard_or_frozen = ((x & kHardness) + (kOnes * 0x7e)) & kHigh;
    return (outside | ~hard_or_frozen) & kHigh;
  } else {
    const uint64_t hard_bits = ZeroBytes((x & kHardness) ^ (kOnes * 0x02));
    return hard_bits & ~outside;
  }
}

// The top bit of every byte that is a boundary state: outside bit clear, boundary bit set.
constexpr uint64_t BoundaryBytes(uint64_t x) {
  return ZeroBytes((x & (kOnes * (kOutsideBit | kBoundaryBit))) ^ (kOnes * kBoundaryBit));
}

// Number of bytes with the top bit set, for a word with no other bits (no popcnt instruction
// on the baseline x86-64 target: std::popcount is a library call there).
constexpr int CountTopBits(uint64_t m) { return static_cast<int>(((m >> 7) * kOnes) >> 56); }

#if !defined(__SSE2__)
// Packs the top bits of the eight bytes into one byte, byte k giving bit k.
constexpr uint64_t PackTopBits(uint64_t m) { return ((m >> 7) * 0x0102040810204080ull) >> 56; }
#endif

uint64_t Load8(const VoxelState* p) {
  uint64_t x;
  std::memcpy(&x, p, sizeof x);
  return x;
}

#if defined(__SSE2__)
// Sixteen voxels at once: the predicate as a byte mask, its top bits gathered by movemask.
template <StatePredicate P>
uint64_t Matches16(const VoxelState* p) {
  const __m128i x = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
  __m128i m;
  if constexpr (P == StatePredicate::kOutside) {
    m = x;
  } else if constexpr (P == StatePredicate::kBoundarySoft) {
    m = _mm_cmpeq_epi8(x, _mm_set1_epi8(kBoundarySoft));
  } else if constexpr (P == StatePredicate::kFree) {
    m = _mm_or_si128(x, _mm_cmpeq_epi8(_mm_and_si128(x, _mm_set1_epi8(kHardnessMask)),
                                       _mm_setzero_si128()));
  } else {
    const __m128i outside_and_hardness = _mm_set1_epi8(static_cast<char>(kOutsideBit | kHardnessMask));
    m = _mm_cmpeq_epi8(_mm_and_si128(x, outside_and_hardness), _mm_set1_epi8(kInsideHard));
  }
  return static_cast<uint64_t>(static_cast<uint32_t>(_mm_movemask_epi8(m)));
}
#endif

template <StatePredicate P>
void Fill(const VoxelState* s, int64_t nv, uint64_t* words, int64_t word_begin, int64_t word_end) {
  // Words covering whole state bytes in blocks; the last partial word bit by bit.
  const int64_t full_words = std::min(word_end, nv / 64);
  int64_t w = word_begin;
  for (; w < full_words; ++w) {
    const VoxelState* p = s + w * 64;
#if defined(__SSE2__)
    words[w] = Matches16<P>(p) | Matches16<P>(p + 16) << 16 | Matches16<P>(p + 32) << 32 |
               Matches16<P>(p + 48) << 48;
#else
    uint64_t bits = 0;
    for (int k = 0; k < 8; ++k) bits |= PackTopBits(Matches<P>(Load8(p + 8 * k))) << (8 * k);
    words[w] = bits;
#endif
  }
  for (; w < word_end; ++w) {
    uint64_t bits = 0;
    for (int64_t i = w * 64; i < std::min(nv, w * 64 + 64); ++i) {
      // The word trick on one byte: only byte 0's verdict is kept.
      bits |= ((Matches<P>(s[i]) >> 7) & 1) << (i - w * 64);
    }
    words[w] = bits;
  }
}

}  // namespace

void FillStatePlane(absl::Span<const VoxelState> states, StatePredicate predicate,
                    FlatBitset& plane, int64_t word_begin, int64_t word_end) {
  const VoxelState* s = states.data();
  const int64_t nv = static_cast<int64_t>(states.size());
  uint64_t* w = plane.words();
  switch (predicate) {
    case StatePredicate::kOutside:
      Fill<StatePredicate::kOutside>(s, nv, w, word_begin, word_end);
      break;
    case StatePredicate::kBoundarySoft:
      Fill<StatePredicate::kBoundarySoft>(s, nv, w, word_begin, word_end);
      break;
    case StatePredicate::kFree:
      Fill<StatePredicate::kFree>(s, nv, w, word_begin, word_end);
      break;
    case StatePredicate::kHard:
      Fill<StatePredicate::kHard>(s, nv, w, word_begin, word_end);
      break;
  }
}

void FillStatePlane(absl::Span<const VoxelState> states, StatePredicate predicate,
                    FlatBitset& plane) {
  ForWordBlocks(plane.threads(), static_cast<int64_t>(plane.word_count()),
                [&](int64_t, int64_t begin, int64_t end) {
                  FillStatePlane(states, predicate, plane, begin, end);
                });
}

void FillFreeAndOutsidePlanes(absl::Span<const VoxelState> states, FlatBitset& free_cells,
                              FlatBitset& outside) {
  const VoxelState* s = states.data();
  const int64_t nv = static_cast<int64_t>(states.size());
  uint64_t* free_words = free_cells.words();
  uint64_t* out_words = outside.words();
  ForWordBlocks(free_cells.threads(), static_cast<int64_t>(free_cells.word_count()),
                [&](int64_t, int64_t begin, int64_t end) {
                  const int64_t full_words = std::min(end, nv / 64);
                  int64_t w = begin;
                  for (; w < full_words; ++w) {
                    const VoxelState* p = s + w * 64;
#if defined(__SSE2__)
                    uint64_t out = 0, soft = 0;
                    for (int k = 0; k < 4; ++k) {
                      out |= Matches16<StatePredicate::kOutside>(p + 16 * k) << (16 * k);
                      soft |= Matches16<StatePredicate::kBoundarySoft>(p + 16 * k) << (16 * k);
                    }
#else
                    uint64_t out = 0, soft = 0;
                    for (int k = 0; k < 8; ++k) {
                      const uint64_t x = Load8(p + 8 * k);
                      out |= PackTopBits(Matches<StatePredicate::kOutside>(x)) << (8 * k);
                      soft |= PackTopBits(Matches<StatePredicate::kBoundarySoft>(x)) << (8 * k);
                    }
#endif
                    out_words[w] = out;
                    free_words[w] = out | soft;
                  }
                  // The last partial word as FillStatePlane fills it.
                  if (w < end) {
                    Fill<StatePredicate::kOutside>(s, nv, out_words, w, end);
                    Fill<StatePredicate::kBoundarySoft>(s, nv, free_words, w, end);
                    for (int64_t v = w; v < end; ++v) free_words[v] |= out_words[v];
                  }
                });
}

namespace {

StateCounts CountStateRange(const VoxelState* s, int64_t nv) {
  StateCounts c;
  int64_t i = 0;
#if defined(__SSE2__)
  // Byte counters (a match is -1, subtracted), summed into 64-bit lanes before they overflow.
  const __m128i zero = _mm_setzero_si128();
  const __m128i position_bits = _mm_set1_epi8(static_cast<char>(kOutsideBit | kBoundaryBit));
  const __m128i boundary_bit = _mm_set1_epi8(kBoundaryBit);
  while (i + 16 <= nv) {
    __m128i outside = zero, boundary = zero, boundary_soft = zero;
    for (int block = 0; block < 255 && i + 16 <= nv; ++block, i += 16) {
      const __m128i x = _mm_loadu_si128(reinterpret_cast<const __m128i*>(s + i));
      outside = _mm_sub_epi8(outside, _mm_cmplt_epi8(x, zero));
      boundary = _mm_sub_epi8(boundary,
                              _mm_cmpeq_epi8(_mm_and_si128(x, position_bits), boundary_bit));
      boundary_soft = _mm_sub_epi8(boundary_soft, _mm_cmpeq_epi8(x, boundary_bit));
    }
    auto sum = [&](__m128i bytes) {
      const __m128i lanes = _mm_sad_epu8(bytes, zero);
      return static_cast<int64_t>(_mm_cvtsi128_si64(lanes)) +
             static_cast<int64_t>(_mm_cvtsi128_si64(_mm_unpackhi_epi64(lanes, lanes)));
    };
    c.outside += sum(outside);
    c.boundary += sum(boundary);
    c.boundary_soft += sum(boundary_soft);
  }
#endif
  for (; i + 8 <= nv; i += 8) {
    const uint64_t x = Load8(s + i);
    c.outside += CountTopBits(Matches<StatePredicate::kOutside>(x));
    c.boundary += CountTopBits(BoundaryBytes(x));
    c.boundary_soft += CountTopBits(Matches<StatePredicate::kBoundarySoft>(x));
  }
  for (; i < nv; ++i) {
    c.outside += IsOutside(s[i]);
    c.boundary += IsBoundary(s[i]);
    c.boundary_soft += IsBoundarySoft(s[i]);
  }
  return c;
}

}  // namespace

StateCounts CountStates(absl::Span<const VoxelState> states, int threads) {
  // Blocks of the voxels of kWordBlock words of a plane.
  constexpr int64_t kBlock = kWordBlock * 64;
  const int64_t nv = static_cast<int64_t>(states.size());
  const int64_t blocks = WordBlockCount(threads, (nv + 63) / 64);
  if (blocks == 1) return CountStateRange(states.data(), nv);
  std::vector<StateCounts> parts(static_cast<size_t>(blocks));
  RunTasks(threads, blocks, [&](int, int64_t b) {
    const int64_t begin = b * kBlock;
    parts[static_cast<size_t>(b)] = CountStateRange(states.data() + begin, std::min(nv, begin + kBlock) - begin);
  });
  StateCounts c;
  for (const StateCounts& p : parts) {
    c.outside += p.outside;
    c.boundary += p.boundary;
    c.boundary_soft += p.boundary_soft;
  }
  return c;
}

int FirstBoundaryOfEight(const VoxelState* states) {
  const uint64_t b = BoundaryBytes(Load8(states));
  return b == 0 ? 8 : __builtin_ctzll(b) / 8;  // little-endian load: byte k is bits 8k..
}

int64_t FirstHardOf(const VoxelState* states, int64_t count) {
  int64_t i = 0;
#if defined(__SSE2__)
  for (; i + 64 <= count; i += 64) {
    const VoxelState* p = states + i;
    if ((Matches16<StatePredicate::kHard>(p) | Matches16<StatePredicate::kHard>(p + 16) |
         Matches16<StatePredicate::kHard>(p + 32) | Matches16<StatePredicate::kHard>(p + 48)) != 0)
      break;
  }
#endif
  for (; i + 8 <= count; i += 8) {
    const uint64_t m = Matches<StatePredicate::kHard>(Load8(states + i));
    if (m != 0) return i + __builtin_ctzll(m) / 8;
  }
  for (; i < count; ++i)
    if (IsHard(states[i])) return i;
  return count;
}

uint64_t OutsideBesideSolidOfEight(const VoxelState* states, const int64_t strides[3]) {
  const uint64_t around = Load8(states - strides[0]) & Load8(states + strides[0]) &
                          Load8(states - strides[1]) & Load8(states + strides[1]) &
                          Load8(states - strides[2]) & Load8(states + strides[2]);
  return Load8(states) & ~around & kHigh;
}

}  // namespace membrane
