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

/// A non-owning pointer to a `T` the caller owns and keeps alive while the holder is used (see
/// the file comment). Copying it copies the pointer; it never deletes.
/// \tparam T the borrowed object's type (may be const).
template <class T>
class Borrowed {
 public:
  /// Unset (null).
  constexpr Borrowed() = default;
  /// Unset (null): `o.reference = nullptr`.
  constexpr Borrowed(std::nullptr_t) {}
  /// Borrows `*pointer` (null: unset). The caller keeps ownership.
  constexpr Borrowed(T* pointer) : pointer_(pointer) {}
  /// The pointer (null when unset); also what `if (b)`, `*b` and `b->` use.
  constexpr operator T*() const { return pointer_; }
  /// Member access to the borrowed object; the pointer must not be null.
  constexpr T* operator->() const { return pointer_; }
  /// The pointer (null when unset).
  constexpr T* get() const { return pointer_; }

 private:
  T* pointer_ = nullptr;
};

}  // namespace edgefront
