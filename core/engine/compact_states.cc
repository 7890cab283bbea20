#include "core/engine/compact_states.h"

#include <algorithm>
#include <cstring>
#include <vector>

#include "core/base/parallel_tasks.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace membrane {
namespace {

// Chunks per cancel poll: 256 chunks of 64 KB are 16 MB, a few milliseconds.
constexpr int64_t kChunksPerPoll = 256;

// The end of the run of `s[begin]` in s[begin, end): sixteen bytes per step where SSE2 is
// there (the runs of a shrunk grid are thousands of voxels long).
int64_t RunEnd(const VoxelState* s, int64_t begin, int64_t end) {
  const VoxelState v = s[begin];
  int64_t i = begin + 1;
#if defined(__SSE2__)
  const __m128i value = _mm_set1_epi8(static_cast<char>(v));
  while (i + 16 <= end) {
    const __m128i x = _mm_loadu_si128(reinterpret_cast<const __m128i*>(s + i));
    const int equal = _mm_movemask_epi8(_mm_cmpeq_epi8(x, value));
    if (equal != 0xffff) return i + __builtin_ctz(~equal & 0xffff);
    i += 16;
  }
#endif
  while (i < end && s[i] == v) ++i;
  return i;
}

// Sets bits [begin, end) of `words`.
void SetBits(uint64_t* words, int64_t begin, int64_t end) {
  while (begin < end) {
    const int64_t w = begin >> 6;
    const int lo = static_cast<int>(begin & 63);
    const int64_t word_end = std::min(end, (w + 1) << 6);
    const int hi = static_cast<int>(word_end - (w << 6));  // 1 .. 64
    const uint64_t upper = hi == 64 ? ~uint64_t{0} : (uint64_t{1} << hi) - 1;
    words[w] |= upper & (~uint64_t{0} << lo);
    begin = word_end;
  }
}

}  // namespace

void CompactStates::EncodeChunk(const VoxelState* s, int64_t count) {
  Chunk chunk;
  chunk.begin = static_cast<int64_t>(runs_.size());
  // Runs take 4 bytes each: past count / 4 runs the bytes themselves are smaller.
  const size_t max_runs = static_cast<size_t>(count / 4);
  for (int64_t i = 0; i < count;) {
    const int64_t end = RunEnd(s, i, count);
    runs_.push_back(MakeRun(s[i], end - i));
    i = end;
    if (runs_.size() - static_cast<size_t>(chunk.begin) > max_runs) {
      runs_.resize(static_cast<size_t>(chunk.begin));
      chunk.raw = true;
      chunk.begin = static_cast<int64_t>(raw_.size());
      chunk.count = static_cast<int32_t>(count);
      raw_.insert(raw_.end(), s, s + count);
      chunks_.push_back(chunk);
      return;
    }
  }
  chunk.count = static_cast<int32_t>(static_cast<int64_t>(runs_.size()) - chunk.begin);
  chunks_.push_back(chunk);
}

bool CompactStates::EncodeChunks(absl::Span<const VoxelState> states, int64_t first,
                                 int64_t end, const CancelToken& cancel) {
  const int64_t size = static_cast<int64_t>(states.size());
  for (int64_t c = first; c < end; ++c) {
    if ((c - first) % kChunksPerPoll == 0 && cancel.cancelled()) return false;
    const int64_t begin = c * kChunk;
    EncodeChunk(states.data() + begin, std::min(kChunk, size - begin));
  }
  return true;
}

bool CompactStates::Encode(absl::Span<const VoxelState> states, const CancelToken& cancel,
                           int threads) {
  size_ = static_cast<int64_t>(states.size());
  chunks_.clear();
  runs_.clear();
  raw_.clear();
  const int64_t chunks = (size_ + kChunk - 1) / kChunk;
  // A few ranges a thread, so that a range of long runs and one of bytes even out.
  const int64_t parts = threads <= 1 ? 1 : std::min<int64_t>(chunks, 4 * int64_t{threads});
  if (parts <= 1) return EncodeChunks(states, 0, chunks, cancel);
  std::vector<CompactStates> encoded(static_cast<size_t>(parts));
  std::vector<char> done(static_cast<size_t>(parts), 0);
  RunTasks(threads, parts, [&](int, int64_t part) {
    CompactStates& e = encoded[static_cast<size_t>(part)];
    e.size_ = size_;
    done[static_cast<size_t>(part)] =
        e.EncodeChunks(states, chunks * part / parts, chunks * (part + 1) / parts, cancel);
  });
  for (CompactStates& e : encoded) {
    if (!done[static_cast<size_t>(&e - encoded.data())]) return false;
    for (Chunk chunk : e.chunks_) {
      chunk.begin += static_cast<int64_t>(chunk.raw ? raw_.size() : runs_.size());
      chunks_.push_back(chunk);
    }
    // The joined chunks' begins were taken before their part's runs and bytes go in.
    runs_.insert(runs_.end(), e.runs_.begin(), e.runs_.end());
    raw_.insert(raw_.end(), e.raw_.begin(), e.raw_.end());
    e = CompactStates();
  }
  return true;
}

bool CompactStates::Decode(absl::Span<VoxelState> states, const CancelToken& cancel,
                           int threads) const {
  VoxelState* to = states.data();
  const int64_t chunks = static_cast<int64_t>(chunks_.size());
  const int64_t parts = threads <= 1 ? 1 : std::min<int64_t>(chunks, 4 * int64_t{threads});
  std::vector<char> done(static_cast<size_t>(std::max<int64_t>(parts, 1)), 1);
  RunTasks(std::max(threads, 1), parts, [&](int, int64_t part) {
    for (int64_t c = chunks * part / parts; c < chunks * (part + 1) / parts; ++c) {
      if (c % kChunksPerPoll == 0 && cancel.cancelled()) {
        done[static_cast<size_t>(part)] = 0;
        return;
      }
      const Chunk& chunk = chunks_[static_cast<size_t>(c)];
      VoxelState* dst = to + c * kChunk;
      if (chunk.raw) {
        std::memcpy(dst, raw_.data() + chunk.begin, static_cast<size_t>(chunk.count));
        continue;
      }
      for (int32_t r = 0; r < chunk.count; ++r) {
        const uint32_t run = runs_[static_cast<size_t>(chunk.begin + r)];
        std::memset(dst, RunState(run), static_cast<size_t>(RunLength(run)));
        dst += RunLength(run);
      }
    }
  });
  for (char d : done)
    if (!d) return false;
  return true;
}

void CompactStates::OutsidePlane(FlatBitset& plane) const {
  if (plane.bits() == size_) {
    plane.clear_all();
  } else {
    plane = FlatBitset(size_);
  }
  uint64_t* words = plane.words();
  for (size_t c = 0; c < chunks_.size(); ++c) {
    const Chunk& chunk = chunks_[c];
    int64_t pos = static_cast<int64_t>(c) * kChunk;
    if (chunk.raw) {
      const VoxelState* s = raw_.data() + chunk.begin;
      for (int32_t k = 0; k < chunk.count; ++k, ++pos) {
        if (IsOutside(s[k])) plane.set(pos);
      }
      continue;
    }
    for (int32_t r = 0; r < chunk.count; ++r) {
      const uint32_t run = runs_[static_cast<size_t>(chunk.begin + r)];
      if (IsOutside(RunState(run))) SetBits(words, pos, pos + RunLength(run));
      pos += RunLength(run);
    }
  }
}

int64_t CompactStates::encoded_bytes() const {
  return static_cast<int64_t>(chunks_.size() * sizeof(Chunk) + runs_.size() * sizeof(uint32_t) +
                              raw_.size());
}

}  // namespace membrane
