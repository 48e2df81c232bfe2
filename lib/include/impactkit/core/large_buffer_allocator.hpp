#pragma once
/// \file large_buffer_allocator.hpp
/// A std::allocator for buffers that grow to many megabytes (the records of
/// a long run): from kThreshold bytes on, the buffer is aligned to 2 MiB and
/// offered to the kernel as transparent huge pages, so that filling it
/// faults once per 2 MiB instead of once per 4 KiB page. A run of 10^5
/// forcing periods recording its impacts and stroboscopic points took some
/// 10,000 page faults, a tenth of its CPU time in the kernel
/// (docs/performance.md). Smaller buffers, the many short records of a
/// sweep, are allocated as usual. Neither the standard library nor the
/// stack chosen for impactkit offers this, hence the few lines below; where
/// the system has no transparent huge pages the advice is a no-op.

#include <cstddef>
#include <cstdlib>
#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace impactkit {

template <class T>
class LargeBufferAllocator {
 public:
  using value_type = T;
  static constexpr std::size_t kHugePage = std::size_t{2} << 20;
  /// Buffers from one huge page on are huge-page aligned (at most one
  /// partly used page each); below it the usual allocation wastes nothing.
  static constexpr std::size_t kThreshold = kHugePage;

  LargeBufferAllocator() = default;
  template <class U>
  LargeBufferAllocator(const LargeBufferAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    const std::size_t bytes = n * sizeof(T);
    if (bytes < kThreshold) return static_cast<T*>(::operator new(bytes));
    const std::size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
    void* buffer = std::aligned_alloc(kHugePage, rounded);
    if (buffer == nullptr) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    madvise(buffer, rounded, MADV_HUGEPAGE);  // advice only: failure changes nothing
#endif
    return static_cast<T*>(buffer);
  }
  void deallocate(T* buffer, std::size_t n) noexcept {
    if (n * sizeof(T) < kThreshold) {
      ::operator delete(buffer);
    } else {
      std::free(buffer);
    }
  }
  template <class U>
  bool operator==(const LargeBufferAllocator<U>&) const noexcept {
    return true;
  }
};

}  // namespace impactkit
