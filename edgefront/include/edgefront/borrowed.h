#pragma once
/// \file borrowed.h
/// `Borrowed<T>`: a pointer, held in an options struct or a scene, to an object the *caller* owns
/// and keeps alive for as long as the holder is used (a reference point set, a face grid, a mesh
/// to draw). The type says who owns it: not the holder, which never deletes it. Null when unset.
///
///     twist::ReferenceNormals ref(cloud);     // the caller's
///     twist::RepairOptions o;
///     o.detect.reference = &ref;              // borrowed: `ref` must outlive every use of `o`
///
/// It converts to and from `T*`, so it reads like the raw pointer it replaces.

#include <cstddef>

namespace edgefront {

template <class T>
class Borrowed {
 public:
  constexpr Borrowed() = default;
  constexpr Borrowed(std::nullptr_t) {}
  constexpr Borrowed(T* pointer) : pointer_(pointer) {}
  /// The pointer (null when unset); also what `if (b)`, `*b` and `b->` use.
  constexpr operator T*() const { return pointer_; }
  constexpr T* operator->() const { return pointer_; }
  constexpr T* get() const { return pointer_; }

 private:
  T* pointer_ = nullptr;
};

}  // namespace edgefront
