// Word passes over a bit-plane split into fixed blocks of words and shared by a few threads
// (RunTasks). A block's words are a pure function of what the pass reads, and the blocks are
// fixed by the plane's size, never by the thread count, so the bits are the same for any count.
#ifndef MEMBRANE_CORE_ENGINE_WORD_BLOCKS_H_
#define MEMBRANE_CORE_ENGINE_WORD_BLOCKS_H_

#include <algorithm>
#include <cstdint>

#include "core/base/parallel_tasks.h"

namespace membrane {

// Words per block: 256 KB, a few hundred microseconds of a pass, against the tens of
// microseconds a thread takes to start.
inline constexpr int64_t kWordBlock = int64_t{1} << 15;

// Number of blocks ForWordBlocks cuts `words` into: 1 (the whole range on the calling thread)
// when threads <= 1 or the range is under two blocks.
inline int64_t WordBlockCount(int threads, int64_t words) {
  if (threads <= 1 || words < 2 * kWordBlock) return 1;
  return (words + kWordBlock - 1) / kWordBlock;
}

// Calls f(block, begin, end) once for every block of WordBlockCount(threads, words), the
// blocks' word ranges [begin, end) covering [0, words) in order, on up to `threads` threads.
// f must write only the words of its range and per-block outputs indexed by `block`.
template <typename F>
void ForWordBlocks(int threads, int64_t words, F&& f) {
  const int64_t blocks = WordBlockCount(threads, words);
  if (blocks == 1) {
    f(int64_t{0}, int64_t{0}, words);
    return;
  }
  RunTasks(threads, blocks, [&](int, int64_t b) {
    f(b, b * kWordBlock, std::min(words, (b + 1) * kWordBlock));
  });
}

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_WORD_BLOCKS_H_
