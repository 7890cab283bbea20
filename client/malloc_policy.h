// How the `membrane` process asks glibc's malloc to manage its memory, set once at the start
// of main, before any thread runs.
#ifndef MEMBRANE_CLIENT_MALLOC_POLICY_H_
#define MEMBRANE_CLIENT_MALLOC_POLICY_H_

namespace membrane::client {

// One arena for the process, no block mapped on its own, no trim: every freed block stays in
// the one heap for the next allocation, and the process gives its memory back at exit.
// Must be called before the process starts a thread or makes its first large allocation.
// membraned sets its own (server/memory_release.h; docs/memory-decisions.md, "The client
// keeps what it frees").
void UseClientMallocPolicy();

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_MALLOC_POLICY_H_
