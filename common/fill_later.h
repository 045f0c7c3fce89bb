// fill_later.h: vectors for large arrays that a parallel pass fills.
#pragma once

#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace vgeo {

// Arrays that a parallel pass fills: std::vector with an allocator whose construct() without a value
// leaves a trivially constructible element as it is. A fresh page is zeroed by the kernel when first
// touched, and std::vector<T>(n) touches every page in one memset on the calling thread (about half a
// second a gigabyte: most of the serial time of a 16-thread build); with this one the threads that
// fill the array touch its pages.
template <class T>
struct FillLaterAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = FillLaterAllocator<U>;
  };
  FillLaterAllocator() noexcept = default;
  template <class U>
  FillLaterAllocator(const FillLaterAllocator<U>&) noexcept {}
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};
template <class T>
using FillLaterVector = std::vector<T, FillLaterAllocator<T>>;

}  // namespace vgeo
