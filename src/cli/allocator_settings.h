// The C allocator's settings for this program: the library leaves process-wide settings to its callers.
#pragma once

namespace dbrg::cli {

// Large freed blocks are kept for reuse rather than handed back to the system at once (glibc only; a
// MALLOC_MMAP_THRESHOLD_ or MALLOC_TRIM_THRESHOLD_ in the environment wins). --max-memory overrides the
// mmap threshold afterwards.
void keep_freed_blocks();

} // namespace dbrg::cli
