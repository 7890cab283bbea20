// Cooperative cancellation for the mesh steps (relaxation, surface): a callback polled between
// units of work, so that a cancelled job (design/contracts.md, `membrane jobs cancel`) stops
// within milliseconds, as the engine does with its CancelToken.
#ifndef MEMBRANE_CORE_MESH_CANCEL_FN_H_
#define MEMBRANE_CORE_MESH_CANCEL_FN_H_

#include <functional>

namespace membrane {

// Returns true once the caller wants the step to stop. May be empty (never cancelled). Wrap a
// CancelToken as [&token] { return token.cancelled(); }.
using CancelFn = std::function<bool()>;

inline bool Cancelled(const CancelFn& cancel) { return cancel && cancel(); }

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_CANCEL_FN_H_
