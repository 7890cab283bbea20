// A shrink's work planes made on a thread of their own while the shrink's first steps run.
//
// The planes' first writes are their pages' first touches: on a 10M-point torus 8 planes of
// 271 MB, whose page faults took about 2.8 s of both threads at the first fine generation.
// The interior guard and the coarse plates before it leave a core idle much of the time (the
// guard's serial steps, the coarse grid's generations on one thread): made beside them, the
// planes cost that core's idle time instead of the generation's wall time.
#ifndef MEMBRANE_CORE_ENGINE_PLANES_AHEAD_H_
#define MEMBRANE_CORE_ENGINE_PLANES_AHEAD_H_

#include <thread>

#include "core/base/cancel_token.h"
#include "core/engine/work_planes.h"

namespace membrane {

class PlanesAhead {
 public:
  // Starts planes.Ensure(count, cancel) on a new thread. When the system refuses the thread,
  // nothing is started: the planes are made when first ensured, as without this. `planes` and
  // `cancel` must outlive this object, and nothing else may touch `planes` until Wait (or the
  // destructor) returns.
  PlanesAhead(WorkPlanes& planes, int count, const CancelToken& cancel);
  // Waits for the thread.
  ~PlanesAhead() { Wait(); }
  PlanesAhead(const PlanesAhead&) = delete;
  PlanesAhead& operator=(const PlanesAhead&) = delete;

  // Returns once the planes are made (or the thread stopped at `cancel`, leaving some of them
  // to the next Ensure); the planes are then the caller's again.
  void Wait();

 private:
  std::thread thread_;
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_PLANES_AHEAD_H_
