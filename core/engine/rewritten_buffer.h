// A buffer of words that its user rewrites whole before reading, kept from use to use.
#ifndef MEMBRANE_CORE_ENGINE_REWRITTEN_BUFFER_H_
#define MEMBRANE_CORE_ENGINE_REWRITTEN_BUFFER_H_

#include <cstddef>
#include <cstdint>
#include <vector>

namespace membrane {

// Makes `buffer` hold `words` words, whose values are unspecified: the caller writes them
// before it reads any. The buffer keeps its block while `words` fits; otherwise the block is
// freed first and one of `words + spare` words made. Grown by resize, it would copy its old
// words and could double (a work plane's copies and halos held up to twice their words).
inline void ResizeRewritten(std::vector<uint64_t>& buffer, size_t words, size_t spare = 0) {
  if (words > buffer.capacity()) {
    std::vector<uint64_t>().swap(buffer);
    buffer.reserve(words + spare);
  }
  buffer.resize(words);
}

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_REWRITTEN_BUFFER_H_
