// An allocator adaptor whose containers leave their new elements unset.
//
// A container's size constructor and resize(n) value-initialize their new elements through
// the allocator's construct(): for a big array of trivial elements that is one more pass over
// its memory, on one thread, and the pass that takes each page's first write (its page fault).
// UnsetConstruct<A> allocates as A does but default-initializes (nothing, for trivial types),
// so arrays whose every element is written before it is read can be written first on the
// run's threads.
#ifndef MEMBRANE_CORE_ENGINE_UNSET_CONSTRUCT_H_
#define MEMBRANE_CORE_ENGINE_UNSET_CONSTRUCT_H_

#include <memory>
#include <new>
#include <type_traits>
#include <utility>

namespace membrane {

// With `kSkipMemberInitializers`, a new element is not even default-initialized: for
// aggregates whose members have default initializers (which default-initialization would
// write) and that the caller writes whole before reading. Such elements must be
// implicit-lifetime types (aggregates, trivially destructible): the allocation gives them
// their lifetime.
template <typename Base, bool kSkipMemberInitializers = false>
struct UnsetConstruct : Base {
  using Base::Base;
  UnsetConstruct() = default;
  template <typename Other>
  UnsetConstruct(const UnsetConstruct<Other, kSkipMemberInitializers>& other)
      : Base(static_cast<const Other&>(other)) {}
  template <typename U>
  struct rebind {
    using other = UnsetConstruct<typename std::allocator_traits<Base>::template rebind_alloc<U>,
                                 kSkipMemberInitializers>;
  };
  template <typename U>
  void construct(U* p) {
    if constexpr (kSkipMemberInitializers) {
      static_assert(std::is_aggregate_v<U> && std::is_trivially_destructible_v<U>,
                    "only implicit-lifetime aggregates may be left uninitialized");
    } else {
      ::new (static_cast<void*>(p)) U;
    }
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_UNSET_CONSTRUCT_H_
