// An owned PETSc vector (destroyed with its owner) and scoped read and write
// views of its owned entries, so that code outside solver/ holds no raw Vec
// lifetimes or arrays.
#pragma once

#include "../common/petsc_check.h"
#include <petscvec.h>
#include <span>
#include <utility>

namespace pushout::solver
{
class Vector
{
public:
  /// Takes ownership of `v` (which may be null).
  explicit Vector(Vec v = nullptr) : _v(v) {}
  ~Vector()
  {
    if (_v)
      petsc::check_nothrow(VecDestroy(&_v), "VecDestroy");
  }
  Vector(Vector&& other) noexcept : _v(std::exchange(other._v, nullptr)) {}
  Vector& operator=(Vector&& other) noexcept
  {
    std::swap(_v, other._v);
    return *this;
  }
  Vector(const Vector&) = delete;
  Vector& operator=(const Vector&) = delete;

  /// A new vector of the same layout (entries unset).
  Vector duplicate() const
  {
    Vec v;
    petsc::check(VecDuplicate(_v, &v), "VecDuplicate");
    return Vector(v);
  }
  /// Copies the entries of `from` (same layout) into this vector.
  void copy_from(const Vector& from) { petsc::check(VecCopy(from._v, _v), "VecCopy"); }
  void set(double value) { petsc::check(VecSet(_v, value), "VecSet"); }

  Vec get() const { return _v; }
  operator Vec() const { return _v; }

private:
  Vec _v;
};

/// The owned entries of a vector, readable while this object lives.
class ReadView
{
public:
  explicit ReadView(Vec v) : _v(v)
  {
    PetscInt n;
    petsc::check(VecGetLocalSize(_v, &n), "VecGetLocalSize");
    const double* a;
    petsc::check(VecGetArrayRead(_v, &a), "VecGetArrayRead");
    _a = std::span<const double>(a, std::size_t(n));
  }
  ~ReadView()
  {
    const double* a = _a.data();
    petsc::check_nothrow(VecRestoreArrayRead(_v, &a), "VecRestoreArrayRead");
  }
  ReadView(const ReadView&) = delete;
  ReadView& operator=(const ReadView&) = delete;

  std::span<const double> span() const { return _a; }
  const double* data() const { return _a.data(); }

private:
  Vec _v;
  std::span<const double> _a;
};

/// The owned entries of a vector, writable while this object lives.
class WriteView
{
public:
  explicit WriteView(Vec v) : _v(v)
  {
    PetscInt n;
    petsc::check(VecGetLocalSize(_v, &n), "VecGetLocalSize");
    double* a;
    petsc::check(VecGetArray(_v, &a), "VecGetArray");
    _a = std::span<double>(a, std::size_t(n));
  }
  ~WriteView()
  {
    double* a = _a.data();
    petsc::check_nothrow(VecRestoreArray(_v, &a), "VecRestoreArray");
  }
  WriteView(const WriteView&) = delete;
  WriteView& operator=(const WriteView&) = delete;

  std::span<double> span() const { return _a; }
  double* data() const { return _a.data(); }

private:
  Vec _v;
  std::span<double> _a;
};
} // namespace pushout::solver
