#include "common/raytrace/ray_task_context.h"

#if defined(__SSE__) || defined(__x86_64__)
#include <xmmintrin.h>
#endif

namespace hybridlab {

RayTaskContext::RayTaskContext() {
#if defined(__SSE__) || defined(__x86_64__)
    // MXCSR bits: FTZ (15) and DAZ (6). TBB copies the calling thread's mode into the context.
    constexpr unsigned kFlushToZero = 1u << 15, kDenormalsAreZero = 1u << 6;
    const unsigned saved = _mm_getcsr();
    _mm_setcsr(saved | kFlushToZero | kDenormalsAreZero);
    capture_fp_settings();
    _mm_setcsr(saved);
#else
    capture_fp_settings();  // no such modes: the caller's, at least the same for every task
#endif
}

}  // namespace hybridlab
