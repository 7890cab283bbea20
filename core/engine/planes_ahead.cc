#include "core/engine/planes_ahead.h"

#include <system_error>

namespace membrane {

PlanesAhead::PlanesAhead(WorkPlanes& planes, int count, const CancelToken& cancel) {
  try {
    thread_ = std::thread([&planes, count, &cancel] { planes.Ensure(count, cancel); });
  } catch (const std::system_error&) {
    // No thread: Ensure runs when the planes are first needed.
  }
}

void PlanesAhead::Wait() {
  if (thread_.joinable()) thread_.join();
}

}  // namespace membrane
